// Every struct and binding point the C++ side shares with GLSL, written once: this file is
// compiled as C++ (the splatter and its tests include it) and as GLSL (it is embedded and goes
// first in every shader, see gpu/CMakeLists.txt). The GLSL vector types are plain C++ structs
// here, so a member written below has the same name, type and order on both sides; the
// static_asserts at the end pin the std430 / std140 offsets the GLSL compiler gives them (and the
// GL introspection test in tests/gpu/ checks that the driver agrees).
//
// Storage buffers (binding: contents):
//   0 PrimaryRay[width*height]         core/primary_segments.h, as-is (2 x vec4)
//   1 float[width*height*n]            per-pixel stored free-flight distances (n = freeFlightsPerRay)
//   2 PhotonBeam[beamCount]            core/photon_beam.h, as-is (3 x vec4)
//   3 float[beamCount*n]               per-beam stored free-flight distances
//   4 Medium[media]                    Scene::media
//   5 Volume[volumes]                  dense density volumes of grid media
//   6 float[]                          all volumes' voxels (Volume::offset into it)
// Uniform block 0: SplatFrame.
#ifdef __cplusplus
#pragma once
#include <cstddef>
#include <cstdint>

#include "core/photon_beam.h"
#include "core/primary_segments.h"

namespace tyndall::shader {
struct vec3 {
    float x, y, z;
};
struct vec4 {
    float x, y, z, w;
};
struct ivec2 {
    int32_t x, y;
};
struct ivec3 {
    int32_t x, y, z;
};
using uint = uint32_t;
#define TYNDALL_UNIFORM_BLOCK(Name, slot) struct Name
#define TYNDALL_UNIFORM_INSTANCE(instance)
#else
#define TYNDALL_UNIFORM_BLOCK(Name, slot) layout(std140, binding = slot) uniform Name
#define TYNDALL_UNIFORM_INSTANCE(instance) instance
#endif

const int kBindPrimaryRays = 0;
const int kBindRayFreeFlights = 1;
const int kBindBeams = 2;
const int kBindBeamFreeFlights = 3;
const int kBindMedia = 4;
const int kBindVolumes = 5;
const int kBindVoxels = 6;
const int kBindFrame = 0;  // uniform block

/// core/primary_segments.h's PrimaryRay as GLSL reads it.
struct PrimaryRay {
    vec3 origin;
    float tMax;
    vec3 dir;
    int medium;  // -1 = vacuum
};

/// core/photon_beam.h's PhotonBeam as GLSL reads it.
struct PhotonBeam {
    vec3 origin;
    float tMax;
    vec3 dir;
    float radius;
    vec3 power;
    int medium;
};

/// One medium of Scene::media.
struct Medium {
    vec3 sigmaS;
    float g;
    vec3 sigmaT;
    int volume;  // index into the Volume array; -1 = homogeneous
};

/// A dense density volume (core/density_volume.h).
struct Volume {
    vec4 worldToIndex[3];
    ivec3 size;
    uint offset;  // first voxel in the voxel buffer
};

/// Per-splat constants: the camera that generated the primary rays, in the terms of
/// core/camera.h, and the buffer shapes.
TYNDALL_UNIFORM_BLOCK(SplatFrame, kBindFrame) {
    vec3 cameraPosition;
    float tanHalfX;  // tan(yFov/2) * width/height
    vec3 cameraRight;
    float tanHalfY;  // tan(yFov/2)
    vec3 cameraUp;
    float focalPixels;  // 0.5 * height / tanHalfY
    vec3 cameraForward;
    float lensRadius;
    ivec2 filmSize;
    float focusDistance;
    int freeFlightsPerRay;
    int freeFlightsPerBeam;
    int beamCount;
    ivec2 pad;
}
TYNDALL_UNIFORM_INSTANCE(frame);

#ifndef __cplusplus
// Grid media compiled in or out: software rasterizers run both sides of every branch, so a
// scene without grid media gets a shader without their code (GlBeamSplatter defines it).
#ifndef TYNDALL_GRID_MEDIA
#define TYNDALL_GRID_MEDIA 1
#endif
layout(std430, binding = kBindPrimaryRays) readonly buffer PrimaryRays {
    PrimaryRay rays[];
};
layout(std430, binding = kBindRayFreeFlights) readonly buffer RayFreeFlights {
    float rayFreeFlights[];
};
layout(std430, binding = kBindBeams) readonly buffer Beams {
    PhotonBeam beams[];
};
layout(std430, binding = kBindBeamFreeFlights) readonly buffer BeamFreeFlights {
    float beamFreeFlights[];
};
layout(std430, binding = kBindMedia) readonly buffer Media {
    Medium media[];
};
layout(std430, binding = kBindVolumes) readonly buffer Volumes {
    Volume volumes[];
};
layout(std430, binding = kBindVoxels) readonly buffer Voxels {
    float voxels[];
};
#else
// std430 (storage buffers) and std140 (the uniform block) give these offsets: a vec3 is aligned
// like a vec4 and the float or int after it fills its fourth slot.
static_assert(sizeof(PrimaryRay) == 32 && offsetof(PrimaryRay, tMax) == 12 && offsetof(PrimaryRay, dir) == 16 &&
              offsetof(PrimaryRay, medium) == 28);
static_assert(sizeof(PhotonBeam) == 48 && offsetof(PhotonBeam, tMax) == 12 && offsetof(PhotonBeam, dir) == 16 &&
              offsetof(PhotonBeam, radius) == 28 && offsetof(PhotonBeam, power) == 32 &&
              offsetof(PhotonBeam, medium) == 44);
static_assert(sizeof(Medium) == 32 && offsetof(Medium, sigmaT) == 16 && offsetof(Medium, volume) == 28);
static_assert(sizeof(Volume) == 64 && offsetof(Volume, size) == 48 && offsetof(Volume, offset) == 60);
static_assert(sizeof(SplatFrame) == 96 && offsetof(SplatFrame, cameraRight) == 16 &&
              offsetof(SplatFrame, cameraUp) == 32 && offsetof(SplatFrame, cameraForward) == 48 &&
              offsetof(SplatFrame, filmSize) == 64 && offsetof(SplatFrame, focusDistance) == 72 &&
              offsetof(SplatFrame, freeFlightsPerBeam) == 80 && offsetof(SplatFrame, beamCount) == 84);
}  // namespace tyndall::shader

namespace tyndall {
// The pass data goes up as-is: core's structs must have the layout GLSL reads.
static_assert(sizeof(tyndall::PrimaryRay) == sizeof(shader::PrimaryRay) &&
                  offsetof(tyndall::PrimaryRay, origin) == offsetof(shader::PrimaryRay, origin) &&
                  offsetof(tyndall::PrimaryRay, tMax) == offsetof(shader::PrimaryRay, tMax) &&
                  offsetof(tyndall::PrimaryRay, dir) == offsetof(shader::PrimaryRay, dir) &&
                  offsetof(tyndall::PrimaryRay, medium) == offsetof(shader::PrimaryRay, medium) &&
                  sizeof(MediumId) == sizeof(int),
              "core's PrimaryRay must match the GLSL PrimaryRay");
static_assert(sizeof(tyndall::PhotonBeam) == sizeof(shader::PhotonBeam) &&
                  offsetof(tyndall::PhotonBeam, origin) == offsetof(shader::PhotonBeam, origin) &&
                  offsetof(tyndall::PhotonBeam, tMax) == offsetof(shader::PhotonBeam, tMax) &&
                  offsetof(tyndall::PhotonBeam, dir) == offsetof(shader::PhotonBeam, dir) &&
                  offsetof(tyndall::PhotonBeam, radius) == offsetof(shader::PhotonBeam, radius) &&
                  offsetof(tyndall::PhotonBeam, power) == offsetof(shader::PhotonBeam, power) &&
                  offsetof(tyndall::PhotonBeam, medium) == offsetof(shader::PhotonBeam, medium),
              "core's PhotonBeam must match the GLSL PhotonBeam");
using GlMedium = shader::Medium;
using GlVolume = shader::Volume;
using GlSplatFrame = shader::SplatFrame;
using shader::kBindBeamFreeFlights;
using shader::kBindBeams;
using shader::kBindFrame;
using shader::kBindMedia;
using shader::kBindPrimaryRays;
using shader::kBindRayFreeFlights;
using shader::kBindVolumes;
using shader::kBindVoxels;
}  // namespace tyndall
#endif
