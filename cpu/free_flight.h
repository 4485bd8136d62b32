#pragma once
// Free-flight sampling in a medium, for photon paths, the reference path tracer and the stored
// transmittance distances. Homogeneous media sample analytically with spectral MIS over the
// three channels; density-grid media use delta (Woodcock) tracking against the grid's majorant:
// piecewise constant along the ray when the grid has a majorant grid (a DDA over its coarse
// cells), else one value per segment. No ray marching anywhere: every estimate here is unbiased.
// Randomness comes only from the caller's keyed stream `rng`.
#include <cmath>

#include "core/medium.h"
#include "core/rng.h"

namespace tyndall {

/// The majorant along [tMin, tEnd] of a ray through a density grid, as constant pieces in
/// increasing t: the grid's majorant grid walked cell by cell when it has one (parts outside it
/// skipped: density 0 there), else one piece with majorant(ray). Tracking and the equiangular
/// estimator's distance sampling (cpu/equiangular.h) walk it.
class MajorantPieces {
public:
    MajorantPieces(const DensityGrid& grid, const Ray& ray, float tEnd, float tMin = 0.0f) {
        if (const MajorantGrid* mg = grid.majorantGrid()) {
            m_walk = mg->walk(ray, tMin, tEnd);
            m_useWalk = true;
        } else {
            m_single = grid.majorant(Ray{ray.o, ray.d, tMin, tEnd});
            m_tMin = tMin;
            m_tEnd = tEnd;
        }
    }
    /// The next piece [*t0, *t1] and its majorant; false after the last.
    bool next(float* t0, float* t1, float* majorant) {
        if (m_useWalk) return m_walk.next(t0, t1, majorant);
        if (m_done) return false;
        m_done = true;
        *t0 = m_tMin;
        *t1 = m_tEnd;
        *majorant = m_single;
        return true;
    }

private:
    MajorantGrid::Walk m_walk;
    bool m_useWalk = false;
    bool m_done = false;
    float m_single = 0, m_tMin = 0, m_tEnd = 0;
};

/// Outcome of sampling a free flight along [0, tEnd] of `ray`.
struct FreeFlight {
    bool scattered = false;  ///< a real scattering event at distance t < tEnd
    float t = 0;
    /// Throughput factor for the sampled event: scattering -> sigma_s Tr / pdf;
    /// passing -> Tr(tEnd) / P(pass). For delta tracking both are the albedo / 1.
    Rgb weight{1.0f};
};

/// sampleFreeFlight for every medium but the homogeneous grey ones (those are inline below).
FreeFlight sampleFreeFlightSpectralOrGrid(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

inline FreeFlight sampleFreeFlight(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (!medium.homogeneous()) return sampleFreeFlightSpectralOrGrid(medium, ray, tEnd, rng);
    Rgb st = medium.sigmaT();
    if (!(st.r == st.g && st.r == st.b)) return sampleFreeFlightSpectralOrGrid(medium, ray, tEnd, rng);
    // Grey extinction: exact exponential sampling, no MIS; the weights need no exp:
    // sigma_s Tr / (sigma_t Tr) on scattering, Tr / Tr on passing.
    FreeFlight ff;
    float u = rng.uniform();
    float t = st.r > 0 ? -std::log(1.0f - u) / st.r : kInfinity;  // u < 1
    if (t < tEnd) {
        ff.scattered = true;
        ff.t = t;
        ff.weight = medium.sigmaS / st.r;
    } else {
        ff.t = tEnd;
    }
    return ff;
}

/// Distance to the first real collision (absorption or scattering) along `ray`, or +infinity when
/// it passes tEnd: one sample of the stored step transmittance, Tr(t) = P(distance > t). Needs grey
/// extinction for grid media (channel 0 is used for homogeneous ones).
float sampleCollisionDistance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

/// `n` (<= kMaxFreeFlights) independent collision distances along one segment, each distributed as
/// sampleCollisionDistance's: the stored set of one beam or one pixel. Grid media walk the
/// majorant grid once for all n trackers.
constexpr int kMaxFreeFlights = 64;
void sampleCollisionDistances(const Medium& medium, const Ray& ray, float tEnd, Rng& rng, int n, float* out);

/// The emission of a homogeneous medium reaching the start of a segment of length d:
/// sigma_a Le (1 - exp(-sigma_t d)) / sigma_t per channel (sigma_a Le d where sigma_t = 0).
Rgb homogeneousEmission(const Medium& medium, float d);

/// An unbiased estimate of the emission reaching ray.o from [0, tEnd],
/// E = integral of Tr(0, s) sigma_a(s) Le(s) ds, for the reference path tracer (camera paths use
/// cpu/segment_emission.h's lower-variance one): exact for homogeneous media, ratio
/// tracking for grid media (at each tentative collision x, T sigma_a(x) Le(x) / sigma_majorant(x)
/// with T the running ratio-tracking transmittance, which then takes the factor
/// 1 - sigma_t(x) / sigma_majorant(x)). Zero for media that do not emit, drawing nothing.
Rgb estimateEmission(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

/// Transmittance estimate over [0, tEnd]: analytic for homogeneous media; for grid media residual
/// ratio tracking (Novak et al. 2014) against a density comb (residualTransmittance), unbiased.
/// Shadow rays, the equiangular estimator's legs and the camera paths' segments use it.
Rgb estimateTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

/// Plain ratio tracking over [0, tEnd] of a grid medium (the running product of
/// 1 - density / majorant at tentative collisions at rate sigma_t majorant): the reference path
/// tracer's estimate, and the baseline the tests compare residualTransmittance's variance with.
/// Analytic for homogeneous media.
Rgb ratioTrackingTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

/// Comb points per majorant cell along the ray's dominant cell axis: the controls of residual
/// tracking (here and cpu/segment_emission.h) sample the density this densely at most.
constexpr float kCombPointsPerCell = 4.0f;
/// Most comb points on one majorant piece.
constexpr int kMaxCombPoints = 64;
/// Comb points per unit length along `ray` for a piece of a grid's majorant grid:
/// kCombPointsPerCell per cell crossed along the ray's dominant cell axis (two voxels of an
/// OpenVDB grid's 8-voxel cells); kMaxCombPoints over [0, tEnd] without a majorant grid.
float combPointsPerUnit(const DensityGrid& grid, const Ray& ray, float tEnd);

/// Most comb points per unit of a piece's majorant optical depth (sigma_t majorant length).
constexpr float kCombPointsPerDepth = 16.0f;
/// Majorant pieces thinner than this (sigma_t majorant length) get no comb in
/// residualTransmittance: plain ratio tracking's relative variance there is below it.
constexpr float kMinCombDepth = 1.0f / 256.0f;

/// The grid-medium estimate of estimateTransmittance: on each piece of the majorant grid along
/// the ray (MajorantPieces) a control c(t): the density at m points, length x combPointsPerUnit
/// but at most kCombPointsPerDepth x the piece's majorant depth (at least 1, at most
/// kMaxCombPoints; t0 + (j + u) h, h = length / m, one uniform u for the ray), linear between them and constant beyond the first and last. T = exp(-sigma_t C) R with C
/// the control's integral (closed form) and R the product over tentative collisions x at rate
/// sigma_t majorant of 1 - (density(x) - c(x)) / majorant, each factor in [0, 2]
/// (0 <= c, density <= majorant). Pieces thinner than kMinCombDepth take c = 0 (plain ratio
/// tracking). Its relative variance is exp(sigma_t integral of (density - c)^2 / majorant) - 1
/// against plain ratio tracking's exp(sigma_t integral of density^2 / majorant) - 1: near 0 where
/// the comb follows the density (docs/performance.md "Transmittance in grid media" measures it).
/// Draws one uniform for the comb (at the first piece with one) and one per tentative collision.
float residualTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng);

/// residualTransmittance's tracker over [0, tEnd] (the same draws and the same return value), read
/// on the way at the n distances `at` (ascending, in [0, tEnd]; they draw nothing): out[i] its
/// running estimate at at[i], exp(-sigma_t C(0, at[i])) times the factors of the tentative
/// collisions before at[i], with C(0, t) the control's integral up to t in closed form. Each is
/// unbiased for Tr(0, at[i]) (neither the comb nor the collisions depend on where it is read), so
/// one tracker serves several distances along a ray; they are correlated through it.
float residualTransmittanceAlong(const Medium& medium, const Ray& ray, float tEnd, const float* at, int n, float* out,
                                 Rng& rng);

}  // namespace tyndall
