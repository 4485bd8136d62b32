// A measurement, not a check (see rough_fog_box_bias.cpp): is the walls box's image mean biased
// with the default radii? cpu_defaults_convergence_tests' DefaultsConvergence bounds one seed
// pair's bias by what this finds. Run with
//   build/tests/tyndall_measurements --gtest_filter=WallsFogBoxBias.*
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/accumulator.h"
#include "cpu/embree_scene.h"
#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

// About 4 CPU minutes (docs/performance.md "Is the walls box biased?"): the image mean's bias of
// cpu_defaults_convergence_tests' DefaultsConvergence.DefaultRadiiConvergeToThePathTracer over
// seeds, 8 references (seeds 11-18) against 8 PPB renders (seeds 21-28) with the same settings,
// after 100, 400 and 1600 passes; the standard errors from the spread over seeds.
TEST(WallsFogBoxBias, ImageMeanOverSeeds) {
    const int size = 32, seeds = 8;
    const Scene scene = test::wallsFogBox();
    auto mean = [](const Image& img) {
        double s = 0;
        for (const Rgb& p : img.pixels) s += p.r + p.g + p.b;
        return s / (3.0 * double(img.pixels.size()));
    };
    auto meanAndError = [](const std::vector<double>& v) {
        const test::MeanVar mv = test::meanVar(v);
        return std::pair<double, double>{mv.mean, std::sqrt(mv.var / double(mv.n))};
    };
    EmbreeScene rt(scene);
    std::vector<double> refs;
    for (int k = 0; k < seeds; ++k) {
        ReferenceSettings rs;
        rs.width = rs.height = size;
        rs.samplesPerPixel = 4096;
        rs.seed = 11 + uint64_t(k);
        refs.push_back(mean(ReferenceTracer(rt, rs).render().mean));
        std::printf("reference seed %d: %.6f\n", 11 + k, refs.back());
    }
    const uint64_t checkpoints[] = {100, 400, 1600};
    std::vector<double> ppb[3];
    for (int k = 0; k < seeds; ++k) {
        RenderSettings ps;
        ps.width = ps.height = size;
        ps.photonsPerPass = 1000;
        ps.timeBudget = 60;
        ps.seed = 21 + uint64_t(k);
        PassRenderer renderer(scene, ps);
        Accumulator acc(size, size);
        for (uint64_t p = 0, c = 0; p < checkpoints[2]; ++p) {
            acc.addPass(renderer.renderPass(p));
            if (p + 1 == checkpoints[c]) ppb[c++].push_back(mean(acc.mean()));
        }
        std::printf("PPB seed %d: %.6f, %.6f, %.6f after 100, 400, 1600 passes\n", 21 + k, ppb[0].back(), ppb[1].back(),
                    ppb[2].back());
    }
    const auto [r, seR] = meanAndError(refs);
    std::printf("references: %.6f +- %.6f\n", r, seR);
    for (int c = 0; c < 3; ++c) {
        const auto [m, se] = meanAndError(ppb[c]);
        const double bias = m / r - 1, seBias = std::hypot(se, seR) / r;
        std::printf("%4llu passes: PPB %.6f +- %.6f, bias %+.3f%% +- %.3f%% (%.1f se)\n",
                    (unsigned long long)checkpoints[c], m, se, 100 * bias, 100 * seBias, bias / seBias);
    }
}

}  // namespace
}  // namespace tyndall
