#pragma once
// Scattering at one surface point: the one interface the photon tracer (importance), PPB's camera
// paths and the reference path tracer (radiance) scatter through, modelled on pbrt-v4's BSDF
// (Sample_f / f / PDF, lobe flags, TransportMode). A material's behaviour is written here once.
//
// Bsdf::at builds it at a hit for a path arriving along dIn and makes the material's per-vertex
// choice of component (docs/algorithm.md "Partial transmission", "Coated (plastic) vertices"):
//   - Diffuse: the Lambertian base, rho = baseColor: Diffuse materials, and a partly transmissive
//     dielectric's base, chosen with probability 1 - transmission (one number drawn);
//   - Coated: a Plastic's coat over its diffuse base (core/coated_diffuse.h); a plastic with a
//     metal part is its conductor instead with probability metallic (one number drawn), which is
//     Glossy when rough, Specular when smooth;
//   - Glossy: GGX conductor (rough Mirror) or rough dielectric, or a thin rough sheet (core/microfacet.h);
//   - Specular: delta mirror, smooth dielectric (Fresnel's choice of reflection or refraction; a
//     thin one's choice of reflection or passing straight through, Material::thin), Interface (straight through, switching the medium: pbrt's empty BSDF).
// Then sample() draws a direction from the component, f() and pdf() evaluate it toward any.
//
// Random numbers, from the caller's path stream and in this order: at() draws at most one (the
// mixes above); sample() draws per component diffuse 2, coat 3 (its specular part alone 2),
// glossy 3, specular 1, and one more where the caller's roulette plays. Each tracer's images
// depend on this order.
//
// Directions are world-space and point away from the surface; wo = -dIn is fixed at construction.
// With a shading normal (interpolated or normal-mapped), f and pdf live in the shading frame and
// a sample's weight is f |wi . ns| / pdf, times Veach's adjoint |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|)
// in importance mode (cosine-weighted diffuse: rho, and rho max(0, wo.nsf) / (wo.nf) for photons,
// which sample the cosine about the geometric normal instead).
#include <algorithm>
#include <cstdint>

#include "core/coated_diffuse.h"
#include "core/fresnel.h"
#include "core/material.h"
#include "core/material_eval.h"
#include "core/microfacet.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/scene.h"
#include "core/surface_hit.h"
#include "core/transport_mode.h"

namespace tyndall {

/// Lobe flags (pbrt's BxDFFlags): a lobe is reflection or transmission, and diffuse, glossy (a
/// non-delta lobe with a peak) or specular (a delta).
using BsdfLobes = uint8_t;
constexpr BsdfLobes kLobeReflection = 1, kLobeTransmission = 2, kLobeDiffuse = 4, kLobeGlossy = 8,
                    kLobeSpecular = 16, kLobesAll = 31;

/// A scattered direction (Bsdf::sample).
struct BsdfSample {
    Vec3 wi;                    ///< unit direction the path leaves along
    Rgb weight{1.0f};           ///< the factor the throughput took (see Bsdf::sample)
    float pdf = 0;              ///< solid-angle pdf of wi; a delta lobe's is not one (no MIS)
    BsdfLobes lobe = 0;         ///< the lobe taken: reflection or transmission, and its kind
    MediumId medium = kVacuum;  ///< the medium wi travels in
    float eta = 1.0f;           ///< eta_i / eta_t across a dielectric's refraction, else 1
};

/// Russian roulette as a tracer plays it at a scattering vertex, for Bsdf::sample: a callable
/// q(beta, w) giving the probability that a path with throughput `beta` goes on through a lobe of
/// weight `w`, or kNoRoulette (nothing drawn). A path that goes on carries 1/q.
constexpr float kNoRoulette = -1.0f;
struct NoRoulette {
    float operator()(const Rgb&, const Rgb&) const { return kNoRoulette; }
};

class Bsdf {
public:
    /// The scattering at `hit` (its normals final: normal maps applied) of a path arriving along
    /// `dIn` in `medium`, `sp` the material there (core/material_eval.h). Draws from `rng` only
    /// for the mixes (see the file comment). Uniforms: Rng, or anything with float uniform().
    /// Every path vertex builds one: the common part and the diffuse and delta components are
    /// built inline, the components with a frame of their own out of line (buildFramed, by value:
    /// no out-of-line call takes the Bsdf's address; docs/performance.md, the photon stage).
    template <class Uniforms>
    [[gnu::always_inline]] static Bsdf at(const Scene& scene, const SurfaceHit& hit, const SurfacePoint& sp,
                                          const Vec3& dIn, MediumId medium, TransportMode mode, Uniforms& rng);

    /// Every lobe of the chosen component (a coat: diffuse and glossy or specular reflection).
    BsdfLobes lobes() const { return m_lobes; }
    /// An Interface: no scattering, the path goes straight on into mediumBeyond().
    bool isPassThrough() const { return m_type == MaterialType::Interface; }
    const HitSide& side() const { return m_side; }
    /// The direction toward the arriving path, -dIn.
    const Vec3& wo() const { return m_wo; }
    /// The medium on the other side of the surface from the arriving path.
    MediumId mediumBeyond() const { return m_beyond; }
    /// +z of the coat's and the glossy lobes' frame: the shading normal on the arriving side, a
    /// dielectric's toward the exterior.
    const Vec3& normal() const { return local().frame.n; }

    /// f(wo, wi) restricted to the lobe kinds in `lobes` (diffuse, glossy, specular; delta lobes
    /// are 0 here). In the mode's convention: f_radiance(wo, wi) = f_importance(wi, wo).
    Rgb f(const Vec3& wi, BsdfLobes lobes = kLobesAll) const;
    /// The solid-angle density sample() draws wi with (all lobes; 0 for delta components).
    float pdf(const Vec3& wi) const;
    /// The density sample(..., allowed) draws wi with: pdf(wi) when `allowed` has kLobeDiffuse, a
    /// coat's specular lobe's own without it (what a camera path's continuation samples), 0 for a
    /// component none of `allowed` covers.
    float pdf(const Vec3& wi, BsdfLobes allowed) const;

    /// Samples a lobe among `allowed` (kLobesAll, or without kLobeDiffuse: a coat's specular part
    /// alone, weight f_s cos / pdf_s) and a direction, plays `roulette`, and multiplies `*beta` by
    /// the weight: f |wi . ns| / pdf (see the file comment), times 1/q where the roulette played.
    /// The roulette plays as soon as the weight is known: for the importance diffuse lobe before
    /// the direction is drawn (its weight does not depend on it), else after. False when the path
    /// ends: no lobe allowed, a sample below the geometric surface or on a back-facing microfacet,
    /// or the roulette.
    template <class Uniforms, class Roulette = NoRoulette>
    [[gnu::always_inline]] bool sample(Uniforms& rng, Rgb* beta, BsdfSample* s, BsdfLobes allowed = kLobesAll,
                                       const Roulette& roulette = {}) const;

private:
    enum class Kind : uint8_t { Diffuse, Coated, Conductor, RoughDielectric, Delta };
    struct Local {
        Frame frame;  ///< +z: normal()
        Vec3 wo;      ///< m_wo in frame
    };
    /// The chosen component's parts, for the kinds that have them (the others cost nothing to
    /// build: every vertex of every path builds a Bsdf).
    struct Framed {
        Kind kind;
        BsdfLobes lobes;
        union Parts {
            Parts() {}
            Local local;
        } parts;
        union Component {
            Component() {}
            CoatedDiffuse coat;
            RoughConductor metal;
            RoughDielectric glass;
        } component;
    };

    [[gnu::always_inline]] bool sampleDelta(float u, BsdfSample* s, Rgb* w) const;
    /// sample()'s coat, GGX conductor and rough dielectric, out of line and on copies (the Bsdf's
    /// address never leaves the tracer, so the compiler keeps its fields in registers: the photon
    /// stage, docs/performance.md). The direction, pdf, lobe, medium and eta, and the weight
    /// f |wi . ns| / pdf before the roulette and the adjoint; not valid where sample() ends the path.
    struct FramedSample {
        BsdfSample s;
        Rgb weight;
        bool valid = false;
    };
    template <class Uniforms>
    [[gnu::noinline]] static FramedSample sampleFramed(Framed f, HitSide side, MediumId medium, MediumId beyond,
                                                       bool thin, float ior, TransportMode mode, BsdfLobes allowed,
                                                       Uniforms& rng);
    /// at()'s coat (Plastic without its metal part), GGX conductor or rough dielectric at a hit
    /// seen from `side`, shading normal `ns`, `wo` = -dIn: the kind, lobes, frame and component.
    /// `metal`: the metal part was chosen. Everything by value (see at()).
    static Framed buildFramed(const Material& mat, float roughness, Rgb baseColor, bool metal, HitSide side, Vec3 ns,
                              Vec3 wo);

    Kind m_kind = Kind::Diffuse;
    MaterialType m_type = MaterialType::Diffuse;
    TransportMode m_mode = TransportMode::Radiance;
    BsdfLobes m_lobes = 0;
    bool m_shading = false;  ///< ns differs from ng
    HitSide m_side;
    Vec3 m_ng, m_ns;
    Vec3 m_wo;  ///< -dIn, world
    Rgb m_rho;  ///< baseColor: diffuse reflectance, conductor F0, mirror and dielectric tint
    float m_ior = 1.5f;
    bool m_thin = false;  ///< Material::thin
    MediumId m_medium = kVacuum, m_beyond = kVacuum;
    Framed m_framed;  ///< set by at() for the kinds that have a frame
    const Local& local() const { return m_framed.parts.local; }
    const Framed::Component& component() const { return m_framed.component; }
};

template <class Uniforms>
inline Bsdf Bsdf::at(const Scene& scene, const SurfaceHit& hit, const SurfacePoint& sp, const Vec3& dIn,
                     MediumId medium, TransportMode mode, Uniforms& rng) {
    const TriangleMesh& mesh = scene.meshes[size_t(hit.mesh)];
    const Material& mat = scene.materials[size_t(mesh.material)];
    Bsdf b;
    b.m_type = mat.type;
    b.m_mode = mode;
    b.m_side = hitSide(hit, dIn);
    b.m_shading = hasShadingNormal(hit);
    b.m_ng = hit.ng;
    b.m_ns = hit.ns;
    b.m_wo = -dIn;
    b.m_rho = sp.baseColor;
    b.m_ior = mat.ior;
    b.m_thin = mat.thin;
    b.m_medium = medium;
    b.m_beyond = b.m_side.entering ? mesh.interiorMedium : mesh.exteriorMedium;
    // The component choice: one lobe choice for every tracer.
    if (mat.type == MaterialType::Diffuse || (mat.isPartlyTransmissive() && !(rng.uniform() < sp.transmission))) {
        b.m_kind = Kind::Diffuse;
        b.m_lobes = kLobeReflection | kLobeDiffuse;
        return b;
    }
    const bool metal = mat.hasMetalMix() && rng.uniform() < sp.metallic;
    if ((mat.type == MaterialType::Plastic && !metal) || mat.isGlossy() || (metal && mat.isRough())) {
        const Framed framed = buildFramed(mat, sp.roughness, sp.baseColor, metal, b.m_side, b.m_ns, b.m_wo);
        b.m_framed = framed;
        b.m_kind = framed.kind;
        b.m_lobes = framed.lobes;
        return b;
    }
    b.m_kind = Kind::Delta;
    b.m_lobes = mat.type == MaterialType::Interface    ? kLobeTransmission | kLobeSpecular
                : mat.type == MaterialType::Dielectric ? kLobeReflection | kLobeTransmission | kLobeSpecular
                                                       : kLobeReflection | kLobeSpecular;
    return b;
}

inline Rgb Bsdf::f(const Vec3& wi, BsdfLobes lobes) const {
    switch (m_kind) {
        case Kind::Diffuse: {
            if (!(lobes & kLobeDiffuse) || !(dot(wi, m_side.nf) > 0)) return Rgb(0.0f);
            // The light-side direction must be above the shading surface too.
            const Vec3& light = m_mode == TransportMode::Radiance ? wi : m_wo;
            return dot(light, m_side.nsf) > 0 ? m_rho * kInvPi : Rgb(0.0f);
        }
        case Kind::Coated: {
            const Vec3 wiLocal = local().frame.toLocal(wi);
            Rgb f = (lobes & kLobeDiffuse) ? component().coat.evalDiffuse(local().wo, wiLocal) : Rgb(0.0f);
            if (lobes & (kLobeGlossy | kLobeSpecular)) f += Rgb(component().coat.evalSpecular(local().wo, wiLocal));
            return f;
        }
        case Kind::Conductor:
            return (lobes & kLobeGlossy) ? component().metal.eval(local().wo, local().frame.toLocal(wi)) : Rgb(0.0f);
        case Kind::RoughDielectric:
            return (lobes & kLobeGlossy) ? component().glass.eval(local().wo, local().frame.toLocal(wi), m_mode) : Rgb(0.0f);
        case Kind::Delta:
            break;
    }
    return Rgb(0.0f);
}

inline float Bsdf::pdf(const Vec3& wi) const {
    switch (m_kind) {
        case Kind::Diffuse: {
            if (m_mode == TransportMode::Importance) return std::max(dot(wi, m_side.nf), 0.0f) * kInvPi;
            if (m_shading && !(dot(wi, m_side.nf) > 0)) return 0.0f;
            return std::max(dot(wi, m_shading ? m_side.nsf : m_side.nf), 0.0f) * kInvPi;
        }
        case Kind::Coated:
            return component().coat.pdf(local().wo, local().frame.toLocal(wi));
        case Kind::Conductor:
            return component().metal.pdf(local().wo, local().frame.toLocal(wi));
        case Kind::RoughDielectric:
            return component().glass.pdf(local().wo, local().frame.toLocal(wi));
        case Kind::Delta:
            break;
    }
    return 0.0f;
}

inline float Bsdf::pdf(const Vec3& wi, BsdfLobes allowed) const {
    switch (m_kind) {
        case Kind::Diffuse:
            return (allowed & kLobeDiffuse) ? pdf(wi) : 0.0f;
        case Kind::Coated:
            if (allowed & kLobeDiffuse) return pdf(wi);
            return (allowed & (kLobeGlossy | kLobeSpecular))
                       ? component().coat.pdfSpecular(local().wo, local().frame.toLocal(wi))
                       : 0.0f;
        case Kind::Conductor:
        case Kind::RoughDielectric:
            return (allowed & kLobeGlossy) ? pdf(wi) : 0.0f;
        case Kind::Delta:
            break;
    }
    return 0.0f;
}

/// The delta components: `u` chooses between Fresnel reflection and refraction.
inline bool Bsdf::sampleDelta(float u, BsdfSample* s, Rgb* w) const {
    s->lobe = kLobeReflection | kLobeSpecular;
    s->pdf = 0.0f;
    switch (m_type) {
        case MaterialType::Mirror:
        case MaterialType::Plastic:  // the smooth metal part
            s->wi = reflect(m_wo, m_side.nsf);
            *w = m_rho;
            return dot(s->wi, m_side.nf) > 0;
        case MaterialType::Interface:
            s->wi = -m_wo;
            *w = Rgb(1.0f);
            s->medium = m_beyond;
            s->lobe = kLobeTransmission | kLobeSpecular;
            return true;
        case MaterialType::Dielectric: {
            *w = Rgb(1.0f);
            if (m_thin) {
                // The slab's reflectance (internal bounces included); the rest goes straight on.
                if (u < fresnelThinSlab(dot(m_wo, m_ns), m_ior)) {
                    s->wi = reflect(m_wo, m_side.nsf);
                    return dot(s->wi, m_side.nf) > 0;
                }
                s->wi = -m_wo;
                *w = m_rho;
                s->medium = m_beyond;
                s->lobe = kLobeTransmission | kLobeSpecular;
                return true;
            }
            const float F = fresnelDielectric(dot(m_wo, m_ns), m_ior);
            Vec3 wt;
            // Total internal reflection where the shading normal disagrees with F.
            if (u < F || !refract(m_wo, m_ns, m_ior, &wt)) {
                s->wi = reflect(m_wo, m_side.nsf);
                return dot(s->wi, m_side.nf) > 0;
            }
            s->wi = wt;
            *w = m_rho;
            s->eta = m_side.entering ? 1.0f / m_ior : m_ior;
            if (m_mode == TransportMode::Radiance) *w *= s->eta * s->eta;
            s->medium = m_beyond;
            s->lobe = kLobeTransmission | kLobeSpecular;
            return dot(s->wi, m_side.nf) < 0;
        }
        case MaterialType::Diffuse:
            break;
    }
    return false;
}

template <class Uniforms, class Roulette>
inline bool Bsdf::sample(Uniforms& rng, Rgb* beta, BsdfSample* s, BsdfLobes allowed, const Roulette& roulette) const {
    s->medium = m_medium;
    s->eta = 1.0f;
    Rgb w;
    switch (m_kind) {
        case Kind::Diffuse: {
            if (!(allowed & kLobeDiffuse)) return false;
            s->lobe = kLobeReflection | kLobeDiffuse;
            if (m_mode == TransportMode::Importance) {
                // Cosine about the geometric normal; the weight rho max(0, wo.nsf) / (wo.nf) is
                // known before the direction, so the roulette comes first.
                const float ratio = m_shading ? shadingCosineRatio(m_side, m_wo) : 1.0f;
                if (m_shading) *beta *= ratio;
                *beta *= m_rho;
                const float q = roulette(*beta, Rgb(1.0f));
                float invQ = 1.0f;
                if (q >= 0) {
                    if (!(rng.uniform() < q)) return false;
                    invQ = 1.0f / q;
                    *beta *= invQ;
                }
                // The two numbers in one call, in the order the compiler evaluates them (as the
                // photon tracer always has).
                s->wi = Frame(m_side.nf).toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
                s->pdf = std::max(dot(s->wi, m_side.nf), 0.0f) * kInvPi;
                s->weight = m_rho * (ratio * invQ);
                return true;
            }
            // Cosine about the shading normal; below the geometric surface the path ends.
            const Vec3& n = m_shading ? m_side.nsf : m_side.nf;
            s->wi = Frame(n).toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
            if (m_shading && !(dot(s->wi, m_side.nf) > 0)) return false;
            s->pdf = std::max(dot(s->wi, n), 0.0f) * kInvPi;
            w = m_rho;
            break;
        }
        case Kind::Coated:
        case Kind::Conductor:
        case Kind::RoughDielectric: {
            const FramedSample r = sampleFramed(m_framed, m_side, m_medium, m_beyond, m_thin, m_ior, m_mode, allowed, rng);
            if (!r.valid) return false;
            *s = r.s;
            w = r.weight;
            break;
        }
        case Kind::Delta:
            if (!(allowed & kLobeSpecular)) return false;
            if (!sampleDelta(rng.uniform(), s, &w)) return false;
            break;
    }
    const float q = roulette(*beta, w);
    if (q >= 0) {
        if (!(rng.uniform() < q)) return false;
        w *= 1.0f / q;
    }
    if (m_mode == TransportMode::Importance && m_shading) w *= shadingNormalAdjoint(m_ng, m_ns, m_wo, s->wi);
    *beta *= w;
    s->weight = w;
    return true;
}

template <class Uniforms>
Bsdf::FramedSample Bsdf::sampleFramed(Framed f, HitSide side, MediumId medium, MediumId beyond, bool thin, float ior,
                                      TransportMode mode, BsdfLobes allowed, Uniforms& rng) {
    FramedSample r;
    BsdfSample* s = &r.s;
    s->medium = medium;
    s->eta = 1.0f;
    const Local& local = f.parts.local;
    switch (f.kind) {
        case Kind::Coated: {
            const CoatedDiffuse& coat = f.component.coat;
            CoatedSample c;
            if (allowed & kLobeDiffuse) {
                const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
                c = coat.sample(local.wo, u0, u1, u2);
            } else {
                if (!(allowed & (kLobeGlossy | kLobeSpecular))) return r;
                const float u1 = rng.uniform(), u2 = rng.uniform();
                c = coat.sampleSpecular(local.wo, u1, u2);
            }
            if (!c.valid) return r;
            s->wi = normalize(local.frame.toWorld(c.wi));
            s->pdf = c.pdf;
            s->lobe = kLobeReflection | (!c.specular ? kLobeDiffuse : c.delta ? kLobeSpecular : kLobeGlossy);
            if (!(dot(s->wi, side.nf) > 0)) return r;
            r.weight = c.weight;
            break;
        }
        case Kind::Conductor:
        case Kind::RoughDielectric: {
            if (!(allowed & kLobeGlossy)) return r;
            const float u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
            const MicrofacetSample m = f.kind == Kind::Conductor ? f.component.metal.sample(local.wo, u1, u2)
                                                                 : f.component.glass.sample(local.wo, u0, u1, u2, mode);
            if (!m.valid) return r;
            s->wi = normalize(local.frame.toWorld(m.wi));
            s->pdf = m.pdf;
            s->lobe = kLobeGlossy | (m.transmitted ? kLobeTransmission : kLobeReflection);
            if (m.transmitted) {
                s->medium = beyond;
                if (!thin) s->eta = side.entering ? 1.0f / ior : ior;
            }
            if (!(m.transmitted ? dot(s->wi, side.nf) < 0 : dot(s->wi, side.nf) > 0)) return r;
            r.weight = m.weight;
            break;
        }
        case Kind::Diffuse:
        case Kind::Delta:
            return r;
    }
    r.valid = true;
    return r;
}

}  // namespace tyndall
