// RenderSettings' typed switches and GPU mode: the text forms written and read at the edges (scene
// render blocks, EXR metadata, checkpoints), the older "on"/"off" text and JSON booleans read, bad
// text refused naming the key, and validate() naming the setting by its key, not by an option.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/settings.h"

namespace tyndall {
namespace {

TEST(Settings, TypedSwitchesRoundTripThroughTheirText) {
    RenderSettings s;
    s.gpu = GpuMode::Off;
    s.simd = false;
    s.directLight = true;
    s.surfaceBoundary = false;
    s.equiangular = true;
    s.filmLightSampling = false;
    s.photonPlanes = true;
    s.transparentFilm = true;
    nlohmann::json j = s.toJson();
    EXPECT_EQ(j.at("gpu"), "off");
    EXPECT_EQ(j.at("simd"), "off");
    EXPECT_EQ(j.at("direct_light"), "on");
    EXPECT_EQ(j.at("surface_boundary"), "off");
    EXPECT_EQ(j.at("equiangular"), "on");
    EXPECT_EQ(j.at("film_light_sampling"), "off");
    EXPECT_EQ(j.at("photon_planes"), "on");
    EXPECT_EQ(j.at("transparent"), "on");
    RenderSettings back = RenderSettings::fromJson(j, "test");
    EXPECT_EQ(back.gpu, GpuMode::Off);
    EXPECT_FALSE(back.simd);
    EXPECT_TRUE(back.directLight);
    EXPECT_FALSE(back.surfaceBoundary);
    EXPECT_TRUE(back.equiangular);
    EXPECT_FALSE(back.filmLightSampling);
    EXPECT_TRUE(back.photonPlanes);
    EXPECT_TRUE(back.transparentFilm);
    EXPECT_FALSE(RenderSettings::fromJson(nlohmann::json{{"transparent", false}}, "test").transparentFilm);
    for (GpuMode m : {GpuMode::Auto, GpuMode::On, GpuMode::Off}) EXPECT_EQ(gpuModeFromText(gpuModeText(m)), m);
}

TEST(Settings, SwitchesReadOnOffTextAndJsonBooleans) {
    RenderSettings s = RenderSettings::fromJson(
        nlohmann::json{{"simd", false}, {"direct_light", "off"}, {"surface_boundary", true}, {"gpu", "on"},
                       {"equiangular", "on"}},
        "test");
    EXPECT_FALSE(s.simd);
    EXPECT_FALSE(s.directLight);
    EXPECT_TRUE(s.surfaceBoundary);
    EXPECT_EQ(s.gpu, GpuMode::On);
    EXPECT_TRUE(s.equiangular);
}

TEST(Settings, BadTextIsRefusedNamingTheKey) {
    for (const auto& [key, value] : std::vector<std::pair<std::string, nlohmann::json>>{
             {"gpu", "yes"}, {"gpu", true}, {"simd", "maybe"}, {"direct_light", 1}, {"surface_boundary", "ON"},
             {"equiangular", "yes"}, {"photon_planes", "1"}, {"equiangular_samples", "many"},
             {"equiangular_samples", true}}) {
        try {
            RenderSettings::fromJson(nlohmann::json{{key, value}}, "scene.json: /render");
            ADD_FAILURE() << key << " = " << value.dump() << " was accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("scene.json: /render/" + key), std::string::npos) << e.what();
        }
    }
    EXPECT_FALSE(onOffFromText("true"));
    EXPECT_FALSE(gpuModeFromText("Auto"));
}

TEST(Settings, ValidateNamesTheSettingKey) {
    RenderSettings s;
    s.alpha = 1.5;
    try {
        s.validate();
        FAIL() << "alpha 1.5 passed";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.key, "alpha");
        EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos) << e.what();
    }
    s = RenderSettings();
    s.width = 0;
    try {
        s.validate();
        FAIL() << "width 0 passed";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.key, "size");
    }
    EXPECT_NO_THROW(RenderSettings().validate());
}

TEST(Settings, EquiangularSamplesReadAutoOrANumberAndResolveBeforeRendering) {
    RenderSettings s;
    EXPECT_EQ(s.toJson().at("equiangular_samples"), "auto");
    s.equiangularSamples = 0.359375;
    EXPECT_EQ(RenderSettings::fromJson(s.toJson(), "test").equiangularSamples, 0.359375);
    EXPECT_EQ(RenderSettings::fromJson(nlohmann::json{{"equiangular_samples", "auto"}}, "test").equiangularSamples,
              RenderSettings::kAutoEquiangularSamples);
    s.equiangularSamples = 65;
    try {
        s.validate();
        FAIL() << "65 samples passed";
    } catch (const SettingError& e) {
        EXPECT_EQ(e.key, "equiangular_samples");
    }
    s.equiangularSamples = -1;
    EXPECT_THROW(s.validate(), SettingError);
    // auto: 4 at the quality bench's 64x64 and 4000 paths per pass, as sqrt(paths per pixel)
    // below (to 1/64), never under 1/4 nor over 4.
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(64, 64, 4000), 4);
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(128, 128, 4000), 2);
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(256, 256, 4000), 1);
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(512, 512, 4000), 0.5);
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(640, 640, 4000), 26.0 / 64);  // 0.4
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(1920, 1080, 4000), 0.25);     // 0.178
    EXPECT_EQ(RenderSettings::autoEquiangularSamples(16, 16, 100000), 4);
    // Resolved into a number, which stays; an explicit one is kept.
    RenderSettings a;
    a.width = a.height = 128;
    a.photonsPerPass = 4000;
    EXPECT_EQ(resolveEquiangularSamples(a).equiangularSamples, 2);
    EXPECT_EQ(resolveEquiangularSamples(a).toJson().at("equiangular_samples"), 2);
    a.equiangularSamples = 7;
    EXPECT_EQ(resolveEquiangularSamples(a).equiangularSamples, 7);
}

}  // namespace
}  // namespace tyndall
