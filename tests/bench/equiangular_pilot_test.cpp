// The pilot for the equiangular sample count, a bench tool (bench/equiangular_pilot.h; docs/algorithm.md
// "How many samples, and which light"):
// 1. The rule: the count minimises the cost model's error at equal time over the powers of two;
//    it rises with the samples' variance and the rest of the pass's cost, falls with the rest's
//    variance, and reaches its bounds in the limits.
// 2. The pilot's per-segment variance against a closed form (a point light in homogeneous fog:
//    the second moment of the equiangular estimate by quadrature), with the pilot's own number
//    of draws.
// 3. The pilot is a function of the scene and settings alone (not the render's seed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bench/equiangular_pilot.h"
#include "core/phase.h"
#include "cpu/equiangular.h"
#include "cpu/radius_defaults.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

using A = EquiangularAuto;

// ---- 1. The rule ----

TEST(EquiangularAuto, CountMinimisesTheEqualTimeErrorOverPowersOfTwo) {
    for (double v1 : {0.01, 0.3, 1.0, 10.0})
        for (double vRest : {0.001, 0.1, 1.0, 100.0})
            for (double cost : {0.5, 2.0, 12.0})
                for (double vStrat : {v1 / 4, v1 / 16, v1 / 64}) {
                    const double n = equiangularSamplesFor(v1, vStrat, vRest, cost);
                    const double gamma = equiangularStratificationExponent(v1, vStrat);
                    const double j = equiangularTimesVariance(n, v1, gamma, vRest, cost);
                    for (double m = A::kMin; m <= A::kMax; m *= 2)
                        EXPECT_LE(j, equiangularTimesVariance(m, v1, gamma, vRest, cost)) << v1 << " " << vRest;
                    // Without stratification's gain (gamma 1) the optimum is sqrt(v1 C / vRest) over
                    // the reals; the best power of two is one of its two neighbours.
                    if (vStrat == v1 / 4) {
                        const double star = std::sqrt(v1 * cost / vRest);
                        if (star > A::kMin && star < A::kMax) {
                            EXPECT_LE(n, 2 * star) << v1 << " " << vRest << " " << cost;
                            EXPECT_GE(n, star / 2) << v1 << " " << vRest << " " << cost;
                        }
                    }
                }
}

TEST(EquiangularAuto, CountIsMonotoneAndBounded) {
    double last = 0;
    for (double v1 = 1e-4; v1 < 1e4; v1 *= 2) {  // more variance per sample: more samples
        const double n = equiangularSamplesFor(v1, v1 / 4, 1.0, 2.0);
        EXPECT_GE(n, last) << v1;
        last = n;
    }
    EXPECT_EQ(last, A::kMax);
    last = A::kMax;
    for (double vRest = 1e-4; vRest < 1e4; vRest *= 2) {  // more of the rest: fewer samples
        const double n = equiangularSamplesFor(1.0, 0.25, vRest, 2.0);
        EXPECT_LE(n, last) << vRest;
        last = n;
    }
    EXPECT_EQ(last, A::kMin);
    last = 0;
    for (double cost = 1e-3; cost < 1e4; cost *= 2) {  // a dearer rest of the pass: more samples
        const double n = equiangularSamplesFor(1.0, 0.25, 1.0, cost);
        EXPECT_GE(n, last) << cost;
        last = n;
    }
    // Limits: nothing else varies, so every sample pays; nothing to estimate, so the least.
    EXPECT_EQ(equiangularSamplesFor(1.0, 0.25, 0.0, 2.0), A::kMax);
    EXPECT_EQ(equiangularSamplesFor(0.0, 0.0, 1.0, 2.0), A::kMin);
    // Stratification's gain measured from 1 and kStratified distances, within [1, 3].
    EXPECT_NEAR(equiangularStratificationExponent(1.0, 1.0 / 16), 2.0, 1e-12);
    EXPECT_EQ(equiangularStratificationExponent(1.0, 0.5), 1.0);
    EXPECT_EQ(equiangularStratificationExponent(1.0, 1e-9), A::kMaxExponent);
}

// ---- 2. The pilot's variance against a closed form ----

constexpr float kSigmaS = test::kOpenFogSigmaS, kSigmaA = test::kOpenFogSigmaA;
using test::openFog;


TEST(EquiangularAuto, SegmentVarianceAgainstQuadrature) {
    const Light light = test::pointLight({0.2f, 0.3f, -0.1f}, 2.0f);
    const Vec3 o{-2.0f, 0.0f, 0.0f}, d = normalize(Vec3(1.0f, 0.02f, -0.03f));
    const float sMax = 4.0f;
    for (float g : {0.0f, 0.6f}) {
        Scene s = openFog({light}, g);
        s.finalize();
        EmbreeScene rt(s);
        EquiangularScattering eq(rt, 1.0);
        // The estimate Y = f / pdf with f the integrand and the equiangular pdf: E[Y] = int f,
        // E[Y^2] = int f^2 / pdf, by Simpson's rule.
        const double sigmaT = kSigmaS + kSigmaA;
        const Vec3 p = light.position;
        const double t0 = dot(p - o, d), D = length(o + d * float(t0) - p);
        const double span = std::atan2(sMax - t0, D) - std::atan2(0.0 - t0, D);
        auto f = [&](double t) {
            const Vec3 x = o + d * float(t);
            const double r = length(x - p);
            const Vec3 wl = (x - p) / float(r);
            return kSigmaS * hgPhase(dot(wl, -d), g) * light.intensity.g * std::exp(-sigmaT * (r + t)) / (r * r);
        };
        auto pdf = [&](double t) { return D / (span * (D * D + (t - t0) * (t - t0))); };
        const int n = 20000;
        const double h = sMax / n;
        double m1 = 0, m2 = 0;
        for (int i = 0; i <= n; ++i) {
            const double t = i * h, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
            m1 += w * f(t) * h / 3;
            m2 += w * f(t) * f(t) / pdf(t) * h / 3;
        }
        const double expected = 3 * (m2 - m1 * m1);  // r + g + b of a grey light
        // The pilot's own estimator (kPilotDraws draws, its unbiased sample variance) over many
        // segments' keys: its mean against the closed form.
        const int segments = 20000;
        double sum = 0, sum2 = 0;
        for (int k = 0; k < segments; ++k) {
            const double v = equiangularSegmentVariance(eq, 0, o, d, sMax, 1, A::kPilotDraws, 7, uint64_t(k));
            sum += v;
            sum2 += v * v;
        }
        const double mean = sum / segments;
        const double se = std::sqrt(std::max(0.0, sum2 / segments - mean * mean) / (segments - 1));
        std::printf("g %.1f: variance by quadrature %.6g, pilot %.6g +- %.2g\n", g, expected, mean, se);
        EXPECT_LT(se, 0.03 * expected) << "too noisy to test";
        EXPECT_NEAR(mean, expected, 4 * se) << "g = " << g;
    }
}

// ---- 3. Deterministic ----

/// A small fog box lit by a point light above slats that cast shadows through the fog.
Scene slattedFog() {
    Scene s = openFog({test::pointLight({0.0f, 1.2f, 0.0f}, 4.0f)}, 0.0f);
    for (int i = 0; i < 6; ++i)
        s.meshes.push_back(makeQuad("slat", {-1.5f + 0.5f * float(i), 0.9f, -1.5f}, {0.25f, 0, 0}, {0, 0, 3.0f}, 0));
    s.camera = Camera::lookAt({0, 0.2f, 3}, {0, 0.2f, 0}, {0, 1, 0}, 0.9f);
    s.finalize();
    return s;
}

RenderSettings smallSettings(uint64_t seed) {
    RenderSettings r;
    r.width = 32;
    r.height = 32;
    r.photonsPerPass = 500;
    r.passes = 16;
    r.seed = seed;
    r.threads = 2;
    r.gpu = GpuMode::Off;
    return r;
}

TEST(EquiangularAuto, PilotIsAFunctionOfSceneAndSettingsNotTheSeed) {
    const Scene scene = slattedFog();
    EmbreeScene rt(scene);
    const RenderSettings a = resolveRadiusDefaults(smallSettings(1), rt);
    const RenderSettings b = resolveRadiusDefaults(smallSettings(2), rt);
    const EquiangularPilot pa = runEquiangularPilot(scene, a), pb = runEquiangularPilot(scene, b);
    std::printf("pilot: V_ea %.4g (stratified %.4g), V_rest %.4g, C_0/c %.3g -> %.4g samples\n",
                pa.equiangularVariance, pa.stratifiedVariance, pa.restVariance, pa.costRatio, pa.samples);
    EXPECT_GT(pa.equiangularVariance, 0);
    EXPECT_GT(pa.passVariance, 0);
    EXPECT_EQ(pa.pixels, 32 * 32);
    EXPECT_EQ(pa.segments, 32 * 32);
    EXPECT_EQ(pa.equiangularVariance, pb.equiangularVariance);
    EXPECT_EQ(pa.stratifiedVariance, pb.stratifiedVariance);
    EXPECT_EQ(pa.passVariance, pb.passVariance);
    EXPECT_EQ(pa.samples, pb.samples);
    EXPECT_GE(pa.samples, A::kMin);
    EXPECT_LE(pa.samples, A::kMax);
}

}  // namespace
}  // namespace tyndall
