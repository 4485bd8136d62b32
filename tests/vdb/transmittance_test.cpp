// The stored-distance transmittance (DESIGN.md, Transmittance) and the tracking it rests on,
// against exact transmittance for a constant, a linear-ramp and a slab density, each as an
// analytic field with a tight majorant grid, the same field with only its global maximum as
// majorant, and the field voxelised into an in-memory OpenVDB grid.
//
// Statistical bounds (fixed seeds, so each run is the same draw):
// - Stored distances: kPasses passes x n = 4 distances; the estimate averaged over passes is a
//   mean of M = 4 kPasses independent Bernoulli(Tr(t)) indicators, so its standard deviation is
//   sqrt(Tr (1 - Tr) / M). Checked at 8 distances per case and sampler to within 4.5 sigma
//   (+1e-6): two-sided 6.8e-6 each, so all 144 checks pass with probability ~0.999.
// - Kolmogorov-Smirnov on all M distances (batched as the renderer draws them, and one tracker at a
//   time) against F(t) = 1 - Tr(t) (the atom at +infinity is
//   "passed"): D < 1.95 / sqrt(M), the 0.1% critical value.
// - Ratio tracking, residual ratio tracking and the photon free flight (delta tracking): sample
//   means within 4.5 sigma of Tr(tEnd) and 1 - Tr(tEnd), sigma from the sample variance / binomial
//   formula; residual tracking's variance at most half ratio tracking's in the denser medium.
#include "core/transmittance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/medium.h"
#include "core/rng.h"
#include "cpu/free_flight.h"
#include "tests/test_util.h"
#include "tests/vdb/analytic_density.h"

namespace tyndall {
namespace {

using test::AnalyticDensity;
using Kind = AnalyticDensity::Kind;

enum class Variant { TightMajorant, GlobalMajorant, Vdb };

const char* variantName(Variant v) {
    switch (v) {
        case Variant::TightMajorant:
            return "analytic_tight";
        case Variant::GlobalMajorant:
            return "analytic_global";
        case Variant::Vdb:
            return "vdb";
    }
    return "?";
}

struct Case {
    Kind kind;
    Variant variant;
};

class StoredTransmittance : public ::testing::TestWithParam<Case> {
protected:
    void SetUp() override {
        const Case c = GetParam();
        m_analytic = std::make_shared<AnalyticDensity>(c.kind, c.variant == Variant::TightMajorant ? 8 : 0);
        if (c.variant == Variant::Vdb) {
            m_grid = test::voxelise(*m_analytic, 16);
        } else {
            m_grid = m_analytic;
        }
        m_medium.sigmaS = Rgb(0.9f, 1.0f, 1.1f);  // coloured albedo, grey extinction 1.5
        m_medium.sigmaA = Rgb(0.6f, 0.5f, 0.4f);
        m_medium.density = m_grid;
        // Oblique ray from outside the box through it and out the far side (y, z stay in [0, 1]).
        m_ray = Ray{Vec3(-0.5f, 0.4f, 0.45f), normalize(Vec3(1.0f, 0.1f, 0.05f))};
        m_tEnd = 2.0f / m_ray.d.x;  // to x = 1.5

        // Reference optical depth tau(t) on a fine table: exact for the analytic fields, the
        // grid's own density integrated numerically for the voxelised one.
        const int kTable = 8000;
        m_tauTable.resize(kTable + 1);
        m_tauTable[0] = 0;
        for (int i = 1; i <= kTable; ++i) {
            double t0 = m_tEnd * double(i - 1) / kTable, t1 = m_tEnd * double(i) / kTable;
            double depth =
                c.variant == Variant::Vdb
                    ? test::numericOpticalDepth(*m_grid, m_ray, t0, t1, 8)
                    : m_analytic->integral(m_ray.o.x + m_ray.d.x * t0, m_ray.o.x + m_ray.d.x * t1) / m_ray.d.x;
            m_tauTable[i] = m_tauTable[i - 1] + 1.5 * depth;
        }
    }

    double tau(double t) const {
        double x = std::clamp(t / m_tEnd, 0.0, 1.0) * (m_tauTable.size() - 1);
        size_t i = std::min(size_t(x), m_tauTable.size() - 2);
        double f = x - double(i);
        return m_tauTable[i] * (1 - f) + m_tauTable[i + 1] * f;
    }
    double tr(double t) const { return std::exp(-tau(t)); }
    void checkStoredSets(void (*sampler)(const Medium&, const Ray&, float, Rng&, int, float*));

    std::shared_ptr<AnalyticDensity> m_analytic;
    std::shared_ptr<const DensityGrid> m_grid;
    Medium m_medium;
    Ray m_ray;
    float m_tEnd = 0;
    std::vector<double> m_tauTable;
};

// One pass's stored set: n = 4 distances, drawn the way the renderer draws them (batched) or one
// tracker at a time.
using StoredSetSampler = void (*)(const Medium&, const Ray&, float, Rng&, int, float*);
void batched(const Medium& m, const Ray& r, float tEnd, Rng& rng, int n, float* out) {
    sampleCollisionDistances(m, r, tEnd, rng, n, out);
}
void oneByOne(const Medium& m, const Ray& r, float tEnd, Rng& rng, int n, float* out) {
    for (int k = 0; k < n; ++k) out[k] = sampleCollisionDistance(m, r, tEnd, rng);
}

void StoredTransmittance::checkStoredSets(StoredSetSampler sampler) {
    constexpr int kPasses = 20000, kN = 4;
    const std::vector<float> ts = {0.1f, 0.3f, 0.55f, 0.7f, 0.85f, 1.0f, 1.3f, m_tEnd * 0.999f};
    std::vector<double> sum(ts.size(), 0.0);
    std::vector<double> all;
    all.reserve(kPasses * kN);
    for (int pass = 0; pass < kPasses; ++pass) {
        Rng rng = Rng::forKey(11, pass, 0, StreamPurpose::Transmittance);
        float d[kN];
        sampler(m_medium, m_ray, m_tEnd, rng, kN, d);
        all.insert(all.end(), d, d + kN);
        for (size_t i = 0; i < ts.size(); ++i) sum[i] += storedTransmittance(d, kN, ts[i]);
    }
    const double m = double(kPasses) * kN;
    for (size_t i = 0; i < ts.size(); ++i) {
        double expected = tr(ts[i]);
        double sigma = std::sqrt(expected * (1 - expected) / m);
        EXPECT_NEAR(sum[i] / kPasses, expected, 4.5 * sigma + 1e-6) << "t = " << ts[i];
    }
    // Kolmogorov-Smirnov over the finite distances and the atom at +infinity.
    std::sort(all.begin(), all.end());
    double ks = 0;
    for (size_t i = 0; i < all.size() && std::isfinite(all[i]); ++i) {
        ASSERT_GE(all[i], 0.0);
        ASSERT_LT(all[i], m_tEnd);
        double f = 1.0 - tr(all[i]);
        ks = std::max({ks, std::abs(double(i + 1) / m - f), std::abs(double(i) / m - f)});
    }
    size_t finite = std::count_if(all.begin(), all.end(), [](double x) { return std::isfinite(x); });
    ks = std::max(ks, std::abs(double(finite) / m - (1.0 - tr(m_tEnd))));
    EXPECT_LT(ks, 1.95 / std::sqrt(m)) << "KS statistic of the collision distances";
}

TEST_P(StoredTransmittance, AveragedOverPassesMatchesAnalytic) {
    checkStoredSets(batched);
}
TEST_P(StoredTransmittance, OneTrackerAtATimeMatchesAnalytic) {
    checkStoredSets(oneByOne);
}

TEST_P(StoredTransmittance, RatioTrackingIsUnbiased) {
    constexpr int kSamples = 20000;
    std::vector<double> xs;
    for (int i = 0; i < kSamples; ++i) {
        Rng rng = Rng::forKey(12, 0, i, StreamPurpose::Transmittance);
        Rgb t = estimateTransmittance(m_medium, m_ray, m_tEnd, rng);
        ASSERT_EQ(t.r, t.g);
        xs.push_back(t.r);
    }
    test::MeanVar mv = test::meanVar(xs);
    EXPECT_NEAR(mv.mean, tr(m_tEnd), 4.5 * std::sqrt(mv.var / kSamples) + 1e-6);
}

// Residual ratio tracking against the density comb (residualTransmittance, what shadow rays, the
// equiangular legs and camera segments use): unbiased at the fixture's extinction (where the tight
// majorant grid's pieces are thin enough for plain ratio tracking on most of them and the global
// majorant's single piece gets a comb) and at kDense times it (a comb on every piece); there its
// variance is at most half plain ratio tracking's on the same ray.
TEST_P(StoredTransmittance, ResidualTrackingIsUnbiasedAndSteadierThanRatioTracking) {
    constexpr int kSamples = 20000;
    constexpr float kDense = 3.0f;
    for (const float scale : {1.0f, kDense}) {
        Medium medium = m_medium;
        medium.sigmaS = m_medium.sigmaS * scale;
        medium.sigmaA = m_medium.sigmaA * scale;
        const double exact = std::exp(-double(scale) * tau(m_tEnd));
        std::vector<double> residual, ratio;
        for (int i = 0; i < kSamples; ++i) {
            Rng rng = Rng::forKey(14, 0, i, StreamPurpose::Transmittance);
            const float t = residualTransmittance(medium, m_ray, m_tEnd, rng);
            ASSERT_GE(t, 0.0f);
            residual.push_back(t);
            Rng rng2 = Rng::forKey(15, 0, i, StreamPurpose::Transmittance);
            ratio.push_back(ratioTrackingTransmittance(medium, m_ray, m_tEnd, rng2).r);
        }
        const test::MeanVar r = test::meanVar(residual), p = test::meanVar(ratio);
        EXPECT_NEAR(r.mean, exact, 4.5 * std::sqrt(r.var / kSamples) + 1e-6) << "extinction x " << scale;
        EXPECT_NEAR(p.mean, exact, 4.5 * std::sqrt(p.var / kSamples) + 1e-6) << "extinction x " << scale;
        if (scale == kDense) {
            EXPECT_LE(r.var, 0.5 * p.var) << "residual " << r.var << " ratio " << p.var;
        }
    }
}

// One residual tracker read at several distances on the way (residualTransmittanceAlong, what the
// equiangular samples of a grid segment share): each read unbiased for Tr(0, t) at both
// extinctions, distances inside pieces and at the ray's ends; its end value and draws those of
// residualTransmittance with the same stream, bit for bit.
TEST_P(StoredTransmittance, ResidualTrackerReadAlongTheRayIsUnbiasedAtEachDistance) {
    constexpr int kSamples = 20000, kReads = 7;
    constexpr float kDense = 3.0f;
    const float at[kReads] = {0.0f, 0.07f * m_tEnd, 0.23f * m_tEnd, 0.41f * m_tEnd, 0.5f * m_tEnd, 0.83f * m_tEnd,
                              m_tEnd};
    for (const float scale : {1.0f, kDense}) {
        Medium medium = m_medium;
        medium.sigmaS = m_medium.sigmaS * scale;
        medium.sigmaA = m_medium.sigmaA * scale;
        std::vector<double> reads[kReads];
        for (int i = 0; i < kSamples; ++i) {
            Rng rng = Rng::forKey(16, 0, i, StreamPurpose::Transmittance), same = rng;
            float out[kReads];
            const float end = residualTransmittanceAlong(medium, m_ray, m_tEnd, at, kReads, out, rng);
            ASSERT_EQ(end, residualTransmittance(medium, m_ray, m_tEnd, same));
            ASSERT_EQ(rng.uniform(), same.uniform()) << "the reads drew from the stream";
            ASSERT_EQ(out[kReads - 1], end);
            for (int k = 0; k < kReads; ++k) {
                ASSERT_GE(out[k], 0.0f);
                reads[k].push_back(out[k]);
            }
        }
        for (int k = 0; k < kReads; ++k) {
            const double exact = std::exp(-double(scale) * tau(at[k]));
            const test::MeanVar mv = test::meanVar(reads[k]);
            EXPECT_NEAR(mv.mean, exact, 4.5 * std::sqrt(mv.var / kSamples) + 1e-6)
                << "extinction x " << scale << ", read at " << at[k] << " of " << m_tEnd;
        }
    }
}

TEST_P(StoredTransmittance, PhotonFreeFlightScattersWithTheRightProbabilityAndWeight) {
    constexpr int kSamples = 40000;
    int scattered = 0;
    for (int i = 0; i < kSamples; ++i) {
        Rng rng = Rng::forKey(13, 0, i, StreamPurpose::PhotonPath);
        FreeFlight ff = sampleFreeFlight(m_medium, m_ray, m_tEnd, rng);
        if (ff.scattered) {
            ++scattered;
            ASSERT_LT(ff.t, m_tEnd);
            ASSERT_GT(m_grid->density(m_ray.at(ff.t)), 0.0f) << "a real collision where there is no medium";
            Rgb albedo = m_medium.albedo();
            ASSERT_FLOAT_EQ(ff.weight.r, albedo.r);
            ASSERT_FLOAT_EQ(ff.weight.b, albedo.b);
        } else {
            ASSERT_EQ(ff.t, m_tEnd);
            ASSERT_EQ(ff.weight.g, 1.0f);
        }
    }
    double p = 1.0 - tr(m_tEnd);
    EXPECT_NEAR(double(scattered) / kSamples, p, 4.5 * std::sqrt(p * (1 - p) / kSamples));
}

std::vector<Case> allCases() {
    std::vector<Case> cs;
    for (Kind k : {Kind::Constant, Kind::Ramp, Kind::Slab})
        for (Variant v : {Variant::TightMajorant, Variant::GlobalMajorant, Variant::Vdb}) cs.push_back({k, v});
    return cs;
}

INSTANTIATE_TEST_SUITE_P(Densities, StoredTransmittance, ::testing::ValuesIn(allCases()),
                         [](const ::testing::TestParamInfo<Case>& info) {
                             return std::string(test::kindName(info.param.kind)) + "_" +
                                    variantName(info.param.variant);
                         });

// The stored estimate is a step function of t that is exactly the fraction of distances beyond t.
TEST(StoredTransmittanceFunction, CountsDistancesBeyond) {
    const float d[4] = {0.5f, kInfinity, 2.0f, 0.25f};
    EXPECT_EQ(storedTransmittance(d, 4, 0.0f), 1.0f);
    EXPECT_EQ(storedTransmittance(d, 4, 0.3f), 0.75f);
    EXPECT_EQ(storedTransmittance(d, 4, 1.0f), 0.5f);
    EXPECT_EQ(storedTransmittance(d, 4, 5.0f), 0.25f);
}

}  // namespace
}  // namespace tyndall
