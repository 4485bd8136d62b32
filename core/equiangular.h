#pragma once
// Equiangular sampling of a point along a ray toward a point light (Kulla and Fajardo, "Importance
// Sampling Techniques for Path Tracing in Participating Media", EGSR 2012), and the stretch of a
// ray inside a spot light's cone. Pure geometry; cpu/equiangular.h builds the estimator on it.
//
// For the ray o + t d (d unit), t in [a, b], and a light at p: with the foot t0 = dot(p - o, d) and
// the distance D = |o + t0 d - p|, t = t0 + D tan(theta), theta uniform between the angles of the
// interval's ends, theta_a = atan((a - t0) / D) and theta_b = atan((b - t0) / D). Its pdf is
//   pdf(t) = D / ((theta_b - theta_a) (D^2 + (t - t0)^2)),
// proportional to 1 / |x(t) - p|^2, so the light's inverse-square falloff divided by the pdf is the
// constant (theta_b - theta_a) / D: bounded however close the ray passes to the light.
#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace tyndall {

struct EquiangularSample {
    float t = 0;    ///< the ray parameter of the point
    float pdf = 0;  ///< its density over t
    /// 1 / (|x(t) - p|^2 pdf(t)) = (theta_b - theta_a) / D, computed without the squares.
    float inverseSquareOverPdf = 0;
};

/// The smallest distance D used for a ray through the light itself (relative to the interval's
/// scale): keeps the angles finite; such rays have probability zero under pixel jitter.
constexpr float kEquiangularMinDistance = 1e-7f;

/// Samples t in [a, b] (a < b) from uniform `u` in [0, 1).
inline EquiangularSample sampleEquiangular(const Vec3& o, const Vec3& d, float a, float b, const Vec3& p, float u) {
    const float t0 = dot(p - o, d);
    const float scale = std::max({std::abs(a), std::abs(b), std::abs(t0), 1e-30f});
    const float D = std::max(length(o + d * t0 - p), kEquiangularMinDistance * scale);
    const float thetaA = std::atan2(a - t0, D), thetaB = std::atan2(b - t0, D);
    const float theta = thetaA + u * (thetaB - thetaA);
    EquiangularSample s;
    s.t = std::clamp(t0 + D * std::tan(theta), a, b);
    const float h = s.t - t0;
    s.inverseSquareOverPdf = (thetaB - thetaA) / D;
    s.pdf = D / ((thetaB - thetaA) * (D * D + h * h));
    return s;
}

/// The ray o + t d (d unit) seen from a point p as an angle: theta(t) = atan((t - t0) / D), with
/// the foot t0 and the distance D as above. Equiangular sampling is uniform in theta; a
/// piecewise-constant weight w(t) times the inverse square is sampled by choosing a piece by
/// w (theta(t1) - theta(t0)) and then theta uniformly inside it (cpu/equiangular.cpp, grid media).
struct EquiangularLine {
    EquiangularLine(const Vec3& o, const Vec3& d, float a, float b, const Vec3& p) {
        t0 = dot(p - o, d);
        const float scale = std::max({std::abs(a), std::abs(b), std::abs(t0), 1e-30f});
        D = std::max(length(o + d * t0 - p), kEquiangularMinDistance * scale);
    }
    double angle(float t) const { return std::atan2(double(t) - t0, double(D)); }
    float at(double theta) const { return float(t0 + D * std::tan(theta)); }
    float t0 = 0;  ///< the foot of p on the line
    float D = 0;   ///< p's distance from the line (at least kEquiangularMinDistance of the scale)
};

/// Clips [*a, *b] to the part of the ray o + t d inside the solid cone of apex `apex`, unit axis
/// `axis` and half-angle acos(cosAngle) (at most 90 degrees: a convex set, so the part is one
/// interval). Returns false when nothing is left.
inline bool clipToCone(const Vec3& o, const Vec3& d, const Vec3& apex, const Vec3& axis, float cosAngle, float* a,
                       float* b) {
    const Vec3 v = o - apex;
    const double c2 = double(cosAngle) * cosAngle;
    const double da = dot(d, axis), va = dot(v, axis), vd = dot(v, d), vv = dot(v, v);
    // Inside: f(t) = (va + t da)^2 - c2 |v + t d|^2 >= 0 and va + t da >= 0.
    const double A = da * da - c2, B = 2 * (va * da - c2 * vd), C = va * va - c2 * vv;
    auto inside = [&](double t) {
        const double along = va + t * da;
        return along >= 0 && along * along - c2 * (vv + 2 * t * vd + t * t) >= 0;
    };
    // The roots split [a, b] into at most three pieces; the cone is convex, so the pieces inside
    // are adjacent. Each piece is tested at its middle.
    double cuts[4] = {*a, *b, *a, *a};
    int n = 2;
    const double disc = B * B - 4 * A * C;
    if (std::abs(A) > 1e-12 && disc >= 0) {
        const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
        const double r1 = q / A, r2 = q != 0 ? C / q : r1;
        for (double r : {r1, r2})
            if (r > *a && r < *b) cuts[n++] = r;
    } else if (std::abs(A) <= 1e-12 && std::abs(B) > 0) {
        const double r = -C / B;
        if (r > *a && r < *b) cuts[n++] = r;
    }
    std::sort(cuts, cuts + n);
    double lo = 0, hi = -1;
    for (int i = 0; i + 1 < n; ++i) {
        if (!(cuts[i + 1] > cuts[i]) || !inside(0.5 * (cuts[i] + cuts[i + 1]))) continue;
        if (hi < lo) lo = cuts[i];
        hi = cuts[i + 1];
    }
    if (!(hi > lo)) return false;
    *a = float(lo);
    *b = float(hi);
    return *b > *a;
}

}  // namespace tyndall
