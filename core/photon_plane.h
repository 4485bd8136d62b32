#pragma once
// Photon planes (Bitterli and Jarosz 2017, "Beyond Points and Beams", the 0D-blur plane): the
// estimator of the light a photon path scatters once more in a homogeneous medium before a camera
// segment scatters it toward the camera, without a kernel.
//
// A photon beam x_0 + a w_1, a in [0, A] (its length to the next surface), power Phi at x_0, is
// joined with a direction w_2 drawn from the phase function at w_1 and a length B drawn below: the
// parallelogram x_0 + a w_1 + b w_2, a in [0, A], b in [0, B], stands for every path that scatters
// anywhere on the beam into w_2 and travels on along w_2. A camera segment x_c + s w_c, s in
// [0, sMax], meets it in at most one point (a, b, s); the light it scatters toward the camera there
//
//   L = Phi Tr(a) sigma_s Tr(b) / P(B > b) sigma_s p(w_2 . -w_c) Tr_cam(s) V(x_1, x_2) / |det(w_1, w_2, w_c)|
//
// (x_1 = x_0 + a w_1, x_2 = x_c + s w_c; the phase at x_1 cancels against w_2's pdf; V: no surface
// between x_1 and x_2; 1/|det| is the Jacobian of (a, b, s) -> x_0 + a w_1 + b w_2 - x_c - s w_c).
// B is exponential with the smallest channel's sigma_t, so Tr(b) / P(B > b) = exp(-(sigma_t -
// min sigma_t) b) <= 1, and B is capped at the scene's diagonal (no two points of a medium are
// farther apart). Its expectation over w_2 and B is exactly the expectation of the beam of the
// segment after a scattering on that beam (the photon tracer then stores no such beam): the
// integral over where on the beam it scatters is done analytically, so no blur and no radius.
//
// Grazing camera rays (|det| -> 0) make the estimator's variance infinite (logarithmically): 1/|det|
// is clamped at 1/kMinPlaneDet. The clamp biases only rays within 0.057 degrees of the plane, a
// relative share of about kMinPlaneDet / 2 of the planes' light.
#include <cmath>
#include <cstdint>

#include "core/math.h"
#include "core/medium.h"
#include "core/phase.h"

namespace tyndall {

constexpr float kMinPlaneDet = 1e-3f;

/// One photon plane: the beam (origin, dir1, len1) swept along dir2 for len2.
struct PhotonPlane {
    Vec3 origin;
    float len1 = 0;  ///< A: the beam's length (to the next surface)
    Vec3 dir1;       ///< w_1, unit
    float len2 = 0;  ///< B: the sampled length along w_2
    Vec3 dir2;       ///< w_2, unit
    MediumId medium = kVacuum;
    Rgb power;       ///< Phi: the beam's power at its origin (as PhotonBeam::power)
    /// The index of the w_2 segment on its photon path (1 = straight from the light), for
    /// RenderSettings::maxPathLength: the beam's index + 1.
    uint16_t segment = 0;
};

/// Where a camera segment meets a plane.
struct PlaneRayHit {
    float a = 0, b = 0, s = 0;  ///< along w_1, w_2 and the camera segment
    float invDet = 0;           ///< 1 / |det(w_1, w_2, w_c)|, clamped
    float cosTheta = 0;         ///< dot(w_2, w_c)
};

/// The point where camera segment (xc, wc, [0, sMax]) crosses `plane`; false when it misses the
/// parallelogram or the segment, or the two are parallel.
inline bool intersectPlaneRay(const Vec3& xc, const Vec3& wc, float sMax, const PhotonPlane& plane, PlaneRayHit* hit) {
    const Vec3 n = cross(plane.dir1, plane.dir2);
    const float n2 = dot(n, n);
    const float det = dot(n, wc);
    if (n2 < 1e-12f || det == 0.0f) return false;
    const Vec3 toOrigin = plane.origin - xc;
    const float s = dot(n, toOrigin) / det;
    if (!(s >= 0.0f && s <= sMax)) return false;
    const Vec3 q = xc + wc * s - plane.origin;
    const float a = dot(q, cross(plane.dir2, n)) / n2;
    const float b = dot(q, cross(n, plane.dir1)) / n2;
    if (!(a >= 0.0f && a <= plane.len1 && b >= 0.0f && b <= plane.len2)) return false;
    hit->a = a;
    hit->b = b;
    hit->s = s;
    hit->invDet = 1.0f / std::max(std::fabs(det), kMinPlaneDet);
    hit->cosTheta = dot(plane.dir2, wc);
    return true;
}

/// The plane's light toward the camera at `hit` in the homogeneous medium `med`, before the
/// visibility between x_1 and x_2 (the caller's shadow ray) and the camera path's throughput.
inline Rgb planeRadiance(const PlaneRayHit& hit, const PhotonPlane& plane, const Medium& med) {
    const Rgb st = med.sigmaT();
    const float stMin = std::min(st.r, std::min(st.g, st.b));
    auto tr = [&](float c) { return std::exp(-c * (hit.a + hit.s) - (c - stMin) * hit.b); };
    const Rgb attenuation(tr(st.r), tr(st.g), tr(st.b));
    return plane.power * med.sigmaS * med.sigmaS * attenuation * (hgPhase(-hit.cosTheta, med.g) * hit.invDet);
}

/// The length B along w_2 for medium `med` from a uniform number u in [0, 1): exponential with the
/// smallest channel's sigma_t, capped at `cap` (the scene's diagonal).
inline float samplePlaneLength(const Medium& med, float cap, float u) {
    const Rgb st = med.sigmaT();
    const float stMin = std::min(st.r, std::min(st.g, st.b));
    if (!(stMin > 0.0f)) return cap;
    return std::min(cap, -std::log1p(-u) / stMin);
}

}  // namespace tyndall
