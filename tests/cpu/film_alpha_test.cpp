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

TEST(FilmAlpha, EmptySurfaceAndFogPixelsReadTheirCoverage) {
    const Scene s = filmScene();
    // Each pixel's class and, for fog pixels, the closed form from 8 x 8 pinhole rays.
    std::vector<Pixel> cls(kSize * kSize, Pixel::Mixed);
    std::vector<double> expect(kSize * kSize, 0.0);
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

    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = 500;
    ps.seed = 9;
    PassRenderer opaqueRenderer(s, ps);
    ps.transparentFilm = true;
    PassRenderer renderer(s, ps);
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

}  // namespace
}  // namespace tyndall
