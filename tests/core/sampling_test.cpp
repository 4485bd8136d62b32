// Warps: each sampled density matches its stated pdf (moment checks and chi-square tests over
// (z, phi) bins against the integrated pdf, with fixed seeds).
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/rng.h"

using namespace tyndall;

namespace {

/// Chi-square of `n` directions from `sample(u1, u2)` over nZ x nPhi bins of (z, phi), z in
/// [zMin, 1], against `zMass(a, b)`: the probability that z falls in [a, b] (uniform in phi for
/// both warps tested here). Bins are equal in z.
double chiSquareZPhi(const std::function<Vec3(float, float)>& sample, const std::function<double(double, double)>& zMass,
                     double zMin, int nZ, int nPhi, int n, uint64_t seed) {
    std::vector<double> counts(size_t(nZ) * nPhi, 0.0);
    Rng rng(seed, 7);
    for (int i = 0; i < n; ++i) {
        Vec3 d = sample(rng.uniform(), rng.uniform());
        int bz = std::clamp(int((d.z - zMin) / (1.0 - zMin) * nZ), 0, nZ - 1);
        double phi = std::atan2(double(d.y), double(d.x)) + kPi;
        int bp = std::clamp(int(phi / (2 * kPi) * nPhi), 0, nPhi - 1);
        counts[size_t(bz) * nPhi + bp] += 1;
    }
    double chi2 = 0;
    for (int bz = 0; bz < nZ; ++bz) {
        double a = zMin + (1.0 - zMin) * bz / nZ, b = zMin + (1.0 - zMin) * (bz + 1) / nZ;
        double expected = n * zMass(a, b) / nPhi;
        for (int bp = 0; bp < nPhi; ++bp) {
            double o = counts[size_t(bz) * nPhi + bp];
            chi2 += (o - expected) * (o - expected) / expected;
        }
    }
    return chi2;
}

}  // namespace

TEST(Sampling, UniformSphereMoments) {
    Rng rng(1, 1);
    double mz = 0, mz2 = 0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
        ASSERT_NEAR(length(d), 1.0f, 1e-5);
        mz += d.z, mz2 += d.z * d.z;
    }
    EXPECT_NEAR(mz / n, 0.0, 0.005);
    EXPECT_NEAR(mz2 / n, 1.0 / 3.0, 0.005);
}

TEST(Sampling, CosineHemisphereMoments) {
    // For pdf cos/pi: E[cos] = 2/3, E[cos^2] = 1/2.
    Rng rng(2, 1);
    double m1 = 0, m2 = 0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        Vec3 d = sampleCosineHemisphere(rng.uniform(), rng.uniform());
        ASSERT_GE(d.z, 0.0f);
        m1 += d.z, m2 += d.z * d.z;
    }
    EXPECT_NEAR(m1 / n, 2.0 / 3.0, 0.003);
    EXPECT_NEAR(m2 / n, 0.5, 0.003);
}

// 20 x 16 bins, 319 degrees of freedom: the statistic has mean 319 and sd ~25; 420 is p ~ 1e-4
// (as in phase_test.cpp). A warp that bunches phi (e.g. phi = pi u2) or skews z (z = 1 - 2 u1^2)
// scores in the thousands; the moments above cannot see a phi error at all.
TEST(Sampling, UniformSphereChiSquareOverZAndPhi) {
    // pdf 1/(4 pi): z uniform on [-1, 1], phi uniform.
    double chi2 = chiSquareZPhi(sampleUniformSphere, [](double a, double b) { return (b - a) / 2.0; }, -1.0, 20, 16,
                                400000, 11);
    EXPECT_LT(chi2, 420.0);
    EXPECT_GT(chi2, 230.0) << "suspiciously perfect fit";
}

TEST(Sampling, CosineHemisphereChiSquareOverZAndPhi) {
    // pdf cos/pi: P(z in [a, b]) = b^2 - a^2, phi uniform (the concentric map must not bunch it).
    double chi2 = chiSquareZPhi(sampleCosineHemisphere, [](double a, double b) { return b * b - a * a; }, 0.0, 20, 16,
                                400000, 12);
    EXPECT_LT(chi2, 420.0);
    EXPECT_GT(chi2, 230.0) << "suspiciously perfect fit";
}

TEST(Sampling, UniformConeStaysInsideAndIsUniform) {
    Rng rng(3, 1);
    const float cosMax = 0.8f;
    double m1 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        Vec3 d = sampleUniformCone(rng.uniform(), rng.uniform(), cosMax);
        ASSERT_GE(d.z, cosMax - 1e-6f);
        m1 += d.z;
    }
    EXPECT_NEAR(m1 / n, (1.0 + cosMax) / 2.0, 0.002);  // cos uniform on [cosMax, 1]
    EXPECT_NEAR(uniformConePdf(cosMax), 1.0 / (2 * kPi * 0.2), 1e-5);
}

TEST(Sampling, TriangleBarycentricsAreUniform) {
    Rng rng(4, 1);
    double m1 = 0, m2 = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        Vec2 b = sampleUniformTriangle(rng.uniform(), rng.uniform());
        ASSERT_GE(b.x, 0.0f);
        ASSERT_GE(b.y, 0.0f);
        ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
        m1 += b.x, m2 += b.y;
    }
    EXPECT_NEAR(m1 / n, 1.0 / 3.0, 0.003);
    EXPECT_NEAR(m2 / n, 1.0 / 3.0, 0.003);
}

TEST(Rng, KeyedStreamsAreReproducibleAndDistinct) {
    Rng a = Rng::forKey(1, 2, 3, StreamPurpose::PhotonPath), b = Rng::forKey(1, 2, 3, StreamPurpose::PhotonPath);
    Rng c = Rng::forKey(1, 2, 3, StreamPurpose::CameraPath), d = Rng::forKey(1, 3, 2, StreamPurpose::PhotonPath);
    for (int i = 0; i < 10; ++i) {
        uint32_t va = a.nextUInt();
        EXPECT_EQ(va, b.nextUInt());
        EXPECT_NE(va, c.nextUInt());
        EXPECT_NE(va, d.nextUInt());
    }
    Rng u(9, 9);
    for (int i = 0; i < 100000; ++i) {
        float x = u.uniform();
        ASSERT_GE(x, 0.0f);
        ASSERT_LT(x, 1.0f);
    }
}
