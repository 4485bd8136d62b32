#include "bench/equiangular_pilot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/rng.h"
#include "cpu/equiangular.h"
#include "cpu/pass_renderer.h"
#include "cpu/radius_defaults.h"

namespace tyndall {

double equiangularStratificationExponent(double v1, double vStratified) {
    using A = EquiangularAuto;
    if (!(v1 > 0)) return 1.0;
    if (!(vStratified > 0)) return A::kMaxExponent;
    const double gamma = std::log(v1 / vStratified) / std::log(double(A::kStratified));
    return std::isfinite(gamma) ? std::clamp(gamma, 1.0, A::kMaxExponent) : 1.0;
}

double equiangularTimesVariance(double n, double v1, double gamma, double vRest, double costRatio) {
    // Below one distance a pixel gets one on a share n of its passes: v1 / n. From one up, n^-gamma.
    const double vEa = n < 1 ? v1 / n : v1 * std::pow(n, -gamma);
    return (vRest + vEa) * (costRatio + n);
}

double equiangularSamplesFor(double v1, double vStratified, double vRest, double costRatio) {
    using A = EquiangularAuto;
    if (!(v1 > 0) || !(costRatio > 0) || !std::isfinite(v1) || !std::isfinite(costRatio)) return A::kMin;
    const double gamma = equiangularStratificationExponent(v1, vStratified);
    double best = A::kMin, bestJ = std::numeric_limits<double>::infinity();
    for (double n = A::kMin; n <= A::kMax; n *= 2) {
        const double j = equiangularTimesVariance(n, v1, gamma, std::max(vRest, 0.0), costRatio);
        if (j < bestJ) best = n, bestJ = j;
    }
    return best;
}

double equiangularSegmentVariance(const EquiangularScattering& eq, MediumId medium, const Vec3& o, const Vec3& d,
                                  float sMax, int n, int draws, uint64_t pass, uint64_t index) {
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int k = 0; k < draws; ++k) {
        Rng rng = Rng::forKey(EquiangularAuto::kPilotSeed, pass, index * uint64_t(draws) + uint64_t(k),
                              StreamPurpose::Equiangular);
        const Rgb v = eq.estimate(medium, o, d, sMax, n, rng);
        for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
    }
    double variance = 0;
    for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / draws;
        const double var = (sum2[c] - draws * m * m) / (draws - 1);
        if (std::isfinite(var)) variance += std::max(0.0, var);
    }
    return variance;
}

namespace {

struct PilotPixel {
    double pass = 0;         ///< a pass's variance, r + g + b
    double equiangular = 0;  ///< one distance's variance along the primary segment, r + g + b
    double stratified = 0;   ///< the same of kStratified stratified distances' mean
    double brightness = 0;   ///< the two passes' mean, r + g + b
    bool segment = false;    ///< the primary segment lies in a scattering medium
};

/// The pilot's regions: the whole image, or bands of full rows spread over it.
std::vector<PixelRegion> pilotRegions(int width, int height) {
    using A = EquiangularAuto;
    if (uint64_t(width) * uint64_t(height) <= A::kPilotPixels) return {PixelRegion{0, 0, width, height}};
    const int rows = std::max(1, int(A::kPilotPixels / uint64_t(A::kPilotBands) / uint64_t(width)));
    std::vector<PixelRegion> bands;
    for (int b = 0; b < A::kPilotBands; ++b) {
        const int centre = int((2 * b + 1) * int64_t(height) / (2 * A::kPilotBands));
        const int y = std::clamp(centre - rows / 2, 0, std::max(0, height - rows));
        bands.push_back(PixelRegion{0, y, width, std::min(rows, height)});
    }
    return bands;
}

}  // namespace

EquiangularPilot runEquiangularPilot(const Scene& scene, const RenderSettings& s) {
    using A = EquiangularAuto;
    EquiangularPilot pilot;
    RenderSettings ps = s;
    ps.equiangular = true;
    ps.equiangularSamples = 1;
    ps.seed = A::kPilotSeed;
    // Two passes from the middle of the radius plan (the radii shrink over it, and the beams'
    // variance with them).
    const uint64_t planned = plannedPhotonPaths(s) / std::max<uint32_t>(1, s.photonsPerPass);
    const uint64_t first = planned / 2;
    const double imagePixels = double(s.width) * double(s.height);
    bool scattering = false;
    for (const Medium& m : scene.media) scattering |= !m.sigmaS.isBlack();
    if (!scattering) return pilot;
    std::vector<PilotPixel> pixels;
    for (const PixelRegion& region : pilotRegions(s.width, s.height)) {
        ps.region = region;
        PassRenderer renderer(scene, ps);
        const EquiangularScattering eq(renderer.rayTracer(), 1.0);
        const EquiangularScattering eqStratified(renderer.rayTracer(), double(A::kStratified));
        if (!eq.any()) return pilot;
        const Image a = renderer.renderPass(first), b = renderer.renderPass(first + 1);
        const PrimaryPass primary = renderer.tracePrimary(first);
        const size_t start = pixels.size();
        pixels.resize(start + size_t(region.width) * size_t(region.height));
        // Rows in parallel, each pixel's numbers in its own slot (summed in order below).
        tbb::parallel_for(region.y, region.y + region.height, [&](int y) {
            for (int x = region.x; x < region.x + region.width; ++x) {
                const size_t pixel = size_t(y) * size_t(s.width) + size_t(x);
                PilotPixel& p = pixels[start + size_t(y - region.y) * size_t(region.width) + size_t(x - region.x)];
                // A pass's variance from two independent passes: E[(a - b)^2] / 2.
                for (int c = 0; c < 3; ++c) {
                    const double d = double(a.pixels[pixel][c]) - double(b.pixels[pixel][c]);
                    if (std::isfinite(d)) p.pass += 0.5 * d * d;
                    p.brightness += 0.5 * (double(a.pixels[pixel][c]) + double(b.pixels[pixel][c]));
                }
                const PrimaryRay& ray = primary.segments.rays[pixel];
                if (ray.medium != kVacuum && ray.tMax > 0 && !scene.media[ray.medium].sigmaS.isBlack()) {
                    p.segment = true;
                    p.equiangular = equiangularSegmentVariance(eq, ray.medium, ray.origin, ray.dir, ray.tMax, 1,
                                                               A::kPilotDraws, first, pixel);
                    p.stratified = equiangularSegmentVariance(eqStratified, ray.medium, ray.origin, ray.dir, ray.tMax,
                                                              A::kStratified, 2, first + 1, pixel);
                }
                if (!std::isfinite(p.brightness)) p.brightness = 0;
            }
        });
    }
    // The brightest kTrimTop of the pixels left out: lights in view, whose variance no count of
    // distances changes, would otherwise decide it for the whole image.
    std::vector<double> brightness;
    for (const PilotPixel& p : pixels) brightness.push_back(p.brightness);
    double cut = std::numeric_limits<double>::infinity();
    const size_t k = size_t(double(brightness.size()) * (1.0 - A::kTrimTop));
    if (k < brightness.size()) {
        std::nth_element(brightness.begin(), brightness.begin() + ptrdiff_t(k), brightness.end());
        cut = brightness[k];
    }
    for (const PilotPixel& p : pixels) {
        pilot.segments += p.segment ? 1 : 0;
        if (p.brightness >= cut && cut > 0) continue;
        pilot.passVariance += p.pass;
        pilot.equiangularVariance += p.equiangular;
        pilot.stratifiedVariance += p.stratified;
    }
    pilot.photonPaths = double(s.photonsPerPass) * double(pixels.size()) / std::max(1.0, imagePixels);
    pilot.pixels = double(pixels.size());
    pilot.restVariance = std::max(0.0, pilot.passVariance - pilot.equiangularVariance);
    if (pilot.segments > 0) {
        pilot.costRatio = (A::kPixelCost * pilot.pixels + A::kPathCost * pilot.photonPaths) / pilot.segments;
        pilot.samples = equiangularSamplesFor(pilot.equiangularVariance, pilot.stratifiedVariance, pilot.restVariance,
                                              pilot.costRatio);
    }
    return pilot;
}

}  // namespace tyndall
