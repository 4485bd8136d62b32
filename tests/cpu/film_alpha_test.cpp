// The transparent film (RenderSettings::transparentFilm) and its coverage (CameraTracer::
// traceSecondary's `alpha`) against closed forms,
// under a constant visible environment: a pixel that sees only the environment reads alpha 0 and
// no radiance (the background is left out; 2 on an opaque film), a pixel on a diffuse card alpha 1, and a pixel that
// sees the environment through a box of homogeneous grey fog behind an Interface hull reads
// 1 - exp(-sigma_t d), d the chord through the box (averaged here over 8 x 8 pinhole rays from
// edge to edge of the pixel; the render averages its jittered camera rays over the passes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/environment_light.h"
#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "loading/mesh_builders.h"
#include "tests/test_scenes.h"

namespace tyndall {
namespace {

constexpr int kSize = 24;
constexpr float kSigmaT = 0.7f;

/// Camera at the origin looking down -z; a card (x in [-1, -0.25]) at z = -4 on the left, a fog
/// box (x in [0.25, 1], z in [-4, -3]) on the right, nothing in the middle strip.
Scene filmScene() {
    Scene s;
    s.name = "film-alpha";
    s.source = "<test>";
    test::addMaterial(s, "card", MaterialType::Diffuse, Rgb(0.5f));
    test::addMaterial(s, "fog hull", MaterialType::Interface, Rgb(0.8f));
    s.meshes.push_back(makeQuad("card", {-1, -1, -4}, {0.75f, 0, 0}, {0, 2, 0}, 0));
    s.meshes.push_back(makeBox("fog box", {0.25f, -1, -4}, {1, 1, -3}, 1, false));
    s.media.push_back(test::homogeneousMedium(Rgb(0.5f), Rgb(kSigmaT - 0.5f)));
    s.meshes[1].interiorMedium = 0;
    s.environment = EnvironmentLight::constant(Rgb(2.0f));
    s.camera = Camera::lookAt({0, 0, 0}, {0, 0, -5}, {0, 1, 0}, 0.3f);
    s.finalize();
    s.validate();
    return s;
}

enum class Pixel { Mixed, Empty, Card, Fog };

/// Each pixel's class and, for fog pixels, the closed form from 8 x 8 pinhole rays.
void classify(const Scene& s, std::vector<Pixel>& cls, std::vector<double>& expect) {
    cls.assign(kSize * kSize, Pixel::Mixed);
    expect.assign(kSize * kSize, 0.0);
    const int sub = 8;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            int counts[3] = {0, 0, 0};
            double a = 0;
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    // From edge to edge: a pixel is pure only if its borders are.
                    const Ray r = s.camera.generateRay(x + float(i) / (sub - 1), y + float(j) / (sub - 1), kSize,
                                                       kSize, {0.5f, 0.5f});
                    const auto at = [&](float z) { return r.d * (z / r.d.z); };  // the ray at depth z
                    const Vec3 card = at(-4.0f), front = at(-3.0f);
                    if (card.x >= -1 && card.x <= -0.25f && std::abs(card.y) <= 1) {
                        ++counts[1];
                    } else if (front.x >= 0.25f && card.x <= 1 && std::abs(card.y) <= 1) {
                        ++counts[2];
                        a += 1.0 - std::exp(-double(kSigmaT) / std::abs(double(r.d.z)));  // chord 1 / |d.z|
                    } else if (std::abs(card.x) < 0.25f) {
                        ++counts[0];
                    }
                }
            const int n = sub * sub;
            Pixel& c = cls[size_t(y) * kSize + x];
            if (counts[0] == n) c = Pixel::Empty;
            if (counts[1] == n) c = Pixel::Card;
            if (counts[2] == n) c = Pixel::Fog, expect[size_t(y) * kSize + x] = a / n;
        }
}

/// The scene with its pixels' classes and closed forms (classify).
struct FilmCase {
    Scene scene = filmScene();
    std::vector<Pixel> cls;
    std::vector<double> expect;
    FilmCase() { classify(scene, cls, expect); }
};

/// PPB's settings for the film scene: kSize x kSize, seed 9.
RenderSettings filmSettings(uint32_t photonsPerPass, bool transparent) {
    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = photonsPerPass;
    ps.seed = 9;
    ps.transparentFilm = transparent;
    return ps;
}

TEST(FilmAlpha, EmptySurfaceAndFogPixelsReadTheirCoverage) {
    const FilmCase film;
    const std::vector<Pixel>& cls = film.cls;
    const std::vector<double>& expect = film.expect;
    PassRenderer opaqueRenderer(film.scene, filmSettings(500, false));
    PassRenderer renderer(film.scene, filmSettings(500, true));
    const int passes = 16;
    std::vector<double> alpha(kSize * kSize, 0.0), radiance(kSize * kSize, 0.0), opaque(kSize * kSize, 0.0);
    for (int p = 0; p < passes; ++p) {
        const PrimaryPass primary = renderer.tracePrimary(uint64_t(p));
        const PhotonMap photons = renderer.tracePhotons(uint64_t(p));
        Image a;
        const Image transparent = renderer.traceSecondary(primary, photons, nullptr, true, nullptr, &a);
        const Image plain = opaqueRenderer.traceSecondary(primary, photons, nullptr, true, nullptr, nullptr);
        ASSERT_EQ(a.width, kSize);
        for (size_t i = 0; i < alpha.size(); ++i) {
            ASSERT_EQ(a.pixels[i].r, a.pixels[i].b) << "alpha in every channel";
            alpha[i] += a.pixels[i].r / double(passes);
            radiance[i] += transparent.pixels[i].average() / double(passes);
            opaque[i] += plain.pixels[i].average() / double(passes);
        }
    }
    int counted[4] = {0, 0, 0, 0};
    double worstFog = 0;
    for (size_t i = 0; i < cls.size(); ++i) {
        ++counted[int(cls[i])];
        switch (cls[i]) {
            case Pixel::Empty:
                EXPECT_EQ(alpha[i], 0.0) << "pixel " << i;
                EXPECT_EQ(radiance[i], 0.0) << "pixel " << i << ": the background is left out";
                EXPECT_NEAR(opaque[i], 2.0, 1e-5) << "pixel " << i << ": an opaque film shows it";
                break;
            case Pixel::Card:
                EXPECT_EQ(alpha[i], 1.0) << "pixel " << i;
                EXPECT_NEAR(radiance[i], opaque[i], 1e-6) << "pixel " << i;
                break;
            case Pixel::Fog:
                // The jittered rays' chords against the 64 pinhole rays': within 2e-3 here.
                EXPECT_NEAR(alpha[i], expect[i], 2e-3) << "pixel " << i;
                worstFog = std::max(worstFog, std::abs(alpha[i] - expect[i]));
                break;
            case Pixel::Mixed:
                EXPECT_GE(alpha[i], 0.0);
                EXPECT_LE(alpha[i], 1.0);
                break;
        }
    }
    std::printf("pixels: %d empty, %d card, %d fog (worst |alpha - closed form| %.2e), %d mixed\n", counted[1],
                counted[2], counted[3], worstFog, counted[0]);
    EXPECT_GT(counted[int(Pixel::Empty)], 20);
    EXPECT_GT(counted[int(Pixel::Card)], 20);
    EXPECT_GT(counted[int(Pixel::Fog)], 20);
}

TEST(FilmAlpha, ThePathTracerWritesTheCoverageRenderDoes) {
    // tyndall reference --transparent: the same coverage as PPB's transparent film, pixel by pixel
    // within the path tracer's noise (a fog path leaves unscattered with probability
    // exp(-sigma_t d): binomial), exact where it must be (empty 0, card 1), no background.
    const FilmCase film;
    const std::vector<Pixel>& cls = film.cls;
    const std::vector<double>& expect = film.expect;
    ReferenceSettings rs;
    rs.width = rs.height = kSize;
    rs.samplesPerPixel = 64;
    rs.seed = 4;
    rs.transparentFilm = true;
    EmbreeScene rt(film.scene);
    const ReferenceImage ref = ReferenceTracer(rt, rs).render();
    ASSERT_EQ(ref.alpha.width, kSize);
    PassRenderer renderer(film.scene, filmSettings(200, true));
    std::vector<double> ppb(kSize * kSize, 0.0);
    const int passes = 8;
    for (int p = 0; p < passes; ++p) {
        Image a;
        renderer.traceSecondary(renderer.tracePrimary(uint64_t(p)), renderer.tracePhotons(uint64_t(p)), nullptr, true,
                                nullptr, &a);
        for (size_t i = 0; i < ppb.size(); ++i) ppb[i] += a.pixels[i].r / double(passes);
    }
    double sumRef = 0, sumPpb = 0, sumVar = 0, worstZ = 0;
    int fog = 0;
    for (size_t i = 0; i < cls.size(); ++i) {
        const double a = ref.alpha.pixels[i].r;
        EXPECT_GE(a, 0.0);
        EXPECT_LE(a, 1.0);
        if (cls[i] == Pixel::Empty) {
            EXPECT_EQ(a, 0.0) << "pixel " << i;
            EXPECT_EQ(ref.mean.pixels[i].average(), 0.0f) << "pixel " << i << ": the background is left out";
        }
        if (cls[i] == Pixel::Card) {
            EXPECT_EQ(a, 1.0) << "pixel " << i;
        }
        if (cls[i] != Pixel::Fog) continue;
        // Binomial over the paths (the path tracer), against PPB's coverage (its own error 2e-3).
        const double var = std::max(expect[i] * (1 - expect[i]), 0.01) / rs.samplesPerPixel;
        worstZ = std::max(worstZ, std::abs(a - ppb[i]) / std::sqrt(var));
        sumRef += a;
        sumPpb += ppb[i];
        sumVar += var;
        ++fog;
    }
    std::printf("fog pixels %d: mean coverage path tracer %.4f, PPB %.4f (+- %.4f); worst pixel %.1f sigma\n", fog,
                sumRef / fog, sumPpb / fog, std::sqrt(sumVar) / fog, worstZ);
    ASSERT_GT(fog, 20);
    EXPECT_NEAR(sumRef / fog, sumPpb / fog, 4 * std::sqrt(sumVar) / fog + 2e-3);
    EXPECT_LT(worstZ, 4.5);
}

}  // namespace
}  // namespace tyndall
