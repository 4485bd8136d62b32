#pragma once
// A material's parameters at one surface point: the factors times their textures. Every stage that
// shades a surface (photon tracing, camera paths, the reference path tracer, light emission) reads
// materials through here, so a textured and an untextured material take the same route.
//
// Footprint: texture lookups are filtered over a width given in world units at the hit (the
// caller's estimate of what one sample stands for: for camera paths the pixel's width at the
// distance travelled, `pixelSpread * path length`; for photons the surface-photon radius, which the
// density estimate blurs over anyway). It is turned into uv units with the triangle's own uv/world
// scale, so no ray differentials are carried. Averaging jittered passes anti-aliases whatever the
// filter leaves; the filter mainly picks the mip level (less noise, fewer tiles read).
#include <cstdint>

#include "core/scene.h"
#include "core/tangent_frame.h"

namespace tyndall {

/// What a surface point looks like.
struct SurfacePoint {
    Rgb baseColor{0.8f};   ///< Material::albedo x baseColorTexture RGB
    float alpha = 1.0f;    ///< baseColor alpha (alphaMode MASK / BLEND read it)
    Rgb emission{0.0f};    ///< Material::emission x emissiveTexture
    float metallic = 0.0f;
    float roughness = 1.0f;
    float transmission = 1.0f;  ///< Dielectric: Material::transmission x transmissionTexture R
};

/// TEXCOORD_`set` of triangle `tri` at barycentrics (b1, b2); (0, 0) when the mesh has none.
Vec2 meshTexcoord(const TriangleMesh& mesh, int set, uint32_t tri, float b1, float b2);
/// sqrt(uv area / world area) of triangle `tri` in TEXCOORD_`set`: converts a world footprint to uv.
float texcoordScale(const TriangleMesh& mesh, int set, uint32_t tri);

/// A material's factors: what evalSurface returns for an untextured one.
inline SurfacePoint surfaceFactors(const Material& mat) {
    SurfacePoint sp;
    sp.baseColor = mat.albedo;
    sp.alpha = mat.alpha;
    sp.emission = mat.emission;
    sp.metallic = mat.metallic;
    sp.roughness = mat.roughness;
    sp.transmission = mat.transmission;
    return sp;
}

/// The material of `mesh` at (tri, b1, b2), with textures looked up over `footprint` world units.
/// Untextured materials return their factors without touching a texture. Thread-safe.
SurfacePoint evalSurface(const Scene& scene, const TriangleMesh& mesh, uint32_t tri, float b1, float b2,
                         float footprint);

/// The normal-mapped shading normal (unit, within kMinHorizonCos of ng's hemisphere or above) of
/// `mesh` at (tri, b1, b2), `ng` the unit geometric normal toward the exterior: the normalTexture
/// texel in the tangent frame (core/tangent_frame.h) of the normal map's TEXCOORD set. Only for
/// materials with a normal map (Material::isNormalMapped). A flat texel (0.5, 0.5, 1 exactly)
/// gives the interpolated vertex normal, or ng itself for meshes without normals.
Vec3 normalMappedNormal(const Scene& scene, const TriangleMesh& mesh, uint32_t tri, float b1, float b2,
                        const Vec3& ng, float footprint);

/// One texture slot at a point: RGBA, (1, 1, 1, 1) when the slot is empty.
std::array<float, 4> sampleSlot(const Scene& scene, const TextureRef& ref, const TriangleMesh& mesh, uint32_t tri,
                                float b1, float b2, float footprint);

/// World width of one pixel per unit of distance from a pinhole camera with vertical field of view
/// `yFov` rendering `height` rows: the camera-side footprint is pixelSpread * distance.
inline float pixelSpread(float yFov, int height) { return 2.0f * std::tan(0.5f * yFov) / float(std::max(height, 1)); }

}  // namespace tyndall
