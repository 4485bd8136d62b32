#pragma once
// Rough surfaces: the GGX (Trowbridge-Reitz) microfacet distribution with the height-correlated
// Smith masking-shadowing term, sampled by its distribution of visible normals (Heitz, "Sampling
// the GGX Distribution of Visible Normals", JCGT 2018), and the two BSDFs built from it:
//   - a rough conductor (glTF metallic = 1): f = F_Schlick(baseColor) D G / (4 |cos_o cos_i|);
//   - a rough dielectric interface (KHR_materials_transmission with roughness): Walter et al.,
//     "Microfacet Models for Refraction through Rough Surfaces" (EGSR 2007), reflection chosen
//     with probability F, transmission with 1 - F, tinted by baseColor.
// Everything is in the local shading frame: +z is the surface normal pointing to the mesh exterior,
// eta = n_interior / n_exterior. Directions point away from the surface. glTF's perceptual
// roughness r maps to alpha = r^2 (clamped to kMinAlpha; below kSmoothRoughness the renderers
// keep the exact delta lobes: Material::isGlossy()).
// Single scattering only: energy lost to multiple bounces between microfacets (up to ~40% for a
// white conductor at alpha = 1 and grazing view) is not restored.
#include <cmath>

#include "core/fresnel.h"
#include "core/math.h"
#include "core/transport_mode.h"

namespace tyndall {

struct Ggx {
    static constexpr float kMinAlpha = 1e-3f;
    float alpha = 0.5f;

    static Ggx fromRoughness(float roughness) { return {std::max(roughness * roughness, kMinAlpha)}; }

    /// Normal distribution D(wm), wm in the upper hemisphere.
    float D(const Vec3& wm) const {
        float cos2 = wm.z * wm.z;
        if (!(cos2 > 0)) return 0.0f;
        float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
        float a2 = alpha * alpha;
        float e = 1.0f + tan2 / a2;
        return 1.0f / (kPi * a2 * cos2 * cos2 * e * e);
    }
    /// Smith's Lambda for direction w.
    float lambda(const Vec3& w) const {
        float cos2 = w.z * w.z;
        if (!(cos2 > 0)) return kInfinity;
        float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
        return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
    }
    float G1(const Vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
    /// Height-correlated masking-shadowing.
    float G(const Vec3& wo, const Vec3& wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }
    /// Density of visible normals seen from w, on either side: G1(w) max(0, w'.wm) D(wm) / |w.z|
    /// with w' = w flipped to the upper hemisphere (wm is always there; from below the surface the
    /// visible microfacets are those facing -w). Integrates to 1 over wm for every w.
    float visibleD(const Vec3& w, const Vec3& wm) const {
        float c = std::abs(w.z);
        float cosM = w.z < 0 ? -dot(w, wm) : dot(w, wm);
        return c > 0 ? G1(w) * std::max(0.0f, cosM) * D(wm) / c : 0.0f;
    }
    /// Samples a visible normal from w with density visibleD(w, .) (either hemisphere: sampled as
    /// seen from the side w is on; the result is in the upper hemisphere).
    Vec3 sampleVisibleNormal(Vec3 w, float u1, float u2) const {
        if (w.z < 0) w = -w;
        Vec3 vh = normalize(Vec3(alpha * w.x, alpha * w.y, w.z));
        float lensq = vh.x * vh.x + vh.y * vh.y;
        Vec3 t1 = lensq > 0 ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : Vec3(1, 0, 0);
        Vec3 t2 = cross(vh, t1);
        float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
        float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
        float s = 0.5f * (1.0f + vh.z);
        p2 = (1.0f - s) * safeSqrt(1.0f - p1 * p1) + s * p2;
        Vec3 nh = t1 * p1 + t2 * p2 + vh * safeSqrt(1.0f - p1 * p1 - p2 * p2);
        return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
    }
};

inline Rgb fresnelSchlick(const Rgb& f0, float cosTheta) {
    float m = std::pow(clampValue(1.0f - std::abs(cosTheta), 0.0f, 1.0f), 5.0f);
    return f0 + (Rgb(1.0f) - f0) * m;
}

/// A sampled direction: wi, f * |cos_i| / pdf, pdf (solid angle), and whether it was transmitted.
struct MicrofacetSample {
    Vec3 wi;
    Rgb weight;
    float pdf = 0;
    bool transmitted = false;
    bool valid = false;
};

/// Rough conductor with Schlick Fresnel F0 = `f0` (glTF: baseColor of a metal).
struct RoughConductor {
    Ggx ggx;
    Rgb f0{1.0f};

    Rgb eval(const Vec3& wo, const Vec3& wi) const {
        if (wo.z <= 0 || wi.z <= 0) return Rgb(0.0f);
        Vec3 wm = wo + wi;
        if (!(lengthSquared(wm) > 0)) return Rgb(0.0f);
        wm = normalize(wm);
        return fresnelSchlick(f0, dot(wo, wm)) * (ggx.D(wm) * ggx.G(wo, wi) / (4.0f * wo.z * wi.z));
    }
    float pdf(const Vec3& wo, const Vec3& wi) const {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        Vec3 wm = wo + wi;
        if (!(lengthSquared(wm) > 0)) return 0.0f;
        wm = normalize(wm);
        return ggx.visibleD(wo, wm) / (4.0f * std::abs(dot(wo, wm)));
    }
    MicrofacetSample sample(const Vec3& wo, float u1, float u2) const {
        MicrofacetSample s;
        if (wo.z <= 0) return s;
        Vec3 wm = ggx.sampleVisibleNormal(wo, u1, u2);
        s.wi = reflect(wo, wm);
        if (s.wi.z <= 0) return s;
        s.pdf = pdf(wo, s.wi);
        if (!(s.pdf > 0)) return s;
        s.weight = eval(wo, s.wi) * (s.wi.z / s.pdf);
        s.valid = true;
        return s;
    }
};

/// Rough dielectric interface with relative index `eta` (interior over exterior) and a tint on
/// the transmitted lobe.
///
/// `thin`: a thin rough sheet instead (Material::thin with roughness; a frosted pane, the same
/// medium index on both sides, no refraction). A visible microfacet wm is drawn as for the
/// interface; the sheet reflects about it with the thin slab's reflectance R'(wo . wm)
/// (fresnelThinSlab: the first face and the internal bounces), and the rest, 1 - R' times the tint,
/// crosses the sheet along that reflection mirrored through the sheet's plane (z negated):
///   f_r = R'(wo.h) D(h) G(wo, wi) / (4 |wo.z wi.z|),  h = the half vector of wo and wi;
///   f_t = tint (1 - R'(wo.h)) D(h) G(wo, wi) / (4 |wo.z wi.z|),  h = that of wo and wi mirrored.
/// An approximation: the transmitted light spreads as widely as the reflected (as through a pane
/// whose two faces are rough), not by the smaller angle one rough face refracts it; it is
/// reciprocal (no eta^2 in either mode), its albedo is the GGX single-scattering albedo with
/// F = 1 (a white sheet loses only what G masks; RoughConductor's with f0 = 1), and as the
/// roughness goes to 0 it becomes the smooth thin sheet (R' mirrored, 1 - R' straight through).
struct RoughDielectric {
    Ggx ggx;
    float eta = 1.5f;
    Rgb tint{1.0f};
    bool thin = false;

    /// The generalized half vector of (wo, wi), in the upper hemisphere, and eta' (the index ratio
    /// across the surface seen from wo: eta when wo is outside). False for configurations with no
    /// microfacet (back-facing).
    bool halfVector(const Vec3& wo, const Vec3& wi, Vec3* wm, float* etap) const {
        bool reflect = wo.z * wi.z > 0;
        *etap = reflect ? 1.0f : (wo.z > 0 ? eta : 1.0f / eta);
        Vec3 h = wi * *etap + wo;
        if (!(lengthSquared(h) > 0) || wo.z == 0 || wi.z == 0) return false;
        h = normalize(h);
        if (h.z < 0) h = -h;
        if (dot(h, wi) * wi.z < 0 || dot(h, wo) * wo.z < 0) return false;
        *wm = h;
        return true;
    }

    Rgb eval(const Vec3& wo, const Vec3& wi, TransportMode mode) const {
        if (thin) return evalThin(wo, wi);
        Vec3 wm;
        float etap;
        if (!halfVector(wo, wi, &wm, &etap)) return Rgb(0.0f);
        float F = fresnelDielectric(dot(wo, wm), eta);
        if (wo.z * wi.z > 0) return Rgb(ggx.D(wm) * ggx.G(wo, wi) * F / std::abs(4.0f * wi.z * wo.z));
        float denom = dot(wi, wm) + dot(wo, wm) / etap;
        denom = denom * denom * wi.z * wo.z;
        float ft = ggx.D(wm) * (1.0f - F) * ggx.G(wo, wi) * std::abs(dot(wi, wm) * dot(wo, wm) / denom);
        if (mode == TransportMode::Radiance) ft /= etap * etap;
        return tint * ft;
    }
    float pdf(const Vec3& wo, const Vec3& wi) const {
        if (thin) return pdfThin(wo, wi);
        Vec3 wm;
        float etap;
        if (!halfVector(wo, wi, &wm, &etap)) return 0.0f;
        float R = fresnelDielectric(dot(wo, wm), eta), T = 1.0f - R;
        if (wo.z * wi.z > 0) return ggx.visibleD(wo, wm) / (4.0f * std::abs(dot(wo, wm))) * R;
        float denom = dot(wi, wm) + dot(wo, wm) / etap;
        float dwmdwi = std::abs(dot(wi, wm)) / (denom * denom);
        return ggx.visibleD(wo, wm) * dwmdwi * T;
    }
    MicrofacetSample sample(const Vec3& wo, float uLobe, float u1, float u2, TransportMode mode) const {
        MicrofacetSample s;
        if (wo.z == 0) return s;
        Vec3 wm = ggx.sampleVisibleNormal(wo, u1, u2);
        if (thin) return sampleThin(wo, wm, uLobe);
        float R = fresnelDielectric(dot(wo, wm), eta);
        if (uLobe < R) {
            s.wi = reflect(wo, wm);
            if (!(wo.z * s.wi.z > 0)) return s;
        } else {
            // refract() takes either side: wo . wm < 0 (wo inside) flips eta and the normal.
            if (!refract(wo, wm, eta, &s.wi) || !(wo.z * s.wi.z < 0)) return s;
            s.transmitted = true;
        }
        s.pdf = pdf(wo, s.wi);
        if (!(s.pdf > 0)) return s;
        s.weight = eval(wo, s.wi, mode) * (std::abs(s.wi.z) / s.pdf);
        s.valid = isFinite(s.weight);
        return s;
    }

private:
    static Vec3 mirrored(const Vec3& w) { return {w.x, w.y, -w.z}; }
    /// The thin sheet's half vector for (wo, wi), in the upper hemisphere (wi mirrored to wo's side
    /// when it crossed the sheet). False when wo or wi lies in the sheet's plane.
    static bool thinHalfVector(const Vec3& wo, const Vec3& wi, Vec3* h) {
        if (wo.z == 0 || wi.z == 0) return false;
        const Vec3 w = wo.z * wi.z > 0 ? wi : mirrored(wi);
        Vec3 m = wo + w;
        if (!(lengthSquared(m) > 0)) return false;
        m = normalize(m);
        *h = m.z < 0 ? -m : m;
        return true;
    }
    Rgb evalThin(const Vec3& wo, const Vec3& wi) const {
        Vec3 h;
        if (!thinHalfVector(wo, wi, &h)) return Rgb(0.0f);
        const float R = fresnelThinSlab(dot(wo, h), eta);
        const float common = ggx.D(h) * ggx.G(wo, wi) / std::abs(4.0f * wo.z * wi.z);
        return wo.z * wi.z > 0 ? Rgb(R * common) : tint * ((1.0f - R) * common);
    }
    float pdfThin(const Vec3& wo, const Vec3& wi) const {
        Vec3 h;
        if (!thinHalfVector(wo, wi, &h)) return 0.0f;
        const float R = fresnelThinSlab(dot(wo, h), eta);
        return ggx.visibleD(wo, h) / (4.0f * std::abs(dot(wo, h))) * (wo.z * wi.z > 0 ? R : 1.0f - R);
    }
    MicrofacetSample sampleThin(const Vec3& wo, const Vec3& wm, float uLobe) const {
        MicrofacetSample s;
        const Vec3 wr = reflect(wo, wm);
        if (!(wo.z * wr.z > 0)) return s;
        s.transmitted = !(uLobe < fresnelThinSlab(dot(wo, wm), eta));
        s.wi = s.transmitted ? mirrored(wr) : wr;
        s.pdf = pdfThin(wo, s.wi);
        if (!(s.pdf > 0)) return s;
        s.weight = evalThin(wo, s.wi) * (std::abs(s.wi.z) / s.pdf);
        s.valid = isFinite(s.weight);
        return s;
    }
};

}  // namespace tyndall
