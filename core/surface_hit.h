#pragma once
// A ray's hit on a surface and the geometry every stage shades it with: which side the ray
// arrives on, and the factors a shading normal (interpolated or normal-mapped, docs/algorithm.md
// "Normal maps") brings against the geometric one.
#include <cmath>
#include <cstdint>

#include "core/math.h"

namespace tyndall {

struct SurfaceHit {
    float t = 0;
    int mesh = -1;
    uint32_t triangle = 0;
    Vec3 p;   ///< hit point
    Vec3 ng;  ///< unit geometric normal, pointing to the mesh exterior (CCW winding)
    Vec3 ns;  ///< unit shading normal, on ng's side: interpolated on specular meshes with normals, else ng
    float b1 = 0, b2 = 0;  ///< barycentrics of vertices 1 and 2
};

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

/// The diffuse base with a shading normal (docs/algorithm.md "Normal maps"): radiance leaving
/// toward any direction on the geometric side `nf` is rho/pi x max(0, wi . nsf) x L(wi), with wi
/// the light-side direction; per unit of the geometric cosine that is
///   max(0, wi . nsf) / (wi . nf)   (0 for wi below the geometric surface),
/// the factor a photon's density estimate is weighted with (wi: toward where the photon came from)
/// and, by Veach's adjoint, the factor a photon's power takes when it bounces off the surface
/// (wi = the direction it arrived from; the bounce then samples cos about nf). 1 when nsf = nf.
inline float shadingCosineRatio(const HitSide& side, const Vec3& wi) {
    float cg = dot(wi, side.nf);
    return cg > 0 ? std::max(0.0f, dot(wi, side.nsf)) / cg : 0.0f;
}

/// The hit shades with a normal other than the geometric one.
inline bool hasShadingNormal(const SurfaceHit& hit) {
    return hit.ns.x != hit.ng.x || hit.ns.y != hit.ng.y || hit.ns.z != hit.ng.z;
}

/// Veach's adjoint correction for a shading normal on a photon path (importance transport) at a
/// specular or glossy vertex: |wo . ns| |wi . ng| / (|wo . ng| |wi . ns|), with wo toward where the
/// photon came from and wi where it goes. Multiplies the weight of a lobe sampled in the shading
/// frame (Bsdf::sample does); 1 when ns = ng.
inline float shadingNormalAdjoint(const Vec3& ng, const Vec3& ns, const Vec3& wo, const Vec3& wi) {
    float num = std::abs(dot(wo, ns)) * std::abs(dot(wi, ng));
    float den = std::abs(dot(wo, ng)) * std::abs(dot(wi, ns));
    return den > 0 ? num / den : 0.0f;
}

/// |wi . ns| / |wi . ng|: a surface photon's power carries the geometric cosine of its arrival; a
/// BSDF in the shading frame wants the shading one (1 when ns = ng).
inline float shadingOverGeometricCosine(const SurfaceHit& hit, const Vec3& wi) {
    float den = std::abs(dot(wi, hit.ng));
    return den > 0 ? std::abs(dot(wi, hit.ns)) / den : 0.0f;
}

}  // namespace tyndall
