// GGX microfacet BSDFs (core/microfacet.h): white furnace (energy within the single-scattering
// loss), chi-square of visible-normal sampling against the pdf, eval/pdf consistency of the sample
// weights, reciprocity (and the radiance/importance adjoint for transmission).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/microfacet.h"
#include "tests/core/bsdf_checks.h"

namespace tyndall {
namespace {

TEST(Microfacet, WhiteFurnaceConductorLosesOnlyTheSingleScatteringShare) {
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double previous = 2.0;
    for (float roughness : {0.2f, 0.5f, 0.8f, 1.0f}) {
        RoughConductor m{Ggx::fromRoughness(roughness), Rgb(1.0f)};
        for (float cosO : {1.0f, 0.5f, 0.15f}) {
            Vec3 wo = dirOf(cosO, 0.3f);
            const int n = 100000;
            double sum = 0, sum2 = 0;
            for (int k = 0; k < n; ++k) {
                MicrofacetSample s = m.sample(wo, u(gen), u(gen));
                double w = s.valid ? s.weight.g : 0.0;
                sum += w;
                sum2 += w * w;
            }
            double mean = sum / n, sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
            SCOPED_TRACE("roughness " + std::to_string(roughness) + " cos " + std::to_string(cosO));
            EXPECT_LE(mean, 1.0 + 4 * sigma + 1e-4);  // never creates energy
            if (roughness >= 0.5f) {  // the quadrature resolves these lobes
                double quad = albedoByQuadrature([&](const Vec3& wi) { return m.eval(wo, wi).g; }, 600);
                EXPECT_NEAR(mean, quad, 5 * sigma + 0.01 * quad);  // sampling weights = eval / pdf
            } else {
                EXPECT_GE(mean, cosO >= 0.5f ? 0.99 : 0.95);  // alpha = 0.04: ~0.2% lost, ~4% grazing
            }
            // The known single-scattering loss: at alpha = 1, D = 1/pi and G = 2 cos_i / (1 + cos_i)
            // for a normal view, so the albedo is (1/4pi) int G dw = 1 - ln 2 = 0.307 (half the
            // microfacets reflect below the horizon).
            if (roughness == 1.0f && cosO == 1.0f) EXPECT_NEAR(mean, 1.0 - std::log(2.0), 4 * sigma);
            if (cosO == 1.0f) {
                EXPECT_LT(mean, previous + 4 * sigma);  // rougher loses more
                previous = mean;
            }
        }
    }
}

TEST(Microfacet, WhiteFurnaceDielectricReflectsPlusTransmitsAtMostOne) {
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float roughness : {0.2f, 0.6f}) {
        for (float eta : {1.5f, 1.0f / 1.5f}) {
            RoughDielectric m{Ggx::fromRoughness(roughness), eta, Rgb(1.0f)};
            Vec3 wo = dirOf(0.7f, 1.1f);
            const int n = 100000;
            double sum = 0;
            for (int k = 0; k < n; ++k) {
                MicrofacetSample s = m.sample(wo, u(gen), u(gen), u(gen), TransportMode::Importance);
                sum += s.valid ? s.weight.g : 0.0;
            }
            double mean = sum / n;
            SCOPED_TRACE("roughness " + std::to_string(roughness) + " eta " + std::to_string(eta));
            EXPECT_LE(mean, 1.01);
            if (roughness < 0.5f) EXPECT_GE(mean, 0.95);
            double quad = albedoByQuadrature([&](const Vec3& wi) { return m.eval(wo, wi, TransportMode::Importance).g; }, 800);
            EXPECT_NEAR(mean, quad, 0.02);
        }
    }
}

TEST(Microfacet, ChiSquareConductorSamplingMatchesPdf) {
    for (float roughness : {0.3f, 0.7f}) {
        RoughConductor m{Ggx::fromRoughness(roughness), Rgb(0.9f)};
        Vec3 wo = dirOf(0.6f, 0.4f);
        chiSquare(
            [&](std::mt19937& g, std::uniform_real_distribution<float>& u, Vec3* wi) {
                MicrofacetSample s = m.sample(wo, u(g), u(g));
                *wi = s.wi;
                return s.valid;
            },
            [&](const Vec3& wi) { return m.pdf(wo, wi); }, "conductor");
    }
}

TEST(Microfacet, ChiSquareDielectricSamplingMatchesPdf) {
    for (float eta : {1.5f, 1.0f / 1.33f}) {
        RoughDielectric m{Ggx::fromRoughness(0.5f), eta, Rgb(1.0f)};
        Vec3 wo = dirOf(0.8f, 2.0f);
        chiSquare(
            [&](std::mt19937& g, std::uniform_real_distribution<float>& u, Vec3* wi) {
                MicrofacetSample s = m.sample(wo, u(g), u(g), u(g), TransportMode::Radiance);
                *wi = s.wi;
                return s.valid;
            },
            [&](const Vec3& wi) { return m.pdf(wo, wi); }, "dielectric");
    }
}

TEST(Microfacet, Reciprocity) {
    std::mt19937 gen(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    RoughConductor c{Ggx::fromRoughness(0.5f), Rgb(0.9f, 0.6f, 0.3f)};
    RoughDielectric d{Ggx::fromRoughness(0.4f), 1.5f, Rgb(1.0f)};
    int transmissions = 0;
    for (int k = 0; k < 2000; ++k) {
        Vec3 a = dirOf(2 * u(gen) - 1, 2 * kPi * u(gen)), b = dirOf(2 * u(gen) - 1, 2 * kPi * u(gen));
        Rgb fab = c.eval(a, b), fba = c.eval(b, a);
        EXPECT_NEAR(fab.r, fba.r, 1e-4f * (1 + fab.r));
        // Reflection is symmetric; transmission in radiance mode is the adjoint of importance mode.
        float rad = d.eval(a, b, TransportMode::Radiance).g, imp = d.eval(b, a, TransportMode::Importance).g;
        EXPECT_NEAR(rad, imp, 1e-3f * (1 + rad)) << "a.z " << a.z << " b.z " << b.z;
        transmissions += a.z * b.z < 0 && rad > 0;
    }
    EXPECT_GT(transmissions, 100);
}

}  // namespace
}  // namespace tyndall
