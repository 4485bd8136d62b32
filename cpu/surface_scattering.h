#pragma once
// What happens to a path at a surface, shared by photon paths, camera paths and the reference
// path tracer: which way it leaves, the throughput factor, and the medium it ends up in.
#include "core/fresnel.h"
#include "core/material.h"
#include "core/material_eval.h"
#include "core/scene.h"
#include "cpu/embree_scene.h"

namespace tyndall {

/// Orientation of a hit as seen by a ray travelling along `d`.
struct HitSide {
    Vec3 nf;        ///< geometric normal flipped to face the incoming ray
    Vec3 nsf;       ///< shading normal on the same side as nf
    bool entering;  ///< the ray arrives from the exterior side (dot(d, ng) < 0)
};

inline HitSide hitSide(const SurfaceHit& hit, const Vec3& d) {
    bool entering = dot(d, hit.ng) < 0;
    return {entering ? hit.ng : -hit.ng, entering ? hit.ns : -hit.ns, entering};
}

/// Which flux a path carries: photons carry power (no 1/eta^2 at refraction), camera paths
/// carry radiance (scaled by (eta_i/eta_t)^2 when crossing into another index).
enum class TransportMode { Importance, Radiance };

/// A specular interaction (mirror, dielectric, interface): the outgoing direction, throughput
/// factor and new medium. `u` chooses between Fresnel reflection and refraction. Returns false
/// when the path must end (the shading normal sent it below the geometric surface).
struct SpecularEvent {
    Vec3 d;
    Rgb weight{1.0f};
    MediumId medium = kVacuum;
    bool transmitted = false;
};

/// The material at a hit, textures filtered over `footprint` world units (core/material_eval.h).
inline SurfacePoint surfaceAt(const Scene& scene, const SurfaceHit& hit, float footprint) {
    return evalSurface(scene, scene.meshes[size_t(hit.mesh)], hit.triangle, hit.b1, hit.b2, footprint);
}

/// `tint`: the mirror reflectance / dielectric transmission tint at the hit (Material::albedo, times
/// baseColorTexture where the material has one).
inline bool sampleSpecular(const Material& mat, const Rgb& tint, const TriangleMesh& mesh, const SurfaceHit& hit,
                           const Vec3& dIn, MediumId currentMedium, float u, TransportMode mode, SpecularEvent* ev) {
    HitSide side = hitSide(hit, dIn);
    Vec3 wo = -dIn;
    ev->medium = currentMedium;
    ev->transmitted = false;
    switch (mat.type) {
        case MaterialType::Mirror:
            ev->d = reflect(wo, side.nsf);
            ev->weight = tint;
            return dot(ev->d, side.nf) > 0;
        case MaterialType::Interface:
            ev->d = dIn;
            ev->weight = Rgb(1.0f);
            ev->medium = side.entering ? mesh.interiorMedium : mesh.exteriorMedium;
            ev->transmitted = true;
            return true;
        case MaterialType::Dielectric: {
            float f = fresnelDielectric(dot(wo, hit.ns), mat.ior);
            if (u < f) {
                ev->d = reflect(wo, side.nsf);
                ev->weight = Rgb(1.0f);
                return dot(ev->d, side.nf) > 0;
            }
            Vec3 wt;
            if (!refract(wo, hit.ns, mat.ior, &wt)) {  // TIR when the shading normal disagrees with F
                ev->d = reflect(wo, side.nsf);
                ev->weight = Rgb(1.0f);
                return dot(ev->d, side.nf) > 0;
            }
            ev->d = wt;
            ev->weight = tint;
            if (mode == TransportMode::Radiance) {
                float etaRatio = side.entering ? 1.0f / mat.ior : mat.ior;  // eta_i / eta_t
                ev->weight *= etaRatio * etaRatio;
            }
            ev->medium = side.entering ? mesh.interiorMedium : mesh.exteriorMedium;
            ev->transmitted = true;
            return dot(ev->d, side.nf) < 0;
        }
        case MaterialType::Diffuse:
            break;
    }
    return false;
}

/// sampleSpecular with the material's untextured tint.
inline bool sampleSpecular(const Material& mat, const TriangleMesh& mesh, const SurfaceHit& hit, const Vec3& dIn,
                           MediumId currentMedium, float u, TransportMode mode, SpecularEvent* ev) {
    return sampleSpecular(mat, mat.albedo, mesh, hit, dIn, currentMedium, u, mode, ev);
}

}  // namespace tyndall
