#pragma once
// Smooth dielectric interface: unpolarised Fresnel reflectance and Snell refraction.
#include "core/math.h"

namespace tyndall {

/// Fresnel reflectance for light arriving with cosine `cosThetaI` (> 0: on the side the normal
/// points to) at an interface with relative IOR `eta` = n_inside / n_outside. Returns 1 on total
/// internal reflection.
inline float fresnelDielectric(float cosThetaI, float eta) {
    cosThetaI = clampValue(cosThetaI, -1.0f, 1.0f);
    if (cosThetaI < 0) {
        eta = 1.0f / eta;
        cosThetaI = -cosThetaI;
    }
    float sin2ThetaI = 1.0f - cosThetaI * cosThetaI;
    float sin2ThetaT = sin2ThetaI / (eta * eta);
    if (sin2ThetaT >= 1.0f) return 1.0f;
    float cosThetaT = safeSqrt(1.0f - sin2ThetaT);
    float rParl = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
    float rPerp = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
    return 0.5f * (rParl * rParl + rPerp * rPerp);
}

/// Reflectance of a thin slab of relative index `eta` (both faces parallel, the same medium on both
/// sides) for light arriving with cosine `cosThetaI` from either side: the first face's Fresnel R
/// plus the light that enters and leaves after 1, 3, 5, ... internal reflections,
/// R' = R + T^2 R / (1 - R^2) with T = 1 - R (R is the same at the inner faces by reciprocity). The
/// slab transmits 1 - R' (no absorption); 1 where the first face reflects totally (eta < 1).
inline float fresnelThinSlab(float cosThetaI, float eta) {
    const float R = fresnelDielectric(std::abs(cosThetaI), eta);
    if (!(R < 1.0f)) return 1.0f;
    const float T = 1.0f - R;
    return R + T * T * R / (1.0f - R * R);
}

/// Mirror `wo` (pointing away from the surface) about `n`.
inline Vec3 reflect(const Vec3& wo, const Vec3& n) { return -wo + n * (2.0f * dot(wo, n)); }

/// Refracts `wo` (pointing away from the surface, on either side) through normal `n` with
/// eta = n_inside / n_outside, inside being the side opposite to `n`. Returns false on TIR.
inline bool refract(const Vec3& wo, Vec3 n, float eta, Vec3* wt) {
    float cosThetaI = dot(n, wo);
    if (cosThetaI < 0) {
        eta = 1.0f / eta;
        cosThetaI = -cosThetaI;
        n = -n;
    }
    float sin2ThetaI = std::max(0.0f, 1.0f - cosThetaI * cosThetaI);
    float sin2ThetaT = sin2ThetaI / (eta * eta);
    if (sin2ThetaT >= 1.0f) return false;
    float cosThetaT = safeSqrt(1.0f - sin2ThetaT);
    *wt = normalize(-wo / eta + n * (cosThetaI / eta - cosThetaT));
    return true;
}

}  // namespace tyndall
