// Henyey-Greenstein: normalisation, pdf equals eval, chi-square of the sampling routine against
// the integrated density, and the sign convention (g > 0 scatters forward) with g = +/-0.7.
#include "core/phase.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"

using namespace tyndall;

namespace {
// Integral of the HG density over cos(theta) in [a, b] (times 2 pi for the azimuth), closed form.
double hgCdfBand(double a, double b, double g) {
    auto F = [g](double mu) {  // antiderivative of 2 pi p(mu) in mu
        if (std::abs(g) < 1e-9) return mu / 2.0;
        return (1.0 - g * g) / (2.0 * g) / std::sqrt(1.0 + g * g - 2.0 * g * mu);
    };
    return F(b) - F(a);
}
}  // namespace

TEST(HenyeyGreenstein, IntegratesToOneOverTheSphere) {
    for (float g : {-0.9f, -0.7f, -0.3f, 0.0f, 0.3f, 0.7f, 0.9f}) {
        const int n = 200000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            double mu = -1.0 + 2.0 * (i + 0.5) / n;
            sum += hgPhase(float(mu), g) * 2.0 * kPi * (2.0 / n);
        }
        EXPECT_NEAR(sum, 1.0, 1e-3) << "g = " << g;
    }
}

TEST(HenyeyGreenstein, SignConventionForwardForPositiveG) {
    // Forward = the direction of travel is kept: cos = +1.
    EXPECT_GT(hgPhase(1.0f, 0.7f), 10.0f * hgPhase(-1.0f, 0.7f));
    EXPECT_GT(hgPhase(-1.0f, -0.7f), 10.0f * hgPhase(1.0f, -0.7f));
    // The mean cosine of HG is g; sampled directions must agree in sign and value.
    for (float g : {0.7f, -0.7f}) {
        Rng rng(3, 4);
        Vec3 w = normalize(Vec3(0.3f, -0.5f, 0.8f));
        double mean = 0;
        const int n = 400000;
        for (int i = 0; i < n; ++i) mean += dot(w, sampleHg(w, g, rng.uniform(), rng.uniform()));
        mean /= n;
        EXPECT_NEAR(mean, g, 0.005) << "g = " << g;
    }
}

TEST(HenyeyGreenstein, SampledPdfEqualsEvalChiSquare) {
    // Histogram of sampled cos(theta) and azimuth against the integrated HG density.
    // 40 x 8 bins; the chi-square statistic with 319 dof has mean 319, sd ~25; threshold 420
    // corresponds to p ~ 1e-4, with a fixed seed.
    for (float g : {-0.7f, 0.0f, 0.3f, 0.7f}) {
        const int nMu = 40, nPhi = 8, n = 800000;
        std::vector<double> counts(nMu * nPhi, 0.0);
        Rng rng(17, 2);
        Vec3 w{0, 0, 1};
        Frame f(w);
        for (int i = 0; i < n; ++i) {
            Vec3 d = f.toLocal(sampleHg(w, g, rng.uniform(), rng.uniform()));
            int bm = std::min(nMu - 1, int((d.z + 1.0f) * 0.5f * nMu));
            float phi = std::atan2(d.y, d.x) + kPi;
            int bp = std::min(nPhi - 1, int(phi / (2 * kPi) * nPhi));
            counts[bm * nPhi + bp] += 1;
        }
        double chi2 = 0;
        for (int bm = 0; bm < nMu; ++bm) {
            double a = -1.0 + 2.0 * bm / nMu, b = -1.0 + 2.0 * (bm + 1) / nMu;
            double expected = n * hgCdfBand(a, b, g) / nPhi;
            for (int bp = 0; bp < nPhi; ++bp) {
                double o = counts[bm * nPhi + bp];
                chi2 += (o - expected) * (o - expected) / expected;
            }
        }
        EXPECT_LT(chi2, 420.0) << "g = " << g;
        EXPECT_GT(chi2, 230.0) << "g = " << g << ": suspiciously perfect fit";
    }
}

TEST(HenyeyGreenstein, SampleWeightIsOne) {
    // Sampling density equals hgPhase: the density of sampled cosines in a small band matches eval.
    const float g = 0.6f;
    Rng rng(5, 5);
    const int n = 2000000;
    int inBand = 0;
    const float mu0 = 0.5f, width = 0.02f;
    for (int i = 0; i < n; ++i) {
        Vec3 d = sampleHg({0, 0, 1}, g, rng.uniform(), rng.uniform());
        inBand += (d.z >= mu0 && d.z < mu0 + width) ? 1 : 0;
    }
    double density = double(inBand) / n / width / (2 * kPi);
    EXPECT_NEAR(density / hgPhase(mu0 + width / 2, g), 1.0, 0.02);
}
