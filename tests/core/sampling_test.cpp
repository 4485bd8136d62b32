// Warps: each sampled density matches its stated pdf (moment checks with fixed seeds).
#include "core/sampling.h"

#include <gtest/gtest.h>

#include "core/rng.h"

using namespace tyndall;

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
