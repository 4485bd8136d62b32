// Self-checks of the reference path tracer: a furnace with a closed-form answer, the agreement of
// its sampling strategies with each other (NEE + MIS against paths alone, equiangular against
// free-flight light sampling), and determinism over thread counts.
//
// Statistics: estimates are compared through their standard errors, computed from the per-pixel
// sample variances (pixels are independent; the three channels of a pixel share paths, so the
// variance of their sum is bounded by the square of the summed standard deviations). Block means
// over 4x4-pixel blocks and the image mean must agree within 4.5 standard errors (a Gaussian
// false alarm over all comparisons of a test has probability < 1e-4), and each standard error
// must be small enough (stated per test) that a wrong weight would be caught.
#include "cpu/reference_tracer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

/// Sum over the pixels of a block (all three channels) and the variance of that sum.
struct BlockSum {
    double sum = 0, var = 0;
};

BlockSum blockSum(const ReferenceImage& img, int x0, int y0, int x1, int y1) {
    BlockSum b;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            double sd = 0;
            for (int c = 0; c < 3; ++c) {
                b.sum += img.mean.at(x, y)[c];
                sd += std::sqrt(double(img.varianceOfMean.at(x, y)[c]));
            }
            b.var += sd * sd;
        }
    return b;
}

/// Two independent renders of the same image agree block by block and overall; the relative
/// standard error of the whole-image difference must stay below `maxRelStdErr`.
void expectSameImage(const ReferenceImage& a, const ReferenceImage& b, double maxRelStdErr, const char* what) {
    const int w = a.mean.width, h = a.mean.height, block = 4;
    BlockSum ta = blockSum(a, 0, 0, w, h), tb = blockSum(b, 0, 0, w, h);
    double se = std::sqrt(ta.var + tb.var);
    std::printf("%s: image sums %.4f vs %.4f (difference %.2f standard errors, relative standard error %.4f)\n", what,
                ta.sum, tb.sum, (ta.sum - tb.sum) / se, se / ta.sum);
    EXPECT_LT(se / ta.sum, maxRelStdErr) << what << ": too noisy to test";
    EXPECT_LT(std::abs(ta.sum - tb.sum), 4.5 * se) << what << ": image means differ";
    for (int y = 0; y < h; y += block)
        for (int x = 0; x < w; x += block) {
            BlockSum ba = blockSum(a, x, y, x + block, y + block), bb = blockSum(b, x, y, x + block, y + block);
            double s = std::sqrt(ba.var + bb.var);
            if (s == 0) {
                EXPECT_EQ(ba.sum, bb.sum) << what << ": block (" << x << ", " << y << ")";
                continue;
            }
            EXPECT_LT(std::abs(ba.sum - bb.sum), 4.5 * s)
                << what << ": block (" << x << ", " << y << "): " << ba.sum << " vs " << bb.sum;
        }
    if (::testing::Test::HasFailure()) {
        test::writeEvidence(std::string(what) + "_a", a.mean);
        test::writeEvidence(std::string(what) + "_b", b.mean);
    }
}

ReferenceImage renderReference(const Scene& scene, ReferenceSettings settings) {
    EmbreeScene rt(scene);
    return ReferenceTracer(rt, settings).render();
}

/// A closed emissive diffuse box (albedo rho, emission Le on the inside) full of a non-absorbing,
/// forward-scattering medium. Radiance is Le / (1 - rho) everywhere, in every direction.
Scene makeFurnace(float rho, float le) {
    Scene s;
    s.name = "furnace";
    s.source = "<test scene>";
    Material wall;
    wall.name = "glowing wall";
    wall.albedo = Rgb(rho);
    wall.emission = Rgb(le);
    s.materials.push_back(wall);
    Medium m;
    m.name = "white fog";
    m.sigmaS = Rgb(0.8f, 0.5f, 0.3f);
    m.sigmaA = Rgb(0.0f);
    m.g = 0.6f;
    s.media.push_back(m);
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("box", {-1, -1, -1}, {1, 1, 1}, 0, /*inward=*/true));
    s.camera = Camera::lookAt({0.3f, -0.2f, 0.5f}, {-0.4f, 0.1f, -1.0f}, {0, 1, 0}, 1.2f);
    s.finalize();
    s.validate();
    return s;
}

TEST(ReferenceTracer, WhiteFurnaceWithMediumIsLeOverOneMinusRho) {
    const float rho = 0.5f, le = 1.0f, expected = le / (1.0f - rho);
    Scene scene = makeFurnace(rho, le);
    for (bool nee : {true, false}) {
        ReferenceSettings s;
        s.width = s.height = 8;
        s.samplesPerPixel = 2048;
        s.nextEventEstimation = nee;
        ReferenceImage img = renderReference(scene, s);
        BlockSum total = blockSum(img, 0, 0, 8, 8);
        double n = 3.0 * 64, mean = total.sum / n, se = std::sqrt(total.var) / n;
        std::printf("furnace, NEE %s: mean %.5f +- %.5f (expected %.1f)\n", nee ? "on" : "off", mean, se, expected);
        EXPECT_LT(se, 0.003 * expected);
        EXPECT_NEAR(mean, expected, 4.5 * se) << "NEE " << nee;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(img.mean.at(x, y)[c], expected, 4.5 * std::sqrt(img.varianceOfMean.at(x, y)[c]) + 1e-4)
                        << "pixel (" << x << ", " << y << ") channel " << c << ", NEE " << nee;
    }
}

/// A 2 x 2 x 2 grey room lit by a large ceiling panel, with a fog ball behind an Interface hull,
/// a mirror, a glass sphere and thin fog everywhere; optionally a point light and a spot outside
/// the fog ball.
Scene makeLampRoom(bool deltaLights) {
    Scene s;
    s.name = "lamp-room";
    s.source = "<test scene>";
    int grey = test::addMaterial(s, "grey", MaterialType::Diffuse, Rgb(0.6f, 0.55f, 0.5f));
    int panel = test::addMaterial(s, "panel", MaterialType::Diffuse, Rgb(0.3f), Rgb(1.5f, 1.4f, 1.2f));
    int mirror = test::addMaterial(s, "mirror", MaterialType::Mirror, Rgb(0.9f));
    int glass = test::addMaterial(s, "glass", MaterialType::Dielectric, Rgb(1.0f));
    int hull = test::addMaterial(s, "hull", MaterialType::Interface, Rgb(1.0f));
    Medium thin;
    thin.name = "thin fog";
    thin.sigmaS = Rgb(0.1f);
    thin.sigmaA = Rgb(0.02f);
    s.media.push_back(thin);
    Medium dense;
    dense.name = "dense fog";
    dense.sigmaS = Rgb(1.5f, 1.2f, 0.9f);
    dense.sigmaA = Rgb(0.2f);
    dense.g = -0.3f;
    s.media.push_back(dense);
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("room", {-1, 0, -1}, {1, 2, 1}, grey, /*inward=*/true));
    s.meshes.push_back(makeQuad("panel", {-0.5f, 1.99f, -0.5f}, {1.0f, 0, 0}, {0, 0, 1.0f}, panel));
    s.meshes.push_back(makeQuad("mirror", {-0.95f, 0.2f, 0.6f}, {0, 0, -1.2f}, {0, 1.2f, 0}, mirror));
    s.meshes.push_back(makeSphere("glass", {0.5f, 0.3f, -0.4f}, 0.3f, 2, glass));
    TriangleMesh ball = makeSphere("fog ball", {-0.3f, 0.6f, -0.3f}, 0.45f, 2, hull);
    ball.interiorMedium = 1;
    s.meshes.push_back(ball);
    if (deltaLights) {
        Light point;
        point.name = "point";
        point.position = {0.4f, 1.4f, 0.3f};
        point.intensity = Rgb(0.6f);
        s.lights.push_back(point);
        Light spot;
        spot.name = "spot";
        spot.type = LightType::Spot;
        spot.position = {-0.3f, 1.7f, -0.3f};
        spot.direction = {0, -1, 0};
        spot.cosOuterAngle = std::cos(0.5f);
        spot.cosInnerAngle = std::cos(0.35f);
        spot.intensity = Rgb(1.5f);
        s.lights.push_back(spot);
    }
    s.camera = Camera::lookAt({0.2f, 1.0f, 0.95f}, {-0.1f, 0.6f, -1.0f}, {0, 1, 0}, 1.3f);
    s.finalize();
    s.validate();
    return s;
}

TEST(ReferenceTracer, NextEventEstimationWithMisMatchesPathsAlone) {
    // Area light only: paths that hit it and paths that sample it must count it the same, through
    // the thin fog, across the Interface into the dense fog ball, via the mirror and the glass.
    Scene scene = makeLampRoom(false);
    ReferenceSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 256;
    s.seed = 3;
    ReferenceImage withNee = renderReference(scene, s);
    s.samplesPerPixel = 1024;
    s.seed = 4;
    s.nextEventEstimation = false;
    ReferenceImage without = renderReference(scene, s);
    expectSameImage(withNee, without, 0.01, "reference_nee_vs_paths");
}

TEST(ReferenceTracer, EquiangularMatchesFreeFlightLightSampling) {
    // Point and spot lights outside the dense fog ball: both strategies have finite variance here.
    Scene scene = makeLampRoom(true);
    ReferenceSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 256;
    s.seed = 5;
    ReferenceImage equiangular = renderReference(scene, s);
    s.seed = 6;
    s.equiangular = false;
    ReferenceImage freeFlight = renderReference(scene, s);
    expectSameImage(equiangular, freeFlight, 0.01, "reference_equiangular_vs_free_flight");
}

TEST(ReferenceTracer, SameImageWithAnyThreadCount) {
    Scene scene = test::makeConsistencyScene();
    EmbreeScene rt(scene);
    ReferenceSettings s;
    s.width = s.height = 16;
    s.samplesPerPixel = 4;
    ReferenceTracer tracer(rt, s);
    ReferenceImage many = tracer.render();
    ReferenceImage one;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = tracer.render();
    }
    ASSERT_EQ(many.mean.pixels.size(), one.mean.pixels.size());
    EXPECT_EQ(0, std::memcmp(many.mean.pixels.data(), one.mean.pixels.data(), many.mean.pixels.size() * sizeof(Rgb)));
    EXPECT_EQ(0, std::memcmp(many.varianceOfMean.pixels.data(), one.varianceOfMean.pixels.data(),
                             many.varianceOfMean.pixels.size() * sizeof(Rgb)));
    // A pixel's mean is the mean of its keyed samples, whoever computes them.
    Rgb sum;
    for (uint32_t k = 0; k < s.samplesPerPixel; ++k) sum += tracer.sample(5, 9, k);
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(many.mean.at(5, 9)[c], sum[c] / float(s.samplesPerPixel));
    double total = 0;
    for (const Rgb& p : many.mean.pixels) total += p.r + p.g + p.b;
    EXPECT_GT(total, 0.0);
}

TEST(ReferenceTracer, RejectsBadSettings) {
    Scene scene = makeFurnace(0.5f, 1.0f);
    EmbreeScene rt(scene);
    ReferenceSettings s;
    s.samplesPerPixel = 0;
    EXPECT_THROW(ReferenceTracer(rt, s), Error);
    s.samplesPerPixel = 1;
    s.maxDepth = 0;
    EXPECT_THROW(ReferenceTracer(rt, s), Error);
}

}  // namespace
}  // namespace tyndall
