// The environment light (core/environment_light.h) and its piecewise-constant distribution: the
// documented lat-long mapping (image centre +Z, top row +Y, u = 1/4 at +X, rotation about +Y),
// the pdf integrating to 1, the samples' histogram over the texels against luminance x solid angle
// (chi-square, with the texel solid angles and the mapping computed here, not by the light), the
// pdf of a sample equal to pdf(direction), the pdf proportional to the luminance seen, a constant
// map's uniform 1 / (4 pi), an EXR written here read back, and bad texels. Beside a point light in
// the LightSampler: the shadow-ray estimate of the irradiance at a point against I cos / d^2 + pi L,
// and environmentPdf equal to the pdf of its samples.
#include "core/environment_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/image_io.h"
#include "core/light_sampler.h"
#include "core/rng.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

/// A 32 x 16 lat-long map: a sky gradient (bright overhead, dim below the horizon), a warm sun
/// 10^3 times brighter at texel (20, 4), a black band (rows 12..13), colour varying with u.
Image testMap() {
    Image img(32, 16);
    for (int j = 0; j < img.height; ++j)
        for (int i = 0; i < img.width; ++i) {
            float sky = j < 8 ? 1.0f + 0.2f * float(8 - j) : 0.1f;
            img.at(i, j) = Rgb(sky * (0.5f + 0.5f * float(i) / 32.0f), sky, sky * 1.2f);
            if (j == 12 || j == 13) img.at(i, j) = Rgb(0.0f);
        }
    img.at(20, 4) = Rgb(1200.0f, 1000.0f, 800.0f);
    return img;
}

/// The test's own lat-long mapping and rotation (the convention in the header, written again).
Vec3 rotateY(const Vec3& d, float degrees) {
    const double r = double(degrees) * M_PI / 180.0;
    const float c = float(std::cos(r)), s = float(std::sin(r));
    return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}
/// The texel holding `world` and, inside it, which half in phi and which half in solid angle
/// (cos theta): 4 sub-bins of equal solid angle.
void texelOf(const Vec3& world, float rotateDegrees, int w, int h, int* x, int* y, int* sub = nullptr) {
    const Vec3 d = rotateY(world, -rotateDegrees);
    double u = std::atan2(double(d.x), -double(d.z)) / (2.0 * M_PI);
    if (u < 0) u += 1.0;
    const double cosTheta = std::clamp(double(d.y), -1.0, 1.0), v = std::acos(cosTheta) / M_PI;
    *x = std::min(int(u * w), w - 1);
    *y = std::min(int(v * h), h - 1);
    if (sub) {
        const double c0 = std::cos(M_PI * *y / h), c1 = std::cos(M_PI * (*y + 1) / h);
        *sub = (u * w - *x < 0.5 ? 0 : 1) + ((c0 - cosTheta) / (c0 - c1) < 0.5 ? 0 : 2);
    }
}
double texelSolidAngle(int j, int w, int h) {
    return 2.0 * M_PI / w * (std::cos(M_PI * j / h) - std::cos(M_PI * (j + 1) / h));
}

TEST(PiecewiseConstant1D, ChoosesByWeightAndNeverAZeroCell) {
    PiecewiseConstant1D d({1.0, 0.0, 3.0, 0.0});
    EXPECT_FLOAT_EQ(d.probability(0), 0.25f);
    EXPECT_FLOAT_EQ(d.probability(1), 0.0f);
    EXPECT_FLOAT_EQ(d.probability(2), 0.75f);
    EXPECT_EQ(d.sample(0.0f).index, 0);
    EXPECT_EQ(d.sample(0.2f).index, 0);
    EXPECT_NEAR(d.sample(0.2f).remainder, 0.8f, 1e-6f);
    EXPECT_EQ(d.sample(0.25f).index, 2);  // the zero cell between is skipped
    EXPECT_EQ(d.sample(std::nextafter(1.0f, 0.0f)).index, 2);
    PiecewiseConstant1D zero({0.0, 0.0});
    EXPECT_FLOAT_EQ(zero.probability(1), 0.5f);
}

TEST(EnvironmentLight, MappingOfTheDocumentedDirections) {
    // One distinct colour at the centre texel, the top row, the u = 1/4 and u = 3/4 columns at the
    // horizon, the left edge and the bottom row.
    Image img(8, 4);
    for (Rgb& p : img.pixels) p = Rgb(1.0f);
    for (int i = 0; i < 8; ++i) img.at(i, 0) = Rgb(0, 0, 5), img.at(i, 3) = Rgb(0, 5, 5);
    img.at(4, 1) = img.at(4, 2) = Rgb(5, 0, 0);  // the centre (u = 1/2, v = 1/2 at their corner)
    img.at(2, 1) = img.at(2, 2) = Rgb(0, 5, 0);  // u = 1/4 .. 3/8
    img.at(6, 1) = img.at(6, 2) = Rgb(5, 5, 0);  // u = 3/4 .. 7/8
    img.at(0, 1) = img.at(0, 2) = Rgb(5, 0, 5);  // u = 0 .. 1/8
    EnvironmentLight env = EnvironmentLight::fromImage(img, "mapping");
    auto at = [&](Vec3 d) { return env.eval(normalize(d)); };
    const float e = 0.05f;  // a little past the corners, into the marked texels
    EXPECT_EQ(at({-e, 0.01f, 1}).r, 5.0f);       // +Z: the image's centre (u just above 1/2)
    EXPECT_EQ(at({0, 1, 0}).b, 5.0f);            // +Y: the top row
    EXPECT_EQ(at({0, -1, 0}).g, 5.0f);           // -Y: the bottom row
    EXPECT_EQ(at({1, 0.01f, e}).g, 5.0f);        // +X: u = 1/4
    EXPECT_EQ(at({1, 0.01f, e}).r, 0.0f);
    EXPECT_EQ(at({-1, 0.01f, -e}).r, 5.0f);      // -X: u = 3/4
    EXPECT_EQ(at({-1, 0.01f, -e}).g, 5.0f);
    EXPECT_EQ(at({e, 0.01f, -1}).b, 5.0f);       // -Z: the left edge (u just above 0)
    // Rotated 90 degrees about +Y: the centre now faces +X.
    env.setRotation(90.0f);
    EXPECT_EQ(at({1, 0.01f, e}).r, 5.0f);
    EXPECT_EQ(at({1, 0.01f, e}).g, 0.0f);
    // The helpers agree with the header's formulas.
    Vec3 c = EnvironmentLight::directionOf(0.5f, 0.5f);
    EXPECT_NEAR(c.z, 1.0f, 1e-6f);
    Vec2 uv = EnvironmentLight::uvOf({1, 0, 0});
    EXPECT_NEAR(uv.x, 0.25f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.5f, 1e-6f);
}

TEST(EnvironmentLight, PdfIntegratesToOneAndFollowsLuminance) {
    EnvironmentLight env = EnvironmentLight::fromImage(testMap(), "test map");
    env.setRotation(37.0f);
    env.setScale(2.5f);
    // Midpoint quadrature over (cos theta, phi) about the world +Y axis.
    const int nc = 1200, np = 2400;
    double sum = 0;
    for (int i = 0; i < nc; ++i)
        for (int k = 0; k < np; ++k) {
            float c = -1.0f + 2.0f * (float(i) + 0.5f) / nc, phi = 2.0f * kPi * (float(k) + 0.5f) / np;
            float s = safeSqrt(1.0f - c * c);
            sum += env.pdf({s * std::cos(phi), c, s * std::sin(phi)});
        }
    sum *= (2.0 / nc) * (2.0 * M_PI / np);
    EXPECT_NEAR(sum, 1.0, 2e-3);
    // pdf(d) = luminance(L(d)) / luminance(integral of L): the scale cancels.
    Rng rng(7, 1);
    const float total = env.integral().luminance();
    for (int k = 0; k < 1000; ++k) {
        Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
        EXPECT_NEAR(env.pdf(d), env.eval(d).luminance() / total, 1e-5f * (1.0f + env.pdf(d)));
    }
}

TEST(EnvironmentLight, SamplesFollowLuminanceTimesSolidAngle) {
    const Image img = testMap();
    const float rotate = -70.0f;
    EnvironmentLight env = EnvironmentLight::fromImage(img, "test map");
    env.setRotation(rotate);
    const int w = img.width, h = img.height, n = 400000;
    // Bins: each texel's 4 sub-bins of equal solid angle (so a direction not uniform inside its
    // texel fails too).
    std::vector<double> observed(size_t(4 * w * h), 0.0), expected(size_t(4 * w * h), 0.0);
    double total = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            for (int q = 0; q < 4; ++q) {
                expected[size_t(4 * (j * w + i) + q)] = img.at(i, j).luminance() * texelSolidAngle(j, w, h) / 4;
                total += expected[size_t(4 * (j * w + i) + q)];
            }
    for (double& e : expected) e *= n / total;
    Rng rng(11, 3);
    int mismatches = 0;
    for (int k = 0; k < n; ++k) {
        EnvironmentSample s = env.sample(rng.uniform(), rng.uniform());
        ASSERT_GT(s.pdf, 0.0f);
        int x, y, q;
        texelOf(s.wi, rotate, w, h, &x, &y, &q);
        observed[size_t(4 * (y * w + x) + q)] += 1;
        // The sample's pdf and radiance are those of its direction (but on a texel edge, where
        // rounding may put the direction in the neighbour).
        if (std::abs(s.pdf - env.pdf(s.wi)) > 1e-4f * s.pdf || !(s.radiance.r == env.eval(s.wi).r)) ++mismatches;
    }
    EXPECT_LT(mismatches, n / 10000);
    double chi2 = 0;
    int dof = -1;
    for (size_t b = 0; b < observed.size(); ++b) {
        if (expected[b] == 0) {
            EXPECT_EQ(observed[b], 0) << "a black texel was sampled: " << b;
            continue;
        }
        chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++dof;
    }
    // Wilson-Hilferty; 5 sigma (a fixed seed, far from flaky).
    double z = (std::cbrt(chi2 / dof) - (1 - 2.0 / (9 * dof))) / std::sqrt(2.0 / (9 * dof));
    EXPECT_LT(z, 5.0) << "chi2 " << chi2 << " over " << dof << " dof";
}

TEST(EnvironmentLight, ConstantMapIsUniform) {
    EnvironmentLight env = EnvironmentLight::constant(Rgb(0.5f, 1.0f, 2.0f));
    env.setRotation(123.0f);
    Rng rng(3, 3);
    for (int k = 0; k < 1000; ++k) {
        EnvironmentSample s = env.sample(rng.uniform(), rng.uniform());
        EXPECT_NEAR(s.pdf, kInv4Pi, 1e-6f);
        EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f);
        Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
        EXPECT_NEAR(env.pdf(d), kInv4Pi, 1e-6f);
        EXPECT_EQ(env.eval(d).b, 2.0f);
    }
    EXPECT_NEAR(env.integral().g, 4.0f * kPi, 1e-4f);
    // A 2:1 image of one colour is the same light (the texels' solid angles sum to 4 pi).
    Image flat(16, 8);
    for (Rgb& p : flat.pixels) p = Rgb(1.0f);
    EnvironmentLight e2 = EnvironmentLight::fromImage(flat, "flat");
    for (int k = 0; k < 100; ++k) EXPECT_NEAR(e2.pdf(sampleUniformSphere(rng.uniform(), rng.uniform())), kInv4Pi, 1e-6f);
    EXPECT_NEAR(e2.integral().r, 4.0f * kPi, 1e-4f);
    // Black: no samples.
    EXPECT_EQ(EnvironmentLight::constant(Rgb(0.0f)).sample(0.5f, 0.5f).pdf, 0.0f);
}

TEST(EnvironmentLight, ReadsAnExrWrittenHereAndRejectsBadTexels) {
    const std::string path = test::outputDir() + "/environment_light_test.exr";
    const Image img = testMap();
    writeImage(path, img);
    EnvironmentLight env = EnvironmentLight::fromFile(path);
    EXPECT_EQ(env.width(), 32);
    EXPECT_EQ(env.height(), 16);
    EXPECT_EQ(env.name(), path);
    EXPECT_FLOAT_EQ(env.eval(EnvironmentLight::directionOf((20.5f) / 32, 4.5f / 16)).r, 1200.0f);

    try {
        EnvironmentLight::fromFile(test::outputDir() + "/no-such-sky.exr");
        ADD_FAILURE() << "a missing file was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no-such-sky.exr"), std::string::npos) << e.what();
    }
    Image bad = img;
    bad.at(3, 2).g = std::nanf("");
    try {
        EnvironmentLight::fromImage(bad, "sky.exr");
        ADD_FAILURE() << "a NaN texel was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("sky.exr"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("(3, 2)"), std::string::npos) << e.what();
    }
    Image negative = img;
    negative.at(5, 5) = Rgb(-1.0f, 2.0f, -3.0f);  // clamped to 0, documented
    EnvironmentLight clamped = EnvironmentLight::fromImage(negative, "neg");
    Rgb L = clamped.eval(EnvironmentLight::directionOf(5.5f / 32, 5.5f / 16));
    EXPECT_EQ(L.r, 0.0f);
    EXPECT_EQ(L.g, 2.0f);
    EXPECT_EQ(L.b, 0.0f);
}

TEST(EnvironmentLight, LightSamplerEstimatesPointPlusEnvironmentIrradiance) {
    // A point light of intensity I at distance d above x and a constant environment L: the upward
    // irradiance at x is I / d^2 + pi L (nothing occludes in the sampler alone).
    Scene s;
    s.name = "point and sky";
    s.source = "<test>";
    Light point;
    point.name = "point";
    point.position = {0.3f, 2.0f, 0.0f};
    point.intensity = Rgb(4.0f);
    s.lights.push_back(point);
    s.environment = EnvironmentLight::constant(Rgb(0.25f));
    s.finalize();
    LightSampler lights(s);
    ASSERT_EQ(lights.environmentSource(), 1);
    const Vec3 x(0.0f, 0.0f, 0.0f), n(0.0f, 1.0f, 0.0f);
    const Vec3 toLight = point.position - x;
    const double closedForm = 4.0 * dot(normalize(toLight), n) / lengthSquared(toLight) + M_PI * 0.25;
    Rng rng(5, 5);
    double sum = 0;
    const int count = 200000;
    int environmentSamples = 0;
    for (int k = 0; k < count; ++k) {
        DirectLightSample ls = lights.sampleDirect(x, rng);
        ASSERT_GT(ls.pdf, 0.0f);
        sum += ls.incident.g * std::max(0.0f, dot(ls.wi, n)) / ls.pdf;
        if (ls.source == 1) {
            ++environmentSamples;
            EXPECT_FALSE(ls.delta);
            EXPECT_NEAR(lights.environmentPdf(x, ls.wi), ls.pdf, 1e-6f * ls.pdf);
        }
    }
    EXPECT_GT(environmentSamples, count / 10);
    // The estimator's standard deviation is below 2x its mean here: 5 standard errors.
    EXPECT_NEAR(sum / count, closedForm, 5 * 2 * closedForm / std::sqrt(double(count)));
}

}  // namespace
}  // namespace tyndall
