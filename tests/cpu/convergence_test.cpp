// The paper's own experiment (PPB, Section 5 / the talk's "Empirical validation"): at fixed
// pixels of a small volumetric-caustic scene, run many independent renders and measure, after N
// passes, the variance and the mean of the running average across runs.
//   Variance of the running mean ~ N^-alpha: the log-log slope over N = 8..256 must lie within
//   0.15 of -alpha (for alpha = 0.3 and 0.8; with 128 runs the slope's standard error is ~0.05).
//   Bias falls: the same runs (same seeds, so the same photon paths) with two initial radii, 0.1
//   and 0.05, estimate the same limit with different biases (bias ~ radius). Their paired
//   difference measures the bias difference with little noise; with alpha = 0.8 (slow reduction,
//   the largest early bias, from blurring the caustic's peak) it must shrink at least 4x from
//   N = 4 to N = 256 and never grow along the way (beyond 2 standard errors).
// Also split invariance: 64 passes x P photon paths and 16 passes x 4P agree within noise, with a
// radius that shrinks enough over the render that a per-pass reduction would be caught.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "core/accumulator.h"
#include "cpu/pass_renderer.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

using namespace tyndall;

namespace {

struct Ensemble {
    std::vector<int> checkpoints;             // N = 1, 2, 4, ..., 256
    std::vector<test::MeanVar> runningMean;   // across runs, per checkpoint
    std::vector<std::vector<double>> values;  // [checkpoint][run]: each run's running mean
};

Scene zoomedCausticScene() {
    Scene s = test::causticScene();
    // Zoom onto the cone just below the focus: every pixel of the 8x8 film sees the caustic.
    s.camera = Camera::lookAt({0, -0.3f, 1.4f}, {0, -0.62f, 0}, {0, 1, 0}, 0.12f);
    return s;
}

Ensemble runEnsemble(const Scene& scene, double alpha, int runs, int passes, uint32_t photons, float radius) {
    Ensemble e;
    for (int n = 1; n <= passes; n *= 2) e.checkpoints.push_back(n);
    std::vector<std::vector<double>> values(e.checkpoints.size(), std::vector<double>(runs));
    tbb::parallel_for(0, runs, [&](int r) {
        RenderSettings s;
        s.width = 8;
        s.height = 8;
        s.photonsPerPass = photons;
        s.alpha = alpha;
        s.radiusOffset = 0;  // the paper's schedule from its first step
        s.radius = radius;
        s.seed = 1000 + uint64_t(r);
        PassRenderer renderer(scene, s);
        double sum = 0;
        size_t next = 0;
        for (int n = 1; n <= passes; ++n) {
            Image img = renderer.renderPass(uint64_t(n - 1));
            double v = 0;
            for (int y = 3; y < 5; ++y)
                for (int x = 3; x < 5; ++x) v += img.at(x, y).r;
            sum += v / 4;
            if (next < e.checkpoints.size() && n == e.checkpoints[next]) values[next++][r] = sum / n;
        }
    });
    for (const auto& v : values) e.runningMean.push_back(test::meanVar(v));
    e.values = std::move(values);
    return e;
}

double varianceSlope(const Ensemble& e) {
    std::vector<double> lx, ly;
    for (size_t i = 0; i < e.checkpoints.size(); ++i) {
        if (e.checkpoints[i] < 8) continue;
        lx.push_back(std::log(double(e.checkpoints[i])));
        ly.push_back(std::log(e.runningMean[i].var));
    }
    return test::slope(lx, ly);
}

double standardError(const test::MeanVar& m) {
    return std::sqrt(m.var / double(m.n));
}

}  // namespace

TEST(Convergence, VarianceFallsAsNToTheMinusAlphaAndBiasFalls) {
    const Scene scene = zoomedCausticScene();
    const int runs = 128, passes = 256;
    Ensemble low = runEnsemble(scene, 0.3, runs, passes, 32, 0.05f);
    Ensemble high = runEnsemble(scene, 0.8, runs, passes, 32, 0.05f);
    double slopeLow = varianceSlope(low), slopeHigh = varianceSlope(high);
    for (size_t i = 0; i < low.checkpoints.size(); ++i)
        std::printf("N=%4d  alpha 0.3: mean %.5f var %.3e   alpha 0.8: mean %.5f var %.3e\n", low.checkpoints[i],
                    low.runningMean[i].mean, low.runningMean[i].var, high.runningMean[i].mean, high.runningMean[i].var);
    std::printf("variance slopes: alpha 0.3 -> %.3f, alpha 0.8 -> %.3f\n", slopeLow, slopeHigh);
    EXPECT_NEAR(slopeLow, -0.3, 0.15);
    EXPECT_NEAR(slopeHigh, -0.8, 0.15);

    Ensemble wide = runEnsemble(scene, 0.8, runs, passes, 32, 0.1f);
    std::vector<test::MeanVar> diff;
    for (size_t i = 0; i < wide.checkpoints.size(); ++i) {
        std::vector<double> d;
        for (int r = 0; r < runs; ++r) d.push_back(wide.values[i][r] - high.values[i][r]);
        diff.push_back(test::meanVar(d));
        std::printf("alpha 0.8, N=%4d: mean(r=0.1) - mean(r=0.05) = %+.5f (se %.5f)\n", wide.checkpoints[i],
                    diff.back().mean, standardError(diff.back()));
    }
    EXPECT_GT(std::abs(diff[2].mean), 4.0 * std::abs(diff.back().mean));  // N = 4 vs N = 256
    EXPECT_GT(std::abs(diff[2].mean), 10.0 * standardError(diff[2])) << "no measurable early bias";
    for (size_t i = 3; i < diff.size(); ++i)
        EXPECT_LT(std::abs(diff[i].mean), std::abs(diff[i - 1].mean) + 2.0 * standardError(diff[i]))
            << "bias grew at N = " << wide.checkpoints[i];
}

TEST(Convergence, SplitInvarianceOfPhotonPathsIntoPasses) {
    // 64 passes x 64 paths vs 16 passes x 256 paths: same radii for the same photon paths, so the
    // two averages estimate the same value. Compared over a 16x16 image of the caustic scene,
    // per pixel, as z-scores from independent runs (16 seeds each way, disjoint).
    //
    // The radius must really shrink over the render, or a reduction applied per pass instead of
    // per photon path would go unseen: a wide first radius (0.3, a tenth of the box, so the bias
    // depends strongly on it) and a small schedule offset (16 paths, not the default 1000). Over
    // the 4096 paths the radius falls to 6% of its start; a per-pass reduction would leave the
    // 64-pass run at factor(63) and the 16-pass run at factor(15) (radii 1.6x apart, both far too
    // wide), and the mean squared z measures ~15 instead of ~1 (checked by making radiiOf() take
    // the pass index: 14.9..17.1 over five seed sets, against 0.78..1.30 per photon path).
    const Scene scene = test::causticScene();
    const float radius = 0.3f;
    const uint64_t offset = 16;
    auto settings = [&](uint32_t photons, uint64_t seed) {
        RenderSettings s;
        s.width = 16;
        s.height = 16;
        s.photonsPerPass = photons;
        s.alpha = 0.5;
        s.radius = radius;
        s.radiusOffset = offset;
        s.seed = seed;
        return s;
    };
    {
        PassRenderer renderer(scene, settings(64, 1));
        const RadiusSchedule& schedule = renderer.radii().schedule;
        ASSERT_LT(schedule.beamFactor(4095), 0.1) << "the radius hardly shrinks: the test could not fail";
        // In the renderer, not only in the schedule: the last pass's beams are that thin.
        PhotonMap last = renderer.tracePhotons(63);
        ASSERT_FALSE(last.beams.empty());
        EXPECT_LT(last.beams.front().radius, 0.1f * radius);
        // A per-pass reduction would end 1.6x apart between the two splits.
        EXPECT_LT(schedule.beamFactor(63) / schedule.beamFactor(15), 0.7);
    }
    auto render = [&](uint32_t photons, int passes, uint64_t seed) {
        RenderSettings s = settings(photons, seed);
        PassRenderer renderer(scene, s);
        Accumulator acc(16, 16);
        for (int i = 0; i < passes; ++i) acc.addPass(renderer.renderPass(uint64_t(i)));
        return acc.mean();
    };
    const int seeds = 16;
    std::vector<Image> a, b;
    for (int k = 0; k < seeds; ++k) {
        a.push_back(render(64, 64, 1000 + k));
        b.push_back(render(256, 16, 2000 + k));
    }
    double chi2 = 0;
    int dof = 0;
    for (size_t p = 0; p < a[0].pixels.size(); ++p) {
        std::vector<double> va, vb;
        for (int k = 0; k < seeds; ++k) va.push_back(a[k].pixels[p].g), vb.push_back(b[k].pixels[p].g);
        test::MeanVar ma = test::meanVar(va), mb = test::meanVar(vb);
        double var = (ma.var + mb.var) / seeds;
        if (var <= 1e-12) continue;
        chi2 += (ma.mean - mb.mean) * (ma.mean - mb.mean) / var;
        ++dof;
    }
    ASSERT_GT(dof, 100);
    // With 16 runs a side each term is ~t^2 with 30 degrees of freedom (mean 1.07); pixels share
    // photon beams, so the mean over pixels spreads more than for independent terms (0.78..1.30).
    std::printf("split invariance: %d pixels, mean squared z = %.3f\n", dof, chi2 / dof);
    EXPECT_LT(chi2 / dof, 2.0);
}
