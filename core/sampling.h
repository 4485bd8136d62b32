#pragma once
// Warps from the unit square to directions and points, each with its pdf (solid angle or area).
#include "core/math.h"

namespace tyndall {

struct Vec2 {
    float x = 0, y = 0;
};

inline Vec3 sampleUniformSphere(float u1, float u2) {
    float z = 1.0f - 2.0f * u1;
    float r = safeSqrt(1.0f - z * z);
    float phi = 2.0f * kPi * u2;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float uniformSpherePdf() { return kInv4Pi; }

/// Direction within `cosThetaMax` of +z, uniform in solid angle.
inline Vec3 sampleUniformCone(float u1, float u2, float cosThetaMax) {
    float cosTheta = 1.0f - u1 * (1.0f - cosThetaMax);
    float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    float phi = 2.0f * kPi * u2;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
inline float uniformConePdf(float cosThetaMax) { return 1.0f / (2.0f * kPi * (1.0f - cosThetaMax)); }

/// Shirley-Chiu concentric map to the unit disk.
inline Vec2 sampleConcentricDisk(float u1, float u2) {
    float a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
    if (a == 0 && b == 0) return {0, 0};
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (kPi / 4.0f) * (b / a);
    } else {
        r = b;
        phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Cosine-weighted direction about +z; pdf = cos(theta) / pi.
inline Vec3 sampleCosineHemisphere(float u1, float u2) {
    Vec2 d = sampleConcentricDisk(u1, u2);
    return {d.x, d.y, safeSqrt(1.0f - d.x * d.x - d.y * d.y)};
}

/// Barycentrics (b1, b2) uniform over a triangle; b0 = 1 - b1 - b2.
inline Vec2 sampleUniformTriangle(float u1, float u2) {
    float su = std::sqrt(u1);
    return {1.0f - su, u2 * su};
}

}  // namespace tyndall
