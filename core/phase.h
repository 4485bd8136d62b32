#pragma once
// Henyey-Greenstein phase function.
//
// Sign convention (tested with g = +/-0.7): `cosTheta` is the cosine between the direction light
// travels BEFORE scattering and the direction it travels AFTER. g > 0 is forward scattering
// (peak at cosTheta = 1), g < 0 backward. In the beam estimator light travels along the beam
// direction w_b and leaves toward the camera, i.e. travels along -w_c: cosTheta = dot(w_b, -w_c).
// Normalised over the sphere: integral of p over all directions = 1 (units 1/sr).
#include "core/math.h"

namespace tyndall {

inline float hgPhase(float cosTheta, float g) {
    float denom = 1.0f + g * g - 2.0f * g * cosTheta;
    return kInv4Pi * (1.0f - g * g) / (denom * std::sqrt(std::max(denom, 1e-12f)));
}

/// Samples the direction light travels after scattering, given `wTravel` before; the pdf equals
/// hgPhase(dot(wTravel, result), g) exactly (so the sampling weight is 1).
inline Vec3 sampleHg(const Vec3& wTravel, float g, float u1, float u2) {
    float cosTheta;
    if (std::abs(g) < 1e-3f) {
        cosTheta = 1.0f - 2.0f * u1;
    } else {
        float sq = (1.0f - g * g) / (1.0f - g + 2.0f * g * u1);
        cosTheta = (1.0f + g * g - sq * sq) / (2.0f * g);
    }
    cosTheta = clampValue(cosTheta, -1.0f, 1.0f);
    float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    float phi = 2.0f * kPi * u2;
    Frame frame(wTravel);
    return frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
}

}  // namespace tyndall
