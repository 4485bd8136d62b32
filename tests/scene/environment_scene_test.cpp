// The environment in scene files: "environment" with a file (relative to the scene) or a constant
// radiance, with scale, rotate and visible; --environment (SceneLoadOptions::environment) lighting
// a glTF without lights instead of the headlight; bad input (both or neither of file and radiance,
// a missing or unreadable image, NaN texels, a negative scale, unknown keys) named with the file
// and place; a non-2:1 image warned about; the viewer's edits of its scale and rotation.
#include <gtest/gtest.h>

#include <cmath>

#include "core/image_io.h"
#include "loading/scene_edits.h"
#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

using nlohmann::json;
using test::errorOf;
using test::GltfBuilder;
using test::writeTestFile;

/// A w x h lat-long image: grey 0.5 with the centre texel (w/2, h/2) red 8.
std::string writeSky(const std::string& name, int w, int h) {
    Image img(w, h);
    for (Rgb& p : img.pixels) p = Rgb(0.5f);
    img.at(w / 2, h / 2) = Rgb(8.0f, 0.0f, 0.0f);
    const std::string path = test::outputDir() + "/" + name;
    writeImage(path, img);
    return path;
}

json sceneWith(const json& environment) {
    json j = json::parse(R"({
      "materials": [{"name": "white"}],
      "shapes": [{"type": "sphere", "name": "ball", "material": "white", "center": [0, 0, 0], "radius": 0.5}],
      "cameras": [{"position": [0, 0, 3], "target": [0, 0, 0]}]
    })");
    j["environment"] = environment;
    return j;
}

SceneFile loadJson(const std::string& name, const json& j, std::vector<std::string>* warnings = nullptr,
                   const std::string& environment = "") {
    SceneLoadOptions o;
    o.environment = environment;
    o.warn = [warnings](const std::string& w) {
        if (warnings) warnings->push_back(w);
    };
    return loadSceneFile(writeTestFile(name, j.dump()), o);
}

TEST(EnvironmentScene, FileRelativeToTheSceneWithScaleRotateVisible) {
    writeSky("env_scene_sky.exr", 16, 8);
    std::vector<std::string> warnings;
    Scene s = loadJson("env_file.json",
                       sceneWith({{"file", "env_scene_sky.exr"}, {"scale", 2}, {"rotate", 90}, {"visible", false}}),
                       &warnings)
                  .scene;
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_TRUE(warnings.empty());  // 16 x 8 is 2:1, and the scene is lit: no headlight
    EXPECT_TRUE(s.lights.empty());
    EXPECT_EQ(s.environment->width(), 16);
    EXPECT_FALSE(s.environment->visible());
    EXPECT_FLOAT_EQ(s.environment->scale(), 2.0f);
    // The image's centre (+Z unrotated) now faces +X, scaled by 2 (u just above 1/2, as the centre
    // texel starts there).
    EXPECT_FLOAT_EQ(s.environment->eval(normalize(Vec3(1.0f, -0.01f, 0.05f))).r, 16.0f);
    EXPECT_FLOAT_EQ(s.environment->eval(Vec3(0.0f, 1.0f, 0.0f)).g, 1.0f);
}

TEST(EnvironmentScene, ConstantRadiance) {
    Scene s = loadJson("env_const.json", sceneWith({{"radiance", {0.25, 0.5, 1.0}}})).scene;
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_TRUE(s.environment->isConstant());
    EXPECT_TRUE(s.environment->visible());
    EXPECT_FLOAT_EQ(s.environment->eval(Vec3(0, 0, 1)).b, 1.0f);
    Scene grey = loadJson("env_grey.json", sceneWith({{"radiance", 3}, {"scale", 0.5}})).scene;
    EXPECT_FLOAT_EQ(grey.environment->eval(Vec3(1, 0, 0)).g, 1.5f);
}

void expectSceneError(const std::string& name, const json& j, const std::string& place, const std::string& what) {
    const std::string path = test::outputDir() + "/" + name;
    std::string err = errorOf([&] { loadJson(name, j); });
    SCOPED_TRACE(name + ": " + err);
    ASSERT_FALSE(err.empty()) << "no error";
    EXPECT_NE(err.find(path), std::string::npos) << "does not name the file";
    EXPECT_NE(err.find(place), std::string::npos) << "does not name the place '" << place << "'";
    EXPECT_NE(err.find(what), std::string::npos) << "does not say '" << what << "'";
    EXPECT_EQ(err.find('\n'), std::string::npos) << "not one line";
}

TEST(EnvironmentScene, BadInputNamesTheFileAndPlace) {
    writeSky("env_scene_sky.exr", 16, 8);
    expectSceneError("env_both.json", sceneWith({{"file", "env_scene_sky.exr"}, {"radiance", 1}}), "/environment",
                "not both");
    expectSceneError("env_neither.json", sceneWith({{"scale", 1}}), "/environment", "\"radiance\"");
    expectSceneError("env_missing.json", sceneWith({{"file", "no-such-sky.exr"}}), "/environment/file",
                     "no-such-sky.exr");
    writeTestFile("env_not_an_image.exr", "this is not an image");
    expectSceneError("env_unreadable.json", sceneWith({{"file", "env_not_an_image.exr"}}), "/environment/file",
                "env_not_an_image.exr");
    expectSceneError("env_scale.json", sceneWith({{"radiance", 1}, {"scale", -1}}), "/environment/scale", "");
    expectSceneError("env_negative.json", sceneWith({{"radiance", {1, -1, 1}}}), "/environment/radiance", "");
    expectSceneError("env_key.json", sceneWith({{"radiance", 1}, {"rotation", 10}}), "/environment", "rotation");
    expectSceneError("env_type.json", sceneWith("sky.exr"), "/environment", "expected an object");
    Image nan(8, 4);
    nan.at(1, 2).r = std::nanf("");
    writeImage(test::outputDir() + "/env_nan.exr", nan);
    expectSceneError("env_nan.json", sceneWith({{"file", "env_nan.exr"}}), "/environment/file", "(1, 2)");
}

TEST(EnvironmentScene, NonTwoToOneImageIsWarnedAbout) {
    writeSky("env_square.exr", 8, 8);
    std::vector<std::string> warnings;
    Scene s = loadJson("env_square.json", sceneWith({{"file", "env_square.exr"}}), &warnings).scene;
    EXPECT_TRUE(s.environment.has_value());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("8x8"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("2:1"), std::string::npos) << warnings[0];
}

TEST(EnvironmentScene, CommandLineEnvironmentLightsAGltfInsteadOfTheHeadlight) {
    const std::string sky = writeSky("env_scene_sky.exr", 16, 8);
    GltfBuilder b;
    b.addNode({{"mesh", b.addCube("cube")}, {"translation", {0, 0, -3}}});
    SceneLoadOptions o;
    o.environment = sky;
    std::vector<std::string> warnings;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    Scene s = loadSceneData(b.text(), SceneFormat::Gltf, "cube.gltf", "", o).scene;
    EXPECT_TRUE(s.lights.empty()) << "a headlight was added";
    EXPECT_TRUE(warnings.empty());
    ASSERT_TRUE(s.environment.has_value());
    EXPECT_EQ(s.environment->name(), sky);
    // It replaces a scene file's own environment.
    Scene j = loadJson("env_replaced.json", sceneWith({{"radiance", 1}}), nullptr, sky).scene;
    EXPECT_FALSE(j.environment->isConstant());
    // A missing --environment file: named, with the option.
    o.environment = test::outputDir() + "/no-such-sky.hdr";
    std::string err = errorOf([&] { loadSceneData(b.text(), SceneFormat::Gltf, "cube.gltf", "", o); });
    EXPECT_NE(err.find("--environment"), std::string::npos) << err;
    EXPECT_NE(err.find("no-such-sky.hdr"), std::string::npos) << err;
}

TEST(EnvironmentScene, EditsCarryScaleAndRotation) {
    Scene s = loadJson("env_edits.json", sceneWith({{"radiance", 1}, {"scale", 2}, {"rotate", 30}})).scene;
    nlohmann::json edits = sceneEdits(s);
    ASSERT_TRUE(edits.contains("environment"));
    edits["environment"]["scale"] = 0.25;
    edits["environment"]["rotate"] = -45.0;
    Scene edited = s;
    applySceneEdits(edited, edits, "test");
    EXPECT_FLOAT_EQ(edited.environment->scale(), 0.25f);
    EXPECT_FLOAT_EQ(edited.environment->rotation(), -45.0f);
    EXPECT_FLOAT_EQ(s.environment->scale(), 2.0f);  // the copy's parameters are its own
    EXPECT_EQ(sceneEdits(edited).dump(), edits.dump());
    Scene none = s;
    none.environment.reset();
    std::string err = errorOf([&] { applySceneEdits(none, edits, "view.json"); });
    EXPECT_NE(err.find("/edits/environment"), std::string::npos) << err;
    EXPECT_NE(err.find("no environment"), std::string::npos) << err;
    EXPECT_FALSE(sceneEdits(none).contains("environment"));
}

}  // namespace
}  // namespace tyndall
