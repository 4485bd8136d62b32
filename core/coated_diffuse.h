#pragma once
// The dielectric specular layer over diffuse (glTF's metallic-roughness model for non-metals:
// plastic, varnish, paint): a GGX reflection lobe with the exact dielectric Fresnel at the coat's
// index `eta` (KHR_materials_ior, 1.5 by default), over a diffuse base that receives what the
// coat transmits, in the local shading frame (+z the normal on the side light arrives from):
//
//   f_s(wo, wi) = F(wo . wm) D(wm) G(wo, wi) / (4 cos_o cos_i)            (wm the half vector)
//   f_d(wo, wi) = rho/pi (1 - F(cos_o)) (1 - F(cos_i)) / (1 - F_avg)
//
// F_avg = 2 int_0^1 F(mu) mu dmu is the hemispherical average of the Fresnel reflectance
// (fresnelDielectricAverage). f_d is symmetric in (wo, wi), so the BSDF is reciprocal, and the
// 1/(1 - F_avg) normalisation makes the diffuse part's albedo exactly rho (1 - F(cos_o)): with a
// smooth coat (delta reflection of weight F(cos_o)) a white base reflects exactly everything (the
// white furnace gives 1 for every view). A rough coat loses what single-scattering GGX loses (the
// microfacet shadowing, as RoughConductor) and the difference between F(cos_o) and the lobe's
// Fresnel over its microfacets; tests/core/coated_diffuse_test.cpp measures the albedo: <= 1 for
// every view and roughness, and >= 0.9 except at grazing views of rough coats.
// What it leaves out (as Cycles' principled BSDF and Mitsuba's roughplastic do not): light
// bouncing between the base and the underside of the coat (the (1 - F_avg) in the normalisation
// stands in for it), and absorption in the coat.
//
// Smooth coats (roughness <= Material::kSmoothRoughness) keep the exact delta reflection: `smooth`
// makes f_s a delta of weight F(cos_o) and pdf() the diffuse part only.
//
// Lobe selection: sample() chooses the specular lobe with probability
//   P_s(wo) = F(cos_o) / (F(cos_o) + (1 - F(cos_o)) mean(rho)),
// each lobe's expected weight, and returns f cos / pdf with the mixture pdf
// P_s pdf_s + (1 - P_s) cos_i / pi (what multiple importance sampling needs).
#include <cmath>

#include "core/fresnel.h"
#include "core/math.h"
#include "core/microfacet.h"
#include "core/sampling.h"

namespace tyndall {

/// 2 int_0^1 F(mu, eta) mu dmu (light arriving from outside, eta = n_coat / n_outside): 0.092 at
/// eta 1.5 (eta >= 1: F is smooth in mu). 16-point Gauss-Legendre, accurate to ~1e-5 (tested
/// against a fine midpoint sum); the last value is kept per thread, so a scene's few indices cost
/// the quadrature about once.
inline float fresnelDielectricAverage(float eta) {
    thread_local float lastEta = -1.0f, lastAverage = 0.0f;
    if (eta == lastEta) return lastAverage;
    static constexpr double x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                    0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
    static constexpr double w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025, 0.1495959888165767,
                                    0.1246289712555339, 0.0951585116824928, 0.0622535239386479, 0.0271524594117541};
    double sum = 0;
    for (int k = 0; k < 8; ++k)
        for (double mu : {0.5 * (1.0 - x[k]), 0.5 * (1.0 + x[k])})
            sum += w[k] * mu * double(fresnelDielectric(float(mu), eta));  // 2 x (w/2) x F mu
    lastEta = eta;
    lastAverage = float(sum);
    return lastAverage;
}

/// A sampled direction of the coated BSDF (see MicrofacetSample); `delta`: the smooth coat's
/// mirror direction (its pdf is a delta: not usable for MIS).
struct CoatedSample {
    Vec3 wi;
    Rgb weight;
    float pdf = 0;
    bool specular = false;
    bool delta = false;
    bool valid = false;
};

struct CoatedDiffuse {
    Ggx ggx;
    bool smooth = false;  ///< delta coat (roughness <= Material::kSmoothRoughness)
    float eta = 1.5f;
    Rgb rho{0.8f};
    float fresnelAverage = 0.0f;  ///< fresnelDielectricAverage(eta)

    static CoatedDiffuse make(float roughness, bool smooth, float eta, const Rgb& rho) {
        return {Ggx::fromRoughness(roughness), smooth, eta, rho, fresnelDielectricAverage(eta)};
    }

    float fresnel(float cosTheta) const { return fresnelDielectric(cosTheta, eta); }

    /// f_d (zero unless both directions are above the surface).
    Rgb evalDiffuse(const Vec3& wo, const Vec3& wi) const {
        if (wo.z <= 0 || wi.z <= 0) return Rgb(0.0f);
        return rho * (kInvPi * (1.0f - fresnel(wo.z)) * (1.0f - fresnel(wi.z)) / (1.0f - fresnelAverage));
    }
    /// f_s of a rough coat (0 for a smooth one: its delta is not a function).
    float evalSpecular(const Vec3& wo, const Vec3& wi) const {
        if (smooth || wo.z <= 0 || wi.z <= 0) return 0.0f;
        Vec3 wm = wo + wi;
        if (!(lengthSquared(wm) > 0)) return 0.0f;
        wm = normalize(wm);
        return fresnel(dot(wo, wm)) * ggx.D(wm) * ggx.G(wo, wi) / (4.0f * wo.z * wi.z);
    }
    Rgb eval(const Vec3& wo, const Vec3& wi) const { return evalDiffuse(wo, wi) + Rgb(evalSpecular(wo, wi)); }

    float specularProbability(const Vec3& wo) const {
        float f = fresnel(std::max(wo.z, 0.0f));
        float d = (1.0f - f) * (rho.r + rho.g + rho.b) / 3.0f;
        return f + d > 0 ? f / (f + d) : 1.0f;
    }
    /// The specular lobe's own pdf (visible normals, reflection), 0 for a smooth coat.
    float pdfSpecular(const Vec3& wo, const Vec3& wi) const {
        if (smooth || wo.z <= 0 || wi.z <= 0) return 0.0f;
        Vec3 wm = wo + wi;
        if (!(lengthSquared(wm) > 0)) return 0.0f;
        wm = normalize(wm);
        return ggx.visibleD(wo, wm) / (4.0f * std::abs(dot(wo, wm)));
    }
    /// The mixture pdf sample() draws from (the non-delta part for a smooth coat).
    float pdf(const Vec3& wo, const Vec3& wi) const {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        float ps = specularProbability(wo);
        return ps * pdfSpecular(wo, wi) + (1.0f - ps) * wi.z * kInvPi;
    }

    /// One direction from the mixture: weight = f cos / pdf (the full f: both lobes).
    CoatedSample sample(const Vec3& wo, float uLobe, float u1, float u2) const {
        CoatedSample s;
        if (wo.z <= 0) return s;
        const float ps = specularProbability(wo);
        if (uLobe < ps) {
            s.specular = true;
            if (smooth) {
                s.wi = Vec3(-wo.x, -wo.y, wo.z);
                s.weight = Rgb(fresnel(wo.z) / ps);
                s.pdf = ps;
                s.delta = true;
                s.valid = true;
                return s;
            }
            s.wi = reflect(wo, ggx.sampleVisibleNormal(wo, u1, u2));
        } else {
            s.wi = sampleCosineHemisphere(u1, u2);
        }
        if (!(s.wi.z > 0)) return s;
        s.pdf = pdf(wo, s.wi);
        if (!(s.pdf > 0)) return s;
        s.weight = eval(wo, s.wi) * (s.wi.z / s.pdf);
        s.valid = isFinite(s.weight);
        return s;
    }

    /// The specular lobe alone: weight = f_s cos / pdf_s (F(cos_o) for a smooth coat, its delta).
    CoatedSample sampleSpecular(const Vec3& wo, float u1, float u2) const {
        CoatedSample s;
        s.specular = true;
        if (wo.z <= 0) return s;
        if (smooth) {
            s.wi = Vec3(-wo.x, -wo.y, wo.z);
            s.weight = Rgb(fresnel(wo.z));
            s.pdf = 1.0f;
            s.delta = true;
            s.valid = true;
            return s;
        }
        s.wi = reflect(wo, ggx.sampleVisibleNormal(wo, u1, u2));
        if (!(s.wi.z > 0)) return s;
        s.pdf = pdfSpecular(wo, s.wi);
        if (!(s.pdf > 0)) return s;
        s.weight = Rgb(evalSpecular(wo, s.wi) * s.wi.z / s.pdf);
        s.valid = isFinite(s.weight);
        return s;
    }
};

}  // namespace tyndall
