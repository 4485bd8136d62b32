#pragma once
// A pilot for the equiangular sample count (RenderSettings::equiangularSamples), for the quality
// bench (tyndall_quality --pilot-only; docs/performance.md, "A pilot for the count"): not used by
// the renderer, whose "auto" is RenderSettings::autoEquiangularSamples. Deterministic: a function
// of the scene and the settings alone (its own seed, not the render's).
//
// The cost model: a pass costs C_0 + N c (c: one equiangular distance and its shadow ray on every
// camera segment in a medium) and leaves a pixel the variance V_rest + V(N) (V(N): N distances'
// variance along the segment, V(1) = V_ea; V_rest: the rest of the pass, the beams, the surface
// photons, the film jitter). At equal time the error's square is (V_rest + V(N)) (C_0 + N c); with
// V(N) = V_ea / N its least is at N* = sqrt((V_ea / V_rest) (C_0 / c)). Stratified distances do
// better than 1 / N: V(n) = V_ea n^-gamma, gamma from V(1) and V(kStratified); below one distance
// V(N) = V_ea / N (one distance on a share N of a pixel's passes).
// The pilot measures the variances at the render's own settings: two passes from the middle of the
// radius plan with one distance per segment (the whole image, or kPilotBands bands of rows across
// it when it has more than kPilotPixels pixels), whose per-pixel difference gives a pass's
// variance, V_rest + V_ea; kPilotDraws single-distance estimates along each pixel's primary segment
// give V_ea, and two estimates of kStratified stratified distances V(kStratified). The brightest
// kTrimTop of the pixels are left out (lights in view, whose variance no count changes). The cost
// ratio is a count: C_0 / c = (kPixelCost pixels + kPathCost photon paths) / (segments in a medium),
// the constants a pixel's and a photon path's share of a pass in units of one distance and its
// shadow ray. The count: the power of two in [kMin, kMax] with the least error at equal time.
#include "core/scene.h"
#include "core/settings.h"
#include "cpu/equiangular.h"

namespace tyndall {

struct EquiangularPilot {
    /// V_ea: one distance's variance along a primary segment, summed over the pilot's pixels
    /// below the kTrimTop cut
    double equiangularVariance = 0;
    double stratifiedVariance = 0;  ///< the same for the mean of kStratified stratified distances
    double passVariance = 0;        ///< a pilot pass's variance (one distance per segment), summed likewise
    double restVariance = 0;        ///< V_rest = passVariance - equiangularVariance (at least 0)
    double pixels = 0;              ///< pixels the pilot rendered
    double segments = 0;            ///< of them, those whose primary segment lies in a scattering medium
    double photonPaths = 0;         ///< photon paths per pass over the pilot's share of the image
    double costRatio = 0;           ///< C_0 / c
    double samples = 0;             ///< the count: equiangularSamplesFor over these (0: no pilot)
};

struct EquiangularAuto {
    /// Single-distance estimates per primary segment for V_ea.
    static constexpr int kPilotDraws = 4;
    /// Stratified distances of the second estimate, which measures how fast stratification
    /// lowers the variance.
    static constexpr int kStratified = 4;
    static constexpr uint64_t kPilotPixels = 65536;
    static constexpr int kPilotBands = 4;
    /// The brightest share of the pilot's pixels left out of the variances (lights in view).
    static constexpr double kTrimTop = 0.01;
    /// The pilot's seed: the same for every render seed, so the count is the scene's and settings'.
    static constexpr uint64_t kPilotSeed = 0x6571756961756c6full;
    /// A pass's cost per pixel and per photon path, in units of one equiangular distance with its
    /// shadow ray on one segment (docs/performance.md, "Single scattering by equiangular sampling").
    static constexpr double kPixelCost = 2.0;
    static constexpr double kPathCost = 6.0;
    /// The counts tried: powers of two from kMin to kMax.
    static constexpr double kMin = 0.25;
    static constexpr double kMax = 8;
    /// n stratified distances have at most n^-kMaxExponent of one's variance (a smooth integrand
    /// in one dimension: n^-3).
    static constexpr double kMaxExponent = 3;
};

/// gamma in V(n) = V(1) n^-gamma, from V(1) and V(kStratified): in [1, kMaxExponent].
double equiangularStratificationExponent(double v1, double vStratified);
/// The error's square at equal time, up to a factor: (vRest + V_ea(n)) (costRatio + n), V_ea(n) =
/// v1 / n below 1 (one distance on a share n of the passes), v1 n^-gamma from 1 up.
double equiangularTimesVariance(double n, double v1, double gamma, double vRest, double costRatio);
/// The power of two in [kMin, kMax] with the least equiangularTimesVariance (the smaller on a tie);
/// kMin where v1 is 0.
double equiangularSamplesFor(double v1, double vStratified, double vRest, double costRatio);

/// The unbiased sample variance (r + g + b) of `draws` (>= 2) estimates of `eq` with `n` distances
/// along the segment o + s d, s in [0, sMax], each from its own stream keyed by the pilot's seed,
/// `pass` and `index`.
double equiangularSegmentVariance(const EquiangularScattering& eq, MediumId medium, const Vec3& o, const Vec3& d,
                                  float sMax, int n, int draws, uint64_t pass, uint64_t index);

/// Runs the pilot for `s` (its radii resolved: resolveRadiusDefaults) on `scene`. Deterministic.
EquiangularPilot runEquiangularPilot(const Scene& scene, const RenderSettings& s);

}  // namespace tyndall
