// The dielectric specular layer over diffuse (core/coated_diffuse.h): the Fresnel average, white
// furnace (exactly 1 with a smooth coat, within the single-scattering loss with a rough one),
// chi-square of both samplers against their pdfs, sample weights = eval cos / pdf, reciprocity,
// the Fresnel limits at normal and grazing incidence.
#include <gtest/gtest.h>

#include <random>

#include "core/coated_diffuse.h"
#include "tests/core/bsdf_checks.h"

namespace tyndall {
namespace {

TEST(CoatedDiffuse, FresnelAverageMatchesAFineSum) {
    for (float eta : {1.0f, 1.2f, 1.5f, 2.0f, 3.0f}) {
        const int n = 200000;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            double mu = (i + 0.5) / n;
            sum += 2.0 * mu * fresnelDielectric(float(mu), eta) / n;
        }
        EXPECT_NEAR(fresnelDielectricAverage(eta), sum, 2e-5) << "eta " << eta;
    }
    EXPECT_NEAR(fresnelDielectricAverage(1.0f), 0.0f, 1e-9f);
    EXPECT_NEAR(fresnelDielectricAverage(1.5f), 0.0918, 5e-4);  // the textbook value
}

TEST(CoatedDiffuse, FresnelLimitsAtNormalAndGrazingIncidence) {
    CoatedDiffuse smooth = CoatedDiffuse::make(0.0f, true, 1.5f, Rgb(1.0f));
    // Normal incidence: ((eta - 1) / (eta + 1))^2 = 0.04 reflected, the rest reaches the base.
    CoatedSample s = smooth.sampleSpecular(Vec3(0, 0, 1), 0.5f, 0.5f);
    ASSERT_TRUE(s.valid && s.delta);
    EXPECT_NEAR(s.weight.g, 0.04f, 1e-6f);
    double diffuse = albedoByQuadrature([&](const Vec3& wi) { return smooth.evalDiffuse(Vec3(0, 0, 1), wi).g; });
    EXPECT_NEAR(diffuse, 0.96, 2e-3);
    // Grazing: the coat reflects (almost) everything and the base receives (almost) nothing.
    Vec3 grazing = dirOf(1e-3f, 0.7f);
    s = smooth.sampleSpecular(grazing, 0.5f, 0.5f);
    EXPECT_GT(s.weight.g, 0.99f);
    EXPECT_GT(smooth.specularProbability(grazing), 0.99f);
    EXPECT_LT(albedoByQuadrature([&](const Vec3& wi) { return smooth.evalDiffuse(grazing, wi).g; }), 0.01);
    // A rough coat's diffuse part follows the same F(cos_o), and its specular lobe brightens toward grazing.
    CoatedDiffuse rough = CoatedDiffuse::make(0.5f, false, 1.5f, Rgb(1.0f));
    double specNormal = albedoByQuadrature([&](const Vec3& wi) { return rough.evalSpecular(Vec3(0, 0, 1), wi); });
    double specGrazing = albedoByQuadrature([&](const Vec3& wi) { return rough.evalSpecular(dirOf(0.1f, 0.3f), wi); });
    EXPECT_NEAR(specNormal, 0.04, 0.015);
    EXPECT_GT(specGrazing, 3 * specNormal);
}

/// Mean and standard error of the sample weights (the directional albedo) over n samples.
template <class Bsdf>
std::pair<double, double> sampledAlbedo(const Bsdf& m, const Vec3& wo, int n, uint32_t seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double sum = 0, sum2 = 0;
    for (int k = 0; k < n; ++k) {
        CoatedSample s = m.sample(wo, u(gen), u(gen), u(gen));
        double w = s.valid ? s.weight.g : 0.0;
        sum += w;
        sum2 += w * w;
    }
    double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(CoatedDiffuse, WhiteFurnaceSmoothCoatReflectsEverything) {
    CoatedDiffuse m = CoatedDiffuse::make(0.0f, true, 1.5f, Rgb(1.0f));
    for (float cosO : {1.0f, 0.7f, 0.3f, 0.05f}) {
        Vec3 wo = dirOf(cosO, 0.4f);
        double diffuse = albedoByQuadrature([&](const Vec3& wi) { return m.evalDiffuse(wo, wi).g; }, 600);
        EXPECT_NEAR(m.fresnel(cosO) + diffuse, 1.0, 1e-3) << "cos " << cosO;
        auto [mean, sigma] = sampledAlbedo(m, wo, 100000, 5);
        EXPECT_NEAR(mean, 1.0, 4 * sigma + 1e-4) << "cos " << cosO;
    }
}

// The rough coat's albedo (white base), measured by sampling (and by quadrature of eval). What it
// loses: the GGX single-scattering share of the specular lobe and, toward grazing, the difference
// between F(cos_o), which weights the base, and the Fresnel the lobe sees on its microfacets
// (smaller). Measured (n = 200000, +- 0.0005):
//   roughness    cos 1    cos 0.5   cos 0.15
//   0.2          1.000    1.000     0.947
//   0.5          0.997    0.978     0.713
//   0.8          0.983    0.948     0.634
//   1.0          0.973    0.935     0.613
// It can exceed 1 by a hair where the microfacets' Fresnel exceeds F(cos_o): at most +0.0004
// (roughness 0.1-0.3, cos 0.5-0.8; 2e6 samples of the specular lobe), hence the 1.0005 bound.
TEST(CoatedDiffuse, WhiteFurnaceRoughCoatLosesOnlyTheSingleScatteringShare) {
    for (float roughness : {0.2f, 0.5f, 0.8f, 1.0f}) {
        CoatedDiffuse m = CoatedDiffuse::make(roughness, false, 1.5f, Rgb(1.0f));
        for (float cosO : {1.0f, 0.5f, 0.15f}) {
            Vec3 wo = dirOf(cosO, 0.3f);
            auto [mean, sigma] = sampledAlbedo(m, wo, 200000, 7);
            SCOPED_TRACE("roughness " + std::to_string(roughness) + " cos " + std::to_string(cosO) + ": albedo " +
                         std::to_string(mean));
            EXPECT_LE(mean, 1.0005 + 4 * sigma);  // creates no energy beyond the hair above
            if (roughness >= 0.5f) {                  // the quadrature resolves these lobes
                double quad = albedoByQuadrature([&](const Vec3& wi) { return m.eval(wo, wi).g; }, 600);
                EXPECT_NEAR(mean, quad, 5 * sigma + 0.005 * quad);  // sampling weights = eval / pdf
            }
            EXPECT_GE(mean, cosO >= 0.5f ? 0.93 : roughness <= 0.2f ? 0.94 : 0.6);
        }
    }
}

TEST(CoatedDiffuse, ChiSquareMixtureAndSpecularSamplingMatchTheirPdfs) {
    for (float roughness : {0.3f, 0.7f}) {
        CoatedDiffuse m = CoatedDiffuse::make(roughness, false, 1.5f, Rgb(0.8f, 0.5f, 0.2f));
        Vec3 wo = dirOf(0.6f, 0.4f);
        chiSquare(
            [&](std::mt19937& g, std::uniform_real_distribution<float>& u, Vec3* wi) {
                CoatedSample s = m.sample(wo, u(g), u(g), u(g));
                *wi = s.wi;
                return s.valid;
            },
            [&](const Vec3& wi) { return m.pdf(wo, wi); }, "coated mixture");
        chiSquare(
            [&](std::mt19937& g, std::uniform_real_distribution<float>& u, Vec3* wi) {
                CoatedSample s = m.sampleSpecular(wo, u(g), u(g));
                *wi = s.wi;
                return s.valid;
            },
            [&](const Vec3& wi) { return m.pdfSpecular(wo, wi); }, "coated specular");
    }
}

TEST(CoatedDiffuse, SampleWeightsAreEvalTimesCosineOverPdf) {
    std::mt19937 gen(9);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    CoatedDiffuse m = CoatedDiffuse::make(0.4f, false, 1.4f, Rgb(0.9f, 0.6f, 0.3f));
    int specular = 0;
    for (int k = 0; k < 2000; ++k) {
        Vec3 wo = dirOf(0.05f + 0.95f * u(gen), 2 * kPi * u(gen));
        CoatedSample s = m.sample(wo, u(gen), u(gen), u(gen));
        if (!s.valid) continue;
        specular += s.specular;
        Rgb expect = m.eval(wo, s.wi) * (s.wi.z / m.pdf(wo, s.wi));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expect[c], 1e-4f * (1 + expect[c]));
        CoatedSample t = m.sampleSpecular(wo, u(gen), u(gen));
        if (t.valid) {
            EXPECT_NEAR(t.weight.g, m.evalSpecular(wo, t.wi) * t.wi.z / m.pdfSpecular(wo, t.wi), 1e-4f);
        }
    }
    EXPECT_GT(specular, 100);
}

TEST(CoatedDiffuse, Reciprocity) {
    std::mt19937 gen(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (bool smooth : {false, true}) {
        CoatedDiffuse m = CoatedDiffuse::make(0.4f, smooth, 1.5f, Rgb(0.9f, 0.6f, 0.3f));
        for (int k = 0; k < 2000; ++k) {
            Vec3 a = dirOf(u(gen), 2 * kPi * u(gen)), b = dirOf(u(gen), 2 * kPi * u(gen));
            Rgb fab = m.eval(a, b), fba = m.eval(b, a);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(fab[c], fba[c], 1e-5f * (1 + fab[c]));
        }
    }
}

}  // namespace
}  // namespace tyndall
