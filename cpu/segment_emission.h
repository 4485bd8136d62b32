#pragma once
// The emission of a grid medium seen along a camera segment (docs/algorithm.md "Emission seen
// along camera segments"): the radiance reaching ray.o from [0, tEnd] of a medium with source
// sigma_a(p) Le(p),
//   E = integral over [0, tEnd] of Tr(0, t) sigma_a(t) Le(t) dt,
// estimated with `samples` stratified distances t_i drawn in proportion to a weight that is
// constant on each piece of the majorant grid along the ray (cpu/free_flight.h MajorantPieces):
//   w = q + alpha (Q / M) majorant,   Q = sum of q l, M = sum of majorant l over the pieces,
// q the piece's cell's emission importance (EmissionImportance) and l the piece's length;
// w = majorant where Q = 0 or where there is no importance grid. The majorant share
// (alpha = kEmissionDefensiveShare) keeps the estimator unbiased wherever the importance misses
// emission: w > 0 wherever the density is. Then
//   E ~ (W / N) sum over i of T_i sigma_a(t_i) Le(t_i) / w(t_i),   W = sum of w l,
// with T_i an unbiased estimate of Tr(0, t_i), independent of t_i, by residual ratio tracking
// (Novak et al. 2014) against a control: on each piece, the density at a comb of points (one
// random offset for the segment, about four per majorant cell), constant over each point's
// stratum. T(t) = exp(-sigma_t C(t)) R(t), C the control's integral (closed form) and R the
// product over tentative collisions x < t at rate sigma_t majorant of
// 1 - (density(x) - control(x)) / majorant (in [0, 2]): near 1 where the comb follows the
// density, so T is far steadier than plain ratio tracking's product. Samples land where the fire
// is bright in proportion to how bright, so the flames do not speckle the way a few trackers'
// tentative collisions do. Homogeneous media: the closed form (homogeneousEmission).
// Randomness only from the caller's stream.
#include <memory>
#include <vector>

#include "core/medium.h"
#include "core/rng.h"
#include "core/scene.h"

namespace tyndall {

/// The majorant-proportional share alpha of the distances' weight.
constexpr float kEmissionDefensiveShare = 0.1f;

/// Per cell of a grid medium's majorant grid (same layout), a relative emission importance: the
/// mean of (r + g + b) of sigma_a density(p) Le(p) (Le before the medium's emissionScale) over a
/// lattice of m^3 points at the cell's stratum centres (m from 4 down to 1 as the occupied cells
/// grow, at most about kMaxLookups points in all), divided by the largest cell's; 0 where the
/// majorant is 0. Not a bound: a peak between the points is covered by the estimator's majorant
/// share. Empty (none()) for a medium that does not emit or has no majorant grid.
class EmissionImportance {
public:
    EmissionImportance() = default;
    explicit EmissionImportance(const Medium& medium);

    bool none() const { return m_cells.empty(); }
    /// The importance of the cell holding world point `p` (clamped into the grid).
    float at(const Vec3& p) const;

    static constexpr size_t kMaxLookups = size_t(1) << 22;

private:
    Affine3 m_worldToCell;
    int m_res[3] = {0, 0, 0};
    std::vector<float> m_cells;
};

/// The estimate above along ray.o + t ray.d, t in [0, tEnd], of `medium` (`importance` may be
/// none()). Draws one uniform for the comb, `samples` for the distances and one per tentative
/// collision of the tracker before the last sample; none for homogeneous media or media that do
/// not emit.
Rgb estimateSegmentEmission(const Medium& medium, const EmissionImportance& importance, const Ray& ray, float tEnd,
                            Rng& rng, int samples);

/// The estimator for every medium of a scene: the importance grids built once (at construction).
class SegmentEmission {
public:
    explicit SegmentEmission(const Scene& scene);

    /// Emission reaching `o` along -d from o + t d, t in [0, tMax], inside medium `id`.
    Rgb estimate(MediumId id, const Vec3& o, const Vec3& d, float tMax, Rng& rng) const {
        return estimateSegmentEmission(m_scene.media[id], m_importance[id], Ray{o, d, 0.0f, tMax}, tMax, rng,
                                       kSamples);
    }

    /// Distances per camera segment (docs/performance.md "Emissive media" measures the choice).
    static constexpr int kSamples = 8;

private:
    const Scene& m_scene;
    std::vector<EmissionImportance> m_importance;  ///< per medium
};

}  // namespace tyndall
