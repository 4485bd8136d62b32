// The render region (RenderSettings::region): a pass with a region has, inside it, the whole
// image's pass pixels bit for bit (the same random streams, radii and photons; the secondary
// stage walks the region's whole tiles so the beam query cache sees what it sees in the whole
// image), and 0 outside; fewer camera rays are traced.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "cpu/pass_renderer.h"
#include "loading/default_scene.h"
#include "loading/default_smoke_scene.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

using namespace tyndall;

namespace {

RenderSettings small(uint64_t seed) {
    RenderSettings s;
    s.width = 72;
    s.height = 56;
    s.photonsPerPass = 600;
    s.seed = seed;
    return s;
}

/// Pixels inside `region` that differ from `full` in any bit, and non-zero pixels outside it.
struct RegionCheck {
    int differentInside = 0, nonZeroOutside = 0, nonZeroInside = 0;
};

RegionCheck check(const Image& full, const Image& part, const PixelRegion& region) {
    RegionCheck c;
    for (int y = 0; y < full.height; ++y)
        for (int x = 0; x < full.width; ++x) {
            const Rgb &a = full.at(x, y), &b = part.at(x, y);
            if (region.contains(x, y)) {
                c.differentInside += a.r != b.r || a.g != b.g || a.b != b.b;
                c.nonZeroInside += !b.isBlack();
            } else {
                c.nonZeroOutside += !b.isBlack();
            }
        }
    return c;
}

/// Renders passes 0..2 of `scene` whole and with each region; the region passes must match.
void expectRegionsMatch(const Scene& scene, const RenderSettings& s, const std::vector<PixelRegion>& regions) {
    PassRenderer whole(scene, s);
    for (const PixelRegion& region : regions) {
        RenderSettings r = s;
        r.region = region;
        r.validate();
        PassRenderer part(scene, r);
        for (uint64_t pass : {0, 1, 5}) {
            PassStats wholeStats, partStats;
            Image a = whole.renderPass(pass, &wholeStats), b = part.renderPass(pass, &partStats);
            RegionCheck c = check(a, b, region);
            EXPECT_EQ(c.differentInside, 0) << scene.name << " region " << region.x << " " << region.y << " "
                                            << region.width << " " << region.height << " pass " << pass;
            EXPECT_EQ(c.nonZeroOutside, 0) << scene.name << " pass " << pass;
            EXPECT_GT(c.nonZeroInside, region.width * region.height / 4) << scene.name << ": the region is black";
            EXPECT_LT(partStats.cameraRays, wholeStats.cameraRays / 2) << "the region traced as many camera rays";
            EXPECT_EQ(partStats.photonPaths, wholeStats.photonPaths);
        }
    }
}

// Not aligned to the 8 x 8 tiles nor to the rasterizer's 8-row bands, one at the far corner, one a
// single pixel.
const std::vector<PixelRegion> kRegions = {{13, 9, 29, 21}, {50, 40, 22, 16}, {31, 27, 1, 1}};

}  // namespace

TEST(RenderRegion, DefaultSceneRegionPixelsEqualTheWholeImagesAndTheRestIsZero) {
    Scene scene = makeDefaultScene();
    scene.validate();
    expectRegionsMatch(scene, small(3), kRegions);
}

// Glass in fog: secondary segments gather through the beam BVH and its query cache.
TEST(RenderRegion, CausticThroughGlassInFogMatches) {
    expectRegionsMatch(test::causticScene(), small(11), {{20, 14, 30, 25}, {0, 0, 9, 7}});
}

// A density grid: per-pixel stored free flights, the heterogeneous splat.
TEST(RenderRegion, SmokeGridMatches) {
    expectRegionsMatch(makeDefaultSmokeScene(), small(5), {{17, 11, 27, 31}});
}

TEST(RenderRegion, SettingsValidateAndRoundTripThroughJson) {
    RenderSettings s;
    s.width = 100;
    s.height = 80;
    s.region = {90, 70, 10, 10};
    EXPECT_NO_THROW(s.validate());
    RenderSettings back = RenderSettings::fromJson(s.toJson(), "test");
    EXPECT_TRUE(back.region == s.region);
    EXPECT_EQ(RenderSettings().toJson().count("region"), 0u) << "no region: no key";
    for (PixelRegion bad : {PixelRegion{91, 70, 10, 10}, PixelRegion{0, 0, 0, 5}, PixelRegion{-1, 0, 5, 5}}) {
        s.region = bad;
        try {
            s.validate();
            ADD_FAILURE() << "region " << bad.x << " " << bad.y << " " << bad.width << " " << bad.height;
        } catch (const SettingError& e) {
            EXPECT_EQ(e.key, "region");
            EXPECT_NE(std::string(e.what()).find("inside the 100x80 image"), std::string::npos) << e.what();
        }
    }
    for (const char* bad : {R"({"region": [1, 2, 3]})", R"({"region": [1, 2, 3, -4]})", R"({"region": "all"})"}) {
        try {
            (void)RenderSettings::fromJson(nlohmann::json::parse(bad), "scene.json: render");
            ADD_FAILURE() << bad;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("scene.json: render/region: expected [x, y, width, height]"),
                      std::string::npos)
                << e.what();
        }
    }
    EXPECT_TRUE(RenderSettings::fromJson(nlohmann::json::parse(R"({"region": null})"), "x").region.whole());
}
