#pragma once
// What happens to a path at a surface, shared by photon paths, camera paths and the reference
// path tracer: which way it leaves, the throughput factor, and the medium it ends up in.
#include "core/coated_diffuse.h"
#include "core/fresnel.h"
#include "core/material.h"
#include "core/material_eval.h"
#include "core/microfacet.h"
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

/// Normal maps: replaces hit->ns by the normal-mapped shading normal when the material has a normal
/// map (texture filtered over `footprint` world units); otherwise leaves the hit as it is (ns = ng
/// on diffuse surfaces, the interpolated normal on specular ones). Every stage calls this before
/// hitSide(), so camera paths, photons and the reference tracer shade with the same normal.
inline void applyNormalMap(const Scene& scene, SurfaceHit* hit, float footprint) {
    const TriangleMesh& mesh = scene.meshes[size_t(hit->mesh)];
    if (!scene.materials[size_t(mesh.material)].isNormalMapped()) return;
    hit->ns = normalMappedNormal(scene, mesh, hit->triangle, hit->b1, hit->b2, hit->ng, footprint);
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

/// Veach's adjoint correction for a shading normal on a photon path (importance transport) at a
/// specular or glossy vertex: |wo . ns| |wi . ng| / (|wo . ng| |wi . ns|), with wo toward where the
/// photon came from and wi where it goes. Multiplies the weight of sampleSpecular/sampleGlossy
/// (which use ns for the cosine); 1 when ns = ng.
inline bool hasShadingNormal(const SurfaceHit& hit) {
    return hit.ns.x != hit.ng.x || hit.ns.y != hit.ng.y || hit.ns.z != hit.ng.z;
}

inline float shadingNormalAdjoint(const SurfaceHit& hit, const Vec3& wo, const Vec3& wi) {
    float num = std::abs(dot(wo, hit.ns)) * std::abs(dot(wi, hit.ng));
    float den = std::abs(dot(wo, hit.ng)) * std::abs(dot(wi, hit.ns));
    return den > 0 ? num / den : 0.0f;
}

/// A partly transmissive dielectric (Material::isPartlyTransmissive) is at each vertex the
/// dielectric with probability sp.transmission, else its diffuse base: true = the diffuse base.
/// `u` is drawn only for such materials, so other materials' random streams are unchanged.
inline bool diffuseBaseChosen(const Material& mat, const SurfacePoint& sp, float u) {
    return mat.type == MaterialType::Diffuse || (mat.isPartlyTransmissive() && !(u < sp.transmission));
}

/// A plastic with a metal part (Material::hasMetalMix) is at each vertex the conductor (F0 =
/// baseColor) with probability sp.metallic, else the coated diffuse: true = the conductor. `u` is
/// drawn only for such materials.
inline bool metalChosen(const Material& mat, const SurfacePoint& sp, float u) {
    return mat.hasMetalMix() && u < sp.metallic;
}

/// |wi . ns| / |wi . ng|: a surface photon's power carries the geometric cosine of its arrival; a
/// BSDF in the shading frame wants the shading one (1 when ns = ng).
inline float shadingOverGeometricCosine(const SurfaceHit& hit, const Vec3& wi) {
    float den = std::abs(dot(wi, hit.ng));
    return den > 0 ? std::abs(dot(wi, hit.ns)) / den : 0.0f;
}

/// `tint`: the mirror reflectance / dielectric transmission tint at the hit (Material::albedo, times
/// baseColorTexture where the material has one). On a Plastic (only called when metalChosen and
/// the material is smooth) the metal part: a mirror.
inline bool sampleSpecular(const Material& mat, const Rgb& tint, const TriangleMesh& mesh, const SurfaceHit& hit,
                           const Vec3& dIn, MediumId currentMedium, float u, TransportMode mode, SpecularEvent* ev) {
    HitSide side = hitSide(hit, dIn);
    Vec3 wo = -dIn;
    ev->medium = currentMedium;
    ev->transmitted = false;
    switch (mat.type) {
        case MaterialType::Mirror:
        case MaterialType::Plastic:
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

/// The GGX lobe of a glossy material (Material::isGlossy) at a hit, in the shading frame.
/// Conductors (Mirror) reflect on the side the path arrives from; dielectrics use the exterior
/// side (+z = hit.ns, toward the mesh exterior) so eta = interior / exterior holds from both sides.
struct GlossyBsdf {
    Frame frame;
    bool conductor = true;
    RoughConductor metal;
    RoughDielectric glass;

    Rgb eval(const Vec3& woWorld, const Vec3& wiWorld, TransportMode mode) const {
        Vec3 wo = frame.toLocal(woWorld), wi = frame.toLocal(wiWorld);
        if (conductor) return metal.eval(wo, wi);
        return glass.eval(wo, wi, mode == TransportMode::Radiance ? MicrofacetMode::Radiance : MicrofacetMode::Importance);
    }
    float pdf(const Vec3& woWorld, const Vec3& wiWorld) const {
        Vec3 wo = frame.toLocal(woWorld), wi = frame.toLocal(wiWorld);
        return conductor ? metal.pdf(wo, wi) : glass.pdf(wo, wi);
    }
};

/// `sp`: the material at the hit (roughness and tint from textures); `dIn`: the arriving direction.
/// A Plastic gives its metal part (a conductor: call it only when metalChosen).
inline GlossyBsdf glossyBsdf(const Material& mat, const SurfacePoint& sp, const SurfaceHit& hit, const Vec3& dIn) {
    GlossyBsdf b;
    Ggx ggx = Ggx::fromRoughness(std::max(sp.roughness, Material::kSmoothRoughness));
    b.conductor = mat.type == MaterialType::Mirror || mat.type == MaterialType::Plastic;
    if (b.conductor) {
        b.frame = Frame(hitSide(hit, dIn).nsf);
        b.metal = RoughConductor{ggx, sp.baseColor};
    } else {
        b.frame = Frame(hit.ns);
        b.glass = RoughDielectric{ggx, mat.ior, sp.baseColor};
    }
    return b;
}

/// Samples the glossy lobe: like sampleSpecular, with `ev->weight` = f |cos| / pdf and `*pdf` the
/// solid-angle pdf (for MIS). False when the path must end (sampled below the geometric surface,
/// or a back-facing microfacet).
inline bool sampleGlossy(const GlossyBsdf& bsdf, const TriangleMesh& mesh, const SurfaceHit& hit, const Vec3& dIn,
                         MediumId currentMedium, float u0, float u1, float u2, TransportMode mode, SpecularEvent* ev,
                         float* pdf = nullptr) {
    HitSide side = hitSide(hit, dIn);
    Vec3 wo = bsdf.frame.toLocal(-dIn);
    MicrofacetSample s = bsdf.conductor
                             ? bsdf.metal.sample(wo, u1, u2)
                             : bsdf.glass.sample(wo, u0, u1, u2,
                                                 mode == TransportMode::Radiance ? MicrofacetMode::Radiance
                                                                                 : MicrofacetMode::Importance);
    if (!s.valid) return false;
    ev->d = normalize(bsdf.frame.toWorld(s.wi));
    ev->weight = s.weight;
    ev->transmitted = s.transmitted;
    ev->medium = s.transmitted ? (side.entering ? mesh.interiorMedium : mesh.exteriorMedium) : currentMedium;
    if (pdf) *pdf = s.pdf;
    return s.transmitted ? dot(ev->d, side.nf) < 0 : dot(ev->d, side.nf) > 0;
}

/// The coated diffuse of a Plastic at a hit (core/coated_diffuse.h), in the shading frame on the
/// side the path arrives from (+z = hitSide(hit, dIn).nsf; the coat is opaque).
struct CoatedBsdf {
    Frame frame;
    CoatedDiffuse coat;

    /// f in world directions (reciprocal: the same for radiance and importance).
    Rgb eval(const Vec3& woWorld, const Vec3& wiWorld) const {
        return coat.eval(frame.toLocal(woWorld), frame.toLocal(wiWorld));
    }
    float pdf(const Vec3& woWorld, const Vec3& wiWorld) const {
        return coat.pdf(frame.toLocal(woWorld), frame.toLocal(wiWorld));
    }
    /// What a surface photon arriving from `wiWorld` adds to a camera path leaving toward `woWorld`
    /// per unit of its power x kernel, before the path throughput: the diffuse part unless
    /// `directLit` (kPhotonDirect with --direct-light on: a shadow ray carries that light), plus the
    /// specular part for `deltaPath` ones (kPhotonDeltaPath: light the continuation cannot find;
    /// docs/algorithm.md "Coated (plastic) vertices"). Shading normal: times |wi . ns| / |wi . ng|
    /// (the caller's shadingOverGeometricCosine).
    Rgb photonWeight(const Vec3& woWorld, const Vec3& wiWorld, bool deltaPath, bool directLit = false) const {
        Vec3 wo = frame.toLocal(woWorld), wi = frame.toLocal(wiWorld);
        Rgb f = directLit ? Rgb(0.0f) : coat.evalDiffuse(wo, wi);
        if (deltaPath) f += Rgb(coat.evalSpecular(wo, wi));
        return f;
    }
    /// The diffuse part alone in world directions (direct light by shadow rays).
    Rgb evalDiffuse(const Vec3& woWorld, const Vec3& wiWorld) const {
        return coat.evalDiffuse(frame.toLocal(woWorld), frame.toLocal(wiWorld));
    }
};

/// `sp`: the plastic at the hit (base colour, roughness from textures); `dIn`: the arriving direction.
inline CoatedBsdf coatedBsdf(const Material& mat, const SurfacePoint& sp, const SurfaceHit& hit, const Vec3& dIn) {
    CoatedBsdf b;
    b.frame = Frame(hitSide(hit, dIn).nsf);
    b.coat = CoatedDiffuse::make(std::max(sp.roughness, Material::kSmoothRoughness), !mat.isRough(), mat.ior,
                                 sp.baseColor);
    return b;
}

/// Samples the coated BSDF like sampleGlossy: the mixture of both lobes (`specularOnly` false:
/// weight = f cos / mixture pdf), or the specular lobe alone (weight = f_s cos / pdf_s; PPB camera
/// paths, whose diffuse part is the photon estimate). `*delta`: the smooth coat's mirror direction
/// was taken (no pdf for MIS). False when the path must end (below the geometric surface).
inline bool sampleCoated(const CoatedBsdf& bsdf, const SurfaceHit& hit, const Vec3& dIn, MediumId currentMedium,
                         float u0, float u1, float u2, bool specularOnly, SpecularEvent* ev, float* pdf = nullptr,
                         bool* delta = nullptr) {
    HitSide side = hitSide(hit, dIn);
    Vec3 wo = bsdf.frame.toLocal(-dIn);
    CoatedSample s = specularOnly ? bsdf.coat.sampleSpecular(wo, u1, u2) : bsdf.coat.sample(wo, u0, u1, u2);
    if (!s.valid) return false;
    ev->d = normalize(bsdf.frame.toWorld(s.wi));
    ev->weight = s.weight;
    ev->transmitted = false;
    ev->medium = currentMedium;
    if (pdf) *pdf = s.pdf;
    if (delta) *delta = s.delta;
    return dot(ev->d, side.nf) > 0;
}

}  // namespace tyndall
