#pragma once
// Every struct the C++ side shares with GLSL, with its GLSL twin in gpu/shaders/layout.glsl and
// the binding points both use. std430 for storage buffers, std140 for the one uniform block;
// explicit padding and static_asserts on size and offsets keep the two in step.
//
// Storage buffers (binding: contents):
//   0 PrimaryRay[width*height]         core/primary_segments.h, as-is (2 x vec4)
//   1 float[width*height*n]            per-pixel stored free-flight distances (n = freeFlightsPerRay)
//   2 PhotonBeam[beamCount]            core/photon_beam.h, as-is (3 x vec4)
//   3 float[beamCount*n]               per-beam stored free-flight distances
//   4 GlMedium[media]                  Scene::media
//   5 GlVolume[volumes]                dense density volumes of grid media
//   6 float[]                          all volumes' voxels (GlVolume::offset into it)
// Uniform block 0: GlSplatFrame.
#include <cstddef>
#include <cstdint>

#include "core/photon_beam.h"
#include "core/primary_segments.h"

namespace tyndall {

enum GlBinding : unsigned {
    kBindPrimaryRays = 0,
    kBindRayFreeFlights = 1,
    kBindBeams = 2,
    kBindBeamFreeFlights = 3,
    kBindMedia = 4,
    kBindVolumes = 5,
    kBindVoxels = 6,
    kBindFrame = 0,  // uniform block
};

/// One medium: GLSL `struct Medium { vec3 sigmaS; float g; vec3 sigmaT; int volume; }`.
struct GlMedium {
    float sigmaS[3];
    float g;
    float sigmaT[3];
    int32_t volume;  ///< index into the GlVolume array; -1 = homogeneous
};
static_assert(sizeof(GlMedium) == 32 && offsetof(GlMedium, sigmaT) == 16 && offsetof(GlMedium, volume) == 28,
              "GlMedium must match struct Medium in layout.glsl");

/// A dense density volume (core/density_volume.h): GLSL
/// `struct Volume { vec4 worldToIndex[3]; ivec3 size; uint offset; }`.
struct GlVolume {
    float worldToIndex[3][4];
    int32_t size[3];
    uint32_t offset;  ///< first voxel in the voxel buffer
};
static_assert(sizeof(GlVolume) == 64 && offsetof(GlVolume, size) == 48 && offsetof(GlVolume, offset) == 60,
              "GlVolume must match struct Volume in layout.glsl");

/// Per-splat constants (std140 uniform block `SplatFrame`): the camera that generated the
/// primary rays, in the terms of core/camera.h, and the buffer shapes.
struct GlSplatFrame {
    float cameraPosition[3];
    float tanHalfX;  ///< tan(yFov/2) * width/height
    float cameraRight[3];
    float tanHalfY;  ///< tan(yFov/2)
    float cameraUp[3];
    float focalPixels;  ///< 0.5 * height / tanHalfY
    float cameraForward[3];
    float lensRadius;
    int32_t filmSize[2];
    float focusDistance;
    int32_t freeFlightsPerRay;
    int32_t freeFlightsPerBeam;
    int32_t beamCount;
    int32_t pad[2];
};
static_assert(sizeof(GlSplatFrame) == 96 && offsetof(GlSplatFrame, filmSize) == 64 &&
                  offsetof(GlSplatFrame, freeFlightsPerBeam) == 80,
              "GlSplatFrame must match uniform block SplatFrame in layout.glsl");

// The pass data goes up as-is: GLSL `struct PrimaryRay { vec3 origin; float tMax; vec3 dir; int medium; }`
// and `struct PhotonBeam { vec3 origin; float tMax; vec3 dir; float radius; vec3 power; int medium; }`.
static_assert(sizeof(PrimaryRay) == 32 && offsetof(PrimaryRay, tMax) == 12 && offsetof(PrimaryRay, dir) == 16 &&
                  offsetof(PrimaryRay, medium) == 28 && sizeof(MediumId) == 4,
              "PrimaryRay must match struct PrimaryRay in layout.glsl");
static_assert(sizeof(PhotonBeam) == 48 && offsetof(PhotonBeam, tMax) == 12 && offsetof(PhotonBeam, dir) == 16 &&
                  offsetof(PhotonBeam, radius) == 28 && offsetof(PhotonBeam, power) == 32 &&
                  offsetof(PhotonBeam, medium) == 44,
              "PhotonBeam must match struct PhotonBeam in layout.glsl");

}  // namespace tyndall
