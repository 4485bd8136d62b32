#pragma once
// What every stage reads at a surface before it scatters there (core/bsdf.h): the material's
// parameters at the hit and its shading normal.
#include "core/bsdf.h"
#include "core/material_eval.h"
#include "core/scene.h"
#include "core/surface_hit.h"

namespace tyndall {

/// The material at a hit, textures filtered over `footprint` world units (core/material_eval.h).
inline SurfacePoint surfaceAt(const Scene& scene, const SurfaceHit& hit, float footprint) {
    const TriangleMesh& mesh = scene.meshes[size_t(hit.mesh)];
    const Material& mat = scene.materials[size_t(mesh.material)];
    return mat.isTextured() ? evalSurface(scene, mesh, hit.triangle, hit.b1, hit.b2, footprint) : surfaceFactors(mat);
}

/// Normal maps: replaces hit->ns by the normal-mapped shading normal when the material has a normal
/// map (texture filtered over `footprint` world units); otherwise leaves the hit as it is (ns = ng
/// on diffuse surfaces, the interpolated normal on specular ones). Every stage calls this before
/// building its Bsdf, so camera paths, photons and the reference tracer shade with the same normal.
inline void applyNormalMap(const Scene& scene, SurfaceHit* hit, float footprint) {
    const TriangleMesh& mesh = scene.meshes[size_t(hit->mesh)];
    if (!scene.materials[size_t(mesh.material)].isNormalMapped()) return;
    const Vec3 ng = hit->ng;  // a copy: the hit's address stays with the caller
    hit->ns = normalMappedNormal(scene, mesh, hit->triangle, hit->b1, hit->b2, ng, footprint);
}

}  // namespace tyndall
