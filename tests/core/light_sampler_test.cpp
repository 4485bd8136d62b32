// Light sampling (LightSampler): the photon choice frequencies follow the power-proportional
// probabilities; next-event estimation (sampleDirect / directPdf / directChoiceProbability) chooses
// by what each source sends to the point, the pdf a scattered path would use for MIS equals the
// pdf of the sample, and the irradiance estimated from the samples matches the closed forms
// (Lambert's for a polygonal area light, I cos / d^2 for point and spot lights).
#include "core/light_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/pixel_jitter.h"
#include "loading/mesh_builders.h"

namespace tyndall {
namespace {

/// A point light, a spot and a 1 x 1 emissive quad (two triangles) facing down at height 1.
Scene makeLights() {
    Scene s;
    s.name = "lights";
    s.source = "<test>";
    Material lamp;
    lamp.name = "lamp";
    lamp.emission = Rgb(2.0f, 1.0f, 0.5f);
    s.materials.push_back(lamp);
    s.meshes.push_back(makeQuad("panel", {-0.2f, 1.0f, -0.4f}, {1.0f, 0, 0}, {0, 0, 1.0f}, 0));
    Light point;
    point.name = "point";
    point.position = {0.0f, 2.0f, 0.0f};
    point.intensity = Rgb(0.5f);
    s.lights.push_back(point);
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0, -1, 0};
    spot.cosOuterAngle = 0.8f;
    spot.cosInnerAngle = 0.9f;
    spot.intensity = Rgb(3.0f);
    s.lights.push_back(spot);
    s.finalize();
    s.validate();
    return s;
}

/// The panel's irradiance at x (normal n), red channel, by Lambert's formula: E = Le/2 sum_edges
/// angle(r_i, r_i+1) dot(unit(r_i x r_i+1), n), r_i the unit directions to its vertices.
double panelIrradiance(const Scene& scene, const Vec3& x, const Vec3& n) {
    const TriangleMesh& panel = scene.meshes[0];
    std::vector<Vec3> r;
    for (int k : {0, 1, 2, 3}) r.push_back(normalize(panel.positions[k] - x));
    double lambert = 0;
    for (size_t i = 0; i < 4; ++i) {
        Vec3 a = r[i], b = r[(i + 1) % 4];
        lambert += std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0)) * dot(normalize(cross(a, b)), n);
    }
    return std::abs(lambert) * 0.5 * scene.materials[0].emission.r;
}

TEST(LightSampler, ChoiceFrequenciesFollowPower) {
    Scene scene = makeLights();
    LightSampler lights(scene);
    ASSERT_EQ(lights.sourceCount(), 4u);
    std::vector<int> counts(4, 0);
    Rng rng = Rng::forKey(1, 0, 0, StreamPurpose::Test);
    const int n = 200000;
    for (int i = 0; i < n; ++i) counts[lights.chooseSource(rng.uniform())]++;
    double chi2 = 0, total = 0;
    for (size_t i = 0; i < 4; ++i) {
        double p = lights.sourceProbability(i), expected = n * p;
        EXPECT_NEAR(p, lights.sourcePower(i).luminance() / lights.totalPower().luminance(), 1e-6);
        chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
        total += p;
    }
    EXPECT_NEAR(total, 1.0, 1e-6);
    EXPECT_LT(chi2, 16.3);  // chi-square, 3 degrees of freedom, p = 0.001
}

TEST(LightSampler, DirectSamplesAgreeWithDirectPdfAndLambertIrradiance) {
    Scene scene = makeLights();
    LightSampler lights(scene);
    const Vec3 x(0.1f, 0.0f, 0.2f), n(0, 1, 0);
    Rng rng = Rng::forKey(2, 0, 0, StreamPurpose::Test);
    const int samples = 400000;
    double sum = 0, sum2 = 0;
    int areaSamples = 0;
    for (int i = 0; i < samples; ++i) {
        DirectLightSample s = lights.sampleDirect(x, rng);
        ASSERT_GE(s.source, 0);
        double e = 0;
        if (s.source >= 2) {  // the panel's triangles
            ++areaSamples;
            ASSERT_FALSE(s.delta);
            ASSERT_GT(s.pdf, 0.0f);
            EXPECT_NEAR(lights.directPdf(size_t(s.source), x, s.point) / s.pdf, 1.0, 1e-4);
            EXPECT_EQ(lights.emitterSource(0, uint32_t(s.source - 2)), s.source);
            e = s.incident.r * std::max(0.0f, dot(s.wi, n)) / s.pdf;
        } else {
            ASSERT_TRUE(s.delta);
            EXPECT_NEAR(s.pdf, lights.directChoiceProbability(size_t(s.source), x), 1e-7);
            float d = length(scene.lights[s.source].position - x);
            float falloff = s.source == 1 ? scene.lights[1].spotFalloff(dot(-s.wi, scene.lights[1].direction)) : 1.0f;
            EXPECT_NEAR(s.incident.r, scene.lights[s.source].intensity.r * falloff / (d * d), 1e-5);
        }
        sum += e;
        sum2 += e * e;
    }
    EXPECT_GT(areaSamples, 0);
    const double lambert = panelIrradiance(scene, x, n);
    double mean = sum / samples, se = std::sqrt((sum2 / samples - mean * mean) / samples);
    std::printf("irradiance from samples %.5f +- %.5f, Lambert %.5f\n", mean, se, lambert);
    EXPECT_LT(se, 0.005 * lambert);
    EXPECT_NEAR(mean, lambert, 4.0 * se);
    // A point behind the panel gets nothing from it.
    Rng rng2 = Rng::forKey(3, 0, 0, StreamPurpose::Test);
    for (int i = 0; i < 1000; ++i) {
        DirectLightSample s = lights.sampleDirect(Vec3(0.0f, 1.5f, 0.0f), rng2);
        if (s.source >= 2) {
            EXPECT_EQ(s.pdf, 0.0f);
        }
    }
}

/// Irradiance at x (normal n) of every source of makeLights(): point and spot in closed form,
/// the panel by panelIrradiance.
double exactIrradiance(const Scene& scene, const Vec3& x, const Vec3& n) {
    double e = 0;
    for (const Light& l : scene.lights) {
        Vec3 toLight = l.position - x;
        float d = length(toLight);
        Vec3 wi = toLight / d;
        float falloff = l.type == LightType::Spot ? l.spotFalloff(dot(-wi, l.direction)) : 1.0f;
        e += l.intensity.r * falloff * std::max(0.0f, dot(wi, n)) / (d * d);
    }
    return e + panelIrradiance(scene, x, n);
}

TEST(LightSampler, DirectChoiceFollowsWhatEachSourceSendsToThePoint) {
    Scene scene = makeLights();
    LightSampler lights(scene);
    // Outside the spot's cone (cos 0.8 around straight down from (0, 3, 0)): the spot is never
    // chosen, though by power it would take a fifth of the shadow rays. Just under the spot it
    // gets most of them. The probabilities sum to one everywhere.
    const Vec3 outside(2.5f, 0.0f, 0.0f);
    EXPECT_EQ(lights.directChoiceProbability(1, outside), 0.0f);
    EXPECT_GT(lights.sourceProbability(1), 0.2f);
    EXPECT_GT(lights.directChoiceProbability(1, Vec3(0.1f, 2.6f, 0.05f)), 0.8f);
    for (Vec3 x : {outside, Vec3(0.1f, 2.6f, 0.05f), Vec3(0.1f, 0.0f, 0.2f)}) {
        double total = 0;
        for (size_t i = 0; i < lights.sourceCount(); ++i) total += lights.directChoiceProbability(i, x);
        EXPECT_NEAR(total, 1.0, 1e-6);
    }
    // The choice frequencies at a point follow directChoiceProbability (chi-square, 3 degrees of
    // freedom, p = 0.001), and the estimate of the irradiance from all sources is unbiased against
    // the closed forms, at a point lit by all three and at one outside the spot.
    for (Vec3 x : {Vec3(0.1f, 0.0f, 0.2f), outside}) {
        const Vec3 n(0, 1, 0);
        Rng rng = Rng::forKey(4, 0, 0, StreamPurpose::Test);
        const int samples = 200000;
        std::vector<int> counts(4, 0);
        double sum = 0, sum2 = 0;
        for (int i = 0; i < samples; ++i) {
            DirectLightSample s = lights.sampleDirect(x, rng);
            ASSERT_GE(s.source, 0);
            counts[size_t(s.source)]++;
            double e = s.pdf > 0 ? s.incident.r * std::max(0.0f, dot(s.wi, n)) / s.pdf : 0.0;
            sum += e;
            sum2 += e * e;
        }
        double chi2 = 0;
        for (size_t i = 0; i < 4; ++i) {
            double expected = samples * lights.directChoiceProbability(i, x);
            if (expected > 0) chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
            else EXPECT_EQ(counts[i], 0);
        }
        EXPECT_LT(chi2, 16.3);
        double exact = exactIrradiance(scene, x, n);
        double mean = sum / samples, se = std::sqrt((sum2 / samples - mean * mean) / samples);
        std::printf("at (%g, %g, %g): irradiance from samples %.5f +- %.5f, closed form %.5f\n", x.x, x.y, x.z, mean,
                    se, exact);
        EXPECT_LT(se, 0.01 * exact);
        EXPECT_NEAR(mean, exact, 4.0 * se);
    }
}

/// Per channel c: the closed-form irradiance at x (normal n) from every light and the panel.
double exactIrradianceChannel(const Scene& scene, const Vec3& x, const Vec3& n, int c) {
    double e = 0;
    for (const Light& l : scene.lights) {
        Vec3 toLight = l.position - x;
        float d = length(toLight);
        Vec3 wi = toLight / d;
        float falloff = l.type == LightType::Spot ? l.spotFalloff(dot(-wi, l.direction)) : 1.0f;
        const float intensity = c == 0 ? l.intensity.r : c == 1 ? l.intensity.g : l.intensity.b;
        e += intensity * falloff * std::max(0.0f, dot(wi, n)) / (d * d);
    }
    const Rgb le = scene.materials[0].emission;
    return e + panelIrradiance(scene, x, n) * (c == 0 ? 1.0 : c == 1 ? le.g / le.r : le.b / le.r);
}

TEST(LightSampler, ReceiverChoiceFollowsTintAndCosineAndStaysUnbiased) {
    // makeLights' point light, spot and panel, the point light made orange, plus a blue light low
    // at the side (grazing at the receiver) and one under the floor (it cannot light the receiver).
    Scene scene = makeLights();
    scene.lights[0].intensity = Rgb(1.0f, 0.5f, 0.1f);
    Light blue = scene.lights[0], under = scene.lights[0];
    blue.name = "blue";
    blue.position = {1.6f, 0.4f, 0.1f};
    blue.intensity = Rgb(0.1f, 0.4f, 1.5f);
    under.name = "under";
    under.position = {0.2f, -1.0f, 0.0f};
    under.intensity = Rgb(4.0f);
    scene.lights.push_back(blue);
    scene.lights.push_back(under);
    scene.finalize();
    LightSampler lights(scene);
    ASSERT_EQ(lights.sourceCount(), 6u);
    const Vec3 x(0.1f, 0.0f, 0.2f), n(0, 1, 0);
    const DirectReceiver receiver{n, n, Rgb(0.8f, 0.5f, 0.2f)};
    // Probabilities: they sum to one; the light under the floor gets none (without the receiver it
    // gets the most); two point lights' ratio is that of |tint x I| cos / d^2.
    double total = 0;
    for (size_t i = 0; i < lights.sourceCount(); ++i) total += lights.directChoiceProbability(i, x, &receiver);
    EXPECT_NEAR(total, 1.0, 1e-6);
    EXPECT_EQ(lights.directChoiceProbability(3, x, &receiver), 0.0f);
    EXPECT_GT(lights.directChoiceProbability(3, x), 0.3f);
    auto weight = [&](const Light& l) {
        const Vec3 toLight = l.position - x;
        const double d2 = lengthSquared(toLight), cosine = toLight.y / std::sqrt(d2);
        const Rgb c = l.intensity * receiver.tint;
        return std::sqrt(double(c.r) * c.r + double(c.g) * c.g + double(c.b) * c.b) * cosine / d2;
    };
    EXPECT_NEAR(lights.directChoiceProbability(0, x, &receiver) / lights.directChoiceProbability(2, x, &receiver),
                weight(scene.lights[0]) / weight(scene.lights[2]), 1e-4 * weight(scene.lights[0]) / weight(scene.lights[2]));
    // Sampled: the frequencies follow the probabilities (chi-square, 4 degrees of freedom over the
    // five sources that can be chosen, p = 0.001); each channel's estimate of tint x irradiance is
    // unbiased against the closed form (4 standard errors, each below 1%); and the channels' summed
    // variance is lower than with the choice by what the lights send to the point alone.
    const int samples = 200000;
    auto run = [&](const DirectReceiver* r, std::vector<int>* counts, double mean[3], double se[3]) {
        Rng rng = Rng::forKey(6, 0, 0, StreamPurpose::Test);
        double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        for (int i = 0; i < samples; ++i) {
            DirectLightSample s = lights.sampleDirect(x, rng, r);
            EXPECT_GE(s.source, 0);
            if (counts && s.source >= 0) (*counts)[size_t(s.source)]++;
            const Rgb e = s.pdf > 0 ? receiver.tint * s.incident * (std::max(0.0f, dot(s.wi, n)) / s.pdf) : Rgb(0.0f);
            const double v[3] = {e.r, e.g, e.b};
            for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += v[c] * v[c];
        }
        double variance = 0;
        for (int c = 0; c < 3; ++c) {
            mean[c] = sum[c] / samples;
            const double var = sum2[c] / samples - mean[c] * mean[c];
            se[c] = std::sqrt(var / samples);
            variance += var;
        }
        return variance;
    };
    std::vector<int> counts(6, 0);
    double mean[3], se[3], plainMean[3], plainSe[3];
    const double variance = run(&receiver, &counts, mean, se);
    const double plainVariance = run(nullptr, nullptr, plainMean, plainSe);
    double chi2 = 0;
    for (size_t i = 0; i < 6; ++i) {
        double expected = samples * lights.directChoiceProbability(i, x, &receiver);
        if (expected > 0) chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
        else EXPECT_EQ(counts[i], 0);
    }
    EXPECT_LT(chi2, 18.5);
    const double tint[3] = {0.8, 0.5, 0.2};
    for (int c = 0; c < 3; ++c) {
        const double exact = tint[c] * exactIrradianceChannel(scene, x, n, c);
        std::printf("channel %d: tint x irradiance %.5f +- %.5f with the receiver, %.5f +- %.5f without, closed form %.5f\n",
                    c, mean[c], se[c], plainMean[c], plainSe[c], exact);
        EXPECT_LT(se[c], 0.01 * exact);
        EXPECT_NEAR(mean[c], exact, 4.0 * se[c]);
        EXPECT_NEAR(plainMean[c], exact, 4.0 * plainSe[c]);
    }
    std::printf("summed channel variance of one sample: %.4g with the receiver, %.4g without\n", variance,
                plainVariance);
    EXPECT_LT(variance, 0.5 * plainVariance);
}

TEST(LightSampler, LightChoiceUniformIsUniformOverPixelsAndEvenOverPasses) {
    // Over 4096 pixels one pass's values are uniform (chi-square over 16 bins, 15 degrees of
    // freedom, p = 0.001): each pass's choice is unbiased. Over 256 passes a pixel's values fall
    // below p in a share within 3/256 of p for every pixel (independent uniforms scatter by
    // sqrt(p (1 - p) 256) ~ 7 in the count).
    for (uint64_t pass : {0, 7, 200}) {
        std::vector<int> bins(16, 0);
        for (uint64_t pixel = 0; pixel < 4096; ++pixel) {
            const float u = lightChoiceUniform(3, pass, pixel);
            ASSERT_GE(u, 0.0f);
            ASSERT_LT(u, 1.0f);
            bins[size_t(u * 16)]++;
        }
        double chi2 = 0;
        for (int b : bins) chi2 += (b - 256.0) * (b - 256.0) / 256.0;
        EXPECT_LT(chi2, 37.7) << pass;
    }
    int worst = 0;
    for (uint64_t pixel = 0; pixel < 256; ++pixel)
        for (double p : {0.1, 0.3, 0.5, 0.77}) {
            int below = 0;
            for (uint64_t pass = 0; pass < 256; ++pass) below += lightChoiceUniform(3, pass, pixel) < p;
            worst = std::max(worst, int(std::lround(std::abs(below - 256 * p))));
        }
    std::printf("largest count off 256 p over 256 pixels: %d\n", worst);
    EXPECT_LE(worst, 3);
}

TEST(LightSampler, ManyLightsAreChosenByPower) {
    Scene scene = makeLights();
    for (size_t k = scene.lights.size(); k <= LightSampler::kMaxSpatialChoiceLights; ++k) {
        Light l = scene.lights[0];
        l.position = Vec3(float(k), 2.0f, 0.0f);
        scene.lights.push_back(l);
    }
    scene.finalize();
    LightSampler lights(scene);
    const Vec3 x(0.1f, 0.0f, 0.2f);
    for (size_t i = 0; i < lights.sourceCount(); ++i)
        EXPECT_EQ(lights.directChoiceProbability(i, x), lights.sourceProbability(i));
}

}  // namespace
}  // namespace tyndall
