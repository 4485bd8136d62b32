#pragma once
// A BVH over photon points in dense media (core/photon_beam.h MediumPoint,
// RenderSettings::mediumPointMfp) for the camera segments' gather: finds every point within its
// radius of a segment. Each point is an Embree user primitive (its radius's box); the primitive's
// intersection callback records the point when the segment passes within its radius, and reports
// no hit, so one traversal finds them all. Thread-safe queries after construction.
#include <embree3/rtcore.h>

#include <vector>

#include "core/photon_beam.h"
#include "core/scene.h"
#include "cpu/embree_scene.h"

namespace tyndall {

inline constexpr float kPointBoundaryReach = 4.0f;

class PointBvh {
public:
    /// Keeps a reference to `points`: they must outlive the BVH.
    PointBvh(const EmbreeDevice& device, const std::vector<MediumPoint>& points);
    ~PointBvh();
    PointBvh(const PointBvh&) = delete;
    PointBvh& operator=(const PointBvh&) = delete;

    /// The indices of the points whose distance to the segment o + s d, s in [0, sMax] (d unit), is
    /// under their radius with the closest point's s in [0, sMax], ascending (so sums over them
    /// are deterministic). `found` is cleared first.
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found) const;

    const std::vector<MediumPoint>& points() const { return m_points; }
    /// The largest radius of the points.
    float maxRadius() const { return m_maxRadius; }

private:
    const std::vector<MediumPoint>& m_points;
    RTCScene m_scene = nullptr;
    float m_maxRadius = 0;
};

/// The normalised 2D biweight kernel of radius r: 3 / (pi r^2) (1 - (u/r)^2)^2, |u| < r.
inline float pointKernel(float u2, float r) {
    const float a = 1.0f - u2 / (r * r);
    return a > 0.0f ? (3.0f * kInvPi) * a * a / (r * r) : 0.0f;
}

/// The points' light toward the camera along the segment o + s d, s in [0, sMax] (d unit), inside
/// the homogeneous medium `medium`, before the camera path's throughput (the beam radiance
/// estimate, Jarosz et al. 2008):
///   sum over the points p of that medium within r_p of the segment of
///     K_2D(u_p, r_p) Tr(0 -> s_p) p(dot(w_p, -d)) Phi_p
/// with s_p the point's projection on the segment and u_p its distance from it. `maxSegment` > 0
/// (a capped path length): only the points whose MediumPoint::segment is at most that.
///
/// `tanStart` / `tanEnd`: where the segment starts / ends on a surface that bounds the medium,
/// tan phi of the angle phi between the segment and that surface's normal; 0 elsewhere. There the
/// kernel's disc round the segment reaches past the surface, where no point can be: with a plane
/// through the segment's end at angle phi, the points lost (outside the medium, s in
/// [0, r tan phi]) are as many, in the mean, as the medium's points beyond the end (s in
/// [-r tan phi, 0]), by symmetry through the end. So at a bounded end the points up to
/// r tan phi beyond it count too (tan phi at most kPointBoundaryReach), with the transmittance at
/// the end: the boundary bias is then second order in r.
Rgb gatherPoints(const Scene& scene, const PointBvh& bvh, MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                 int maxSegment, float tanStart, float tanEnd, std::vector<uint32_t>& scratch);
/// gatherPoints' tan phi at a segment's end on a surface of geometric normal `n` (unit) that
/// bounds the medium, for the segment's direction `d`: at most kPointBoundaryReach.
inline float boundaryTangent(const Vec3& d, const Vec3& n) {
    const float c = std::abs(dot(d, n));
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    return s >= kPointBoundaryReach * c ? kPointBoundaryReach : s / c;
}


}  // namespace tyndall
