#pragma once
// The beam x ray 1D estimator ("beam radiance estimate", Jarosz et al. 2011), shared verbatim by
// the CPU gather and the CPU beam rasterizer; gpu/shaders/beam_estimator.glsl is its GLSL twin
// (tests/gpu/estimator_parity_test.cpp runs both on the same inputs).
//
// For a camera segment x_c + s w_c, s in [0, sMax], and a beam x_b + t w_b, t in [0, tMax]:
//   L += k_r(u) sigma_s(x_w) Phi_b Tr_cam(0->s_w) Tr_beam(0->t_v) p(theta) / sin(theta)
// with (s_w, t_v) the parameters of the closest points of the two lines, u their distance,
// theta the angle between w_c and w_b, and p the HG phase for light travelling along w_b and
// leaving toward the camera (cosine dot(w_b, -w_c)). Contributes only when u < r,
// 0 <= s_w <= sMax and 0 <= t_v <= tMax.
//
// Kernel: the normalised 1D biweight k_r(u) = 15/(16 r) (1 - (u/r)^2)^2, |u| < r.
//
// Near-parallel lines (sin theta -> 0): 1/sin(theta) is integrable but has infinite variance, and
// the closest points become ill-conditioned. Lines with sin(theta) < 1e-6 are skipped (their
// closest points are undefined), and 1/sin(theta) is clamped to 1/kMinSinTheta = 1000 (angles
// under 0.057 degrees). The clamp biases only pairs within 0.057 degrees of parallel, a set of
// directions of measure ~1e-6 of the sphere, and bounds the fireflies they would cause.
#include "core/math.h"
#include "core/phase.h"
#include "core/photon_beam.h"

namespace tyndall {

constexpr float kMinSinTheta = 1e-3f;

/// Closest approach of a camera segment and a beam.
struct BeamRayHit {
    float u = 0;            ///< distance between the two lines
    float s = 0;            ///< s_w: parameter along the camera segment
    float t = 0;            ///< t_v: parameter along the beam
    float invSinTheta = 0;  ///< 1/sin(theta), clamped
    float cosTheta = 0;     ///< dot(w_c, w_b)
};

/// Normalised 1D biweight kernel of radius r (integrates to 1 over u in (-r, r)).
inline float beamKernel(float u, float r) {
    float x = u / r;
    float a = 1.0f - x * x;
    return a > 0.0f ? (15.0f / 16.0f) * a * a / r : 0.0f;
}

/// Closest approach of camera segment (xc, wc, [0, sMax]) and `beam`; false when the beam does not
/// contribute (u >= radius, closest points outside either segment, or lines parallel).
inline bool intersectBeamRay(const Vec3& xc, const Vec3& wc, float sMax, const PhotonBeam& beam, BeamRayHit* hit) {
    Vec3 w0 = xc - beam.origin;
    float b = dot(wc, beam.dir);
    float sin2 = 1.0f - b * b;
    if (sin2 < 1e-12f) return false;
    float d = dot(wc, w0);
    float e = dot(beam.dir, w0);
    float s = (b * e - d) / sin2;
    float t = (e - b * d) / sin2;
    if (s < 0.0f || s > sMax || t < 0.0f || t > beam.tMax) return false;
    Vec3 between = w0 + wc * s - beam.dir * t;
    float u2 = dot(between, between);
    if (u2 >= beam.radius * beam.radius) return false;
    hit->u = std::sqrt(u2);
    hit->s = s;
    hit->t = t;
    hit->cosTheta = b;
    hit->invSinTheta = 1.0f / std::max(std::sqrt(sin2), kMinSinTheta);
    return true;
}

/// The estimator's value for one beam, given the transmittances along camera segment (0 -> s_w)
/// and beam (0 -> t_v) and sigma_s at the gather point x_w. Radiance toward the camera, before
/// the camera path's own throughput.
inline Rgb beamRadiance(const BeamRayHit& hit, const PhotonBeam& beam, const Rgb& sigmaS, float g,
                        const Rgb& trCam, const Rgb& trBeam) {
    float k = beamKernel(hit.u, beam.radius) * hgPhase(-hit.cosTheta, g) * hit.invSinTheta;
    return sigmaS * beam.power * trCam * trBeam * k;
}

}  // namespace tyndall
