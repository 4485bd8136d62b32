// The default radii fit: with every radius setting left automatic, PPB converges to the
// in-tree path tracer. A closed diffuse box of thin fog lit by one point light out of view (the
// quality bench's walls-and-fog box, bench/scenes/walls-fog-box.json, built here), 32 x 32, fixed
// seeds, the radii a `--time` render or the viewer resolves (planned for the open-ended horizon,
// shrinking at PPB's rate past it). Against a 4096-spp path-traced reference (its own noise
// variance removed), the relative RMSE must fall by kFallPer4x per 4x passes from 25 to 1600
// passes of 1000 photon paths (a quarter of the horizon to 16 times it) and end below kFinalRmse;
// the bias of the image mean must end below kFinalBias.
// Slow (about 17 CPU s, 4 of them the reference).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/accumulator.h"
#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "tests/test_scenes.h"

namespace tyndall {
namespace {

// Measured (reference seed 11, PPB seed 21): relative RMSE 0.104, 0.070, 0.049, 0.036 after 25,
// 100, 400, 1600 passes (x0.67-0.73 per 4x passes, the N^(-alpha/2) = x0.71 of the noise); bias
// -3.0%, -1.5%, -0.64%, -0.45% with the plain surface kernel (its loss at the box's edges and corners,
// shrinking with the radius); with --surface-boundary on (the default): see kFinalBias's comment.
// Planted bug (run, plain kernel): radii that never shrink (RadiusSetup::radiiOf's factor 1)
// plateau: 0.093, 0.071, 0.064, 0.062 RMSE, bias -3.6% to -2.7% (five of the then six checks failed).
constexpr double kFallPer4x = 0.8;
constexpr double kFinalRmse = 0.045;
constexpr double kFinalBias = 0.0075;
// With the edge loss divided out the bias is small from the start: measured relative RMSE 0.085,
// 0.054, 0.037, 0.026 and bias -1.18%, +0.36%, +0.51%, +0.48% after 25, 100, 400, 1600 passes
// (equiangular sampling on, the default; off: +0.54%, +0.61%, +0.51% from 100 passes). That
// steady +0.5% is these two seeds' noise, not the renderer's: over 8 references (seeds 11-18)
// and 8 PPB seeds (21-28) the image mean's bias is -0.00% +- 0.17%, -0.03% +- 0.10%, +0.07% +-
// 0.06% after 100, 400, 1600 passes (tyndall_measurements' WallsFogBoxBias; docs/performance.md
// "Is the walls box biased?"); PPB seed 21 reads 0.26% above the PPB seeds' mean after 1600
// passes (their spread 0.13%) and reference seed 11 0.15% below the references' (0.11%). One
// pair's bias thus has a standard deviation of about 0.17% after 1600 passes: the test bounds it
// at 0.75% (kFinalBias) rather than asking it to fall.

struct Error {
    double relRmse, relBias;
};

Error against(const Image& x, const ReferenceImage& ref) {
    double se = 0, noise = 0, sum = 0, sumRef = 0;
    for (size_t i = 0; i < x.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double d = double(x.pixels[i][c]) - ref.mean.pixels[i][c];
            se += d * d;
            noise += ref.varianceOfMean.pixels[i][c];
            sum += x.pixels[i][c];
            sumRef += ref.mean.pixels[i][c];
        }
    const double n = 3.0 * double(x.pixels.size());
    return {std::sqrt(std::max(0.0, (se - noise) / n)) / (sumRef / n), sum / sumRef - 1};
}

TEST(DefaultsConvergence, DefaultRadiiConvergeToThePathTracer) {
    const int size = 32;
    const Scene scene = test::wallsFogBox();
    ReferenceSettings rs;
    rs.width = rs.height = size;
    rs.samplesPerPixel = 4096;
    rs.seed = 11;
    EmbreeScene rt(scene);
    const ReferenceImage ref = ReferenceTracer(rt, rs).render();

    // What `tyndall render --time S` and the viewer resolve: the open-ended plan (kOpenEndedPathsPerPixel
    // paths per pixel, 102 passes here), after which the radii keep shrinking.
    RenderSettings ps;  // every radius setting automatic
    ps.width = ps.height = size;
    ps.photonsPerPass = 1000;
    ps.timeBudget = 60;
    ps.seed = 21;
    PassRenderer renderer(scene, ps);
    std::printf("open-ended plan %llu paths: radius %.4g, surface %.4g, offset %llu\n",
                (unsigned long long)renderer.settings().plannedPaths, renderer.settings().radius,
                renderer.settings().surfaceRadius, (unsigned long long)renderer.settings().radiusOffset);
    Accumulator acc(size, size);
    std::vector<Error> errors;
    const uint64_t checkpoints[] = {25, 100, 400, 1600};
    for (uint64_t p = 0; p < checkpoints[3]; ++p) {
        acc.addPass(renderer.renderPass(p));
        if (p + 1 == checkpoints[errors.size()]) {
            errors.push_back(against(acc.mean(), ref));
            std::printf("%4llu passes (beam radius %.4g): relative RMSE %.4f, bias %+.4f\n", (unsigned long long)(p + 1),
                        renderer.radii().beamRadiusOf((p + 1) * ps.photonsPerPass), errors.back().relRmse,
                        errors.back().relBias);
        }
    }
    for (size_t k = 1; k < errors.size(); ++k)
        EXPECT_LT(errors[k].relRmse, kFallPer4x * errors[k - 1].relRmse)
            << "relative RMSE from " << checkpoints[k - 1] << " to " << checkpoints[k] << " passes";
    EXPECT_LT(errors.back().relRmse, kFinalRmse) << "after " << checkpoints[3] << " passes";
    EXPECT_LT(std::fabs(errors.back().relBias), kFinalBias) << "bias after " << checkpoints[3] << " passes";
}


}  // namespace
}  // namespace tyndall
