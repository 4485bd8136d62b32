// The JSON scene description: the default scene as a file, glTF references with overrides and
// media, camera order, the render block, thin sheets, and the strict JSON reader itself.
#include <gtest/gtest.h>

#include <filesystem>

#include "loading/default_scene.h"
#include "loading/json_reader.h"
#include "core/settings.h"
#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

using test::errorOf;
using test::expectSameScene;
using test::loadText;

std::string sourceDir() {
    return TYNDALL_SOURCE_DIR;
}


TEST(SceneFile, CausticBoxFileIsTheBuiltInDefaultScene) {
    SceneFile f = loadSceneFile(sourceDir() + "/scenes/caustic-box.json");
    expectSameScene(f.scene, makeDefaultScene(), 1e-6f);
    EXPECT_EQ(f.render, defaultSceneRender());
}

TEST(SceneFile, ExtensionPicksTheFormat) {
    EXPECT_EQ(sceneFormatOf("a/b.JSON"), SceneFormat::Json);
    EXPECT_EQ(sceneFormatOf("b.gltf"), SceneFormat::Gltf);
    EXPECT_EQ(sceneFormatOf("b.glb"), SceneFormat::Glb);
    EXPECT_NE(errorOf([] { sceneFormatOf("scene.obj"); }).find("scene 'scene.obj': unknown scene file type '.obj'"),
              std::string::npos);
}

/// A glTF with a closed "tank" (glass), an open "window" (glass) and a light, written to disk.
std::string writeTankGltf() {
    test::GltfBuilder b;
    int glass = b.addMaterial({{"name", "glass"},
                               {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}},
                               {"pbrMetallicRoughness", {{"roughnessFactor", 0.0}}}});
    b.addNode({{"name", "tank"}, {"mesh", b.addCube("tank mesh", glass)}, {"translation", {0, 0.5, 0}}});
    b.addNode({{"name", "window"}, {"mesh", b.addMesh("w", {-1, 0, 2, 1, 0, 2, 0, 1, 2}, {0, 1, 2}, glass)}});
    b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    b.addNode({{"name", "gltf cam"}, {"camera", 0}, {"translation", {0, 1, 6}}});
    return test::writeTestFile("tank.gltf", b.text());
}

TEST(SceneFile, GltfReferenceWithMediaOverridesShapesAndCameras) {
    writeTankGltf();
    std::string json = R"({
      "name": "tank scene",
      "gltf": "tank.gltf",
      "render": {"passes": 3, "photons": 777},
      "materials": [
        {"name": "glass", "type": "dielectric", "ior": 1.33},
        {"name": "floor", "albedo": [0.5, 0.5, 0.5]}
      ],
      "media": [
        {"name": "water", "sigma_s": [0.1, 0.2, 0.3], "sigma_a": 0.05, "g": 0.5, "inside": "tank"},
        {"name": "haze", "sigma_s": 0.01}
      ],
      "global_medium": "haze",
      "shapes": [{"type": "quad", "name": "floor", "material": "floor", "corner": [-5, 0, 5], "edge1": [10, 0, 0], "edge2": [0, 0, -10]}],
      "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": 3}],
      "cameras": [{"name": "mine", "position": [0, 2, 8], "target": [0, 0.5, 0], "fov": 30}]
    })";
    std::string path = test::writeTestFile("tank.json", json);
    SceneFile f = loadSceneFile(path);
    const Scene& s = f.scene;
    EXPECT_EQ(s.name, "tank scene");
    EXPECT_EQ(s.source, path);
    ASSERT_EQ(s.meshes.size(), 3u);
    EXPECT_EQ(s.meshes[0].name, "tank");
    EXPECT_EQ(s.meshes[2].name, "floor");
    // The file's "glass" replaced the glTF's: ior 1.33 for both glTF meshes.
    EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(s.materials[size_t(s.meshes[0].material)].ior, 1.33f);
    ASSERT_EQ(s.media.size(), 2u);
    EXPECT_EQ(s.meshes[0].interiorMedium, 0);  // water in the closed tank
    EXPECT_EQ(s.meshes[0].exteriorMedium, 1);  // haze around it
    EXPECT_EQ(s.meshes[1].interiorMedium, 1);  // the open window is a thin sheet: haze on both sides
    EXPECT_EQ(s.globalMedium, 1);
    EXPECT_FLOAT_EQ(s.media[0].sigmaS.b, 0.3f);
    EXPECT_FLOAT_EQ(s.media[0].g, 0.5f);
    // The file's cameras come before the glTF's.
    EXPECT_EQ(f.cameras, (std::vector<std::string>{"mine", "gltf cam"}));
    EXPECT_NEAR(s.camera.position.z, 8.0f, 1e-6f);
    SceneLoadOptions o;
    o.camera = "gltf cam";
    EXPECT_NEAR(loadSceneFile(path, o).scene.camera.position.z, 6.0f, 1e-6f);
    // The render block comes back for the command line to merge.
    RenderSettings r = RenderSettings::fromJson(f.render, f.renderWhere);
    EXPECT_EQ(r.passes, 3u);
    EXPECT_EQ(r.photonsPerPass, 777u);
    EXPECT_EQ(f.renderWhere, path + ": /render");
}

TEST(SceneFile, MediumInsideAMultiPrimitiveMeshTakesEveryPrimitive) {
    // A glTF mesh with two primitives becomes meshes "twin#0" and "twin#1"; "inside": "twin" fills both.
    test::GltfBuilder b;
    int mesh = b.addCube("cube");
    nlohmann::json prim = b.doc["meshes"][mesh]["primitives"][0];
    b.doc["meshes"][mesh]["primitives"].push_back(prim);  // the same closed cube twice
    b.addNode({{"name", "twin"}, {"mesh", mesh}});
    test::writeTestFile("twin.gltf", b.text());
    std::string path = test::writeTestFile("twin.json", R"({"gltf": "twin.gltf",
        "media": [{"name": "smoke", "sigma_s": 1, "inside": "twin"}],
        "lights": [{"type": "point", "position": [0, 0, 0], "intensity": 1}]})");
    Scene s = loadSceneFile(path).scene;
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].name, "twin#0");
    EXPECT_EQ(s.meshes[1].name, "twin#1");
    EXPECT_EQ(s.meshes[0].interiorMedium, 0);
    EXPECT_EQ(s.meshes[1].interiorMedium, 0);
}

TEST(SceneFile, EveryShapeTypeBuilds) {
    std::string json = R"({
      "materials": [{"name": "m"}, {"name": "glass", "type": "dielectric"}, {"name": "chrome", "type": "mirror"}],
      "shapes": [
        {"type": "quad", "material": "m", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 0, -1]},
        {"type": "box", "material": 0, "min": [0, 0, 0], "max": [1, 2, 3], "inward": true},
        {"type": "sphere", "material": "glass", "center": [0, 1, 0], "radius": 0.5, "subdivisions": 2},
        {"type": "cylinder", "material": "m", "from": [0, 0, 0], "to": [0, 1, 0], "radius": 0.1, "segments": 8},
        {"type": "bumpy_sphere", "material": "glass", "center": [0, 1, 0], "radius": 0.5, "subdivisions": 3,
         "amplitude": 0.1, "frequency": 6, "bumps": 5, "seed": 7},
        {"type": "water", "material": "glass", "top": [0, 0, 0], "size": [4, 2], "depth": 1, "resolution": [8, 4],
         "waves": [{"amplitude": 0.05, "wavelength": 1.5, "direction": [1, 0.5], "phase": 1}]},
        {"type": "paraboloid", "material": "chrome", "apex": [0, 0, 0], "axis": [0, 0, 1], "focal_length": 0.1,
         "radius": 0.3, "inner_radius": 0.05, "rings": 4, "segments": 12},
        {"type": "lens", "material": "glass", "center": [0, 0, 1], "axis": [0, 0, 1], "radius": 0.3, "thickness": 0.1,
         "curvature_radius": 1.0, "rings": 3, "segments": 12},
        {"type": "perforated_sphere", "material": "chrome", "center": [0, 0, 0], "radius": 1, "subdivisions": 2,
         "holes": 6, "hole_angle": 15},
        {"type": "mesh", "name": "tri", "material": "m", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "indices": [0, 1, 2],
         "transform": {"scale": 2, "rotate": {"axis": [0, 0, 1], "degrees": 90}, "translate": [10, 0, 0]}}
      ],
      "lights": [{"type": "point", "position": [0, 5, 0], "intensity": 1}],
      "cameras": [{"position": [0, 1, 5], "direction": [0, 0, -1]}]
    })";
    Scene s = loadText(json, SceneFormat::Json, nullptr, "", "shapes.json").scene;
    ASSERT_EQ(s.meshes.size(), 10u);
    const bool closed[] = {false, true, true, true, true, true, false, true, false, false};
    for (size_t i = 0; i < s.meshes.size(); ++i) EXPECT_EQ(s.meshes[i].isClosed(), closed[i]) << s.meshes[i].name;
    EXPECT_EQ(s.meshes[0].name, "quad 0");
    EXPECT_EQ(s.meshes[9].name, "tri");
    // scale 2, then 90 degrees about z ((1,0,0) -> (0,1,0)), then +10 in x.
    EXPECT_NEAR(s.meshes[9].positions[1].x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.meshes[9].positions[1].y, 2.0f, 1e-5f);
}

TEST(SceneFile, CommentsAreAllowed) {
    std::string json =
        "// a comment\n{ /* block */ \"lights\": [{\"type\": \"point\", \"position\": [0, 0, 0], "
        "\"intensity\": 1}], \"materials\": [{\"name\": \"m\"}], \"shapes\": [{\"type\": \"sphere\", "
        "\"material\": \"m\", \"center\": [0, 0, -3], \"radius\": 1}]}";
    EXPECT_EQ(loadText(json, SceneFormat::Json, nullptr, "", "c.json").scene.meshes.size(), 1u);
}

TEST(JsonReader, RecordsKnownKeysAndRejectsTheRest) {
    nlohmann::json j = nlohmann::json::parse(R"({"a": 1, "b": [1, 2, 3], "c": "x", "typo": 0})");
    JsonObject o = JsonValue(j, "f.json", "/thing").object();
    EXPECT_EQ(o.number("a", 0.0), 1.0);
    EXPECT_EQ(o.vec3("b", Vec3()).z, 3.0f);
    EXPECT_EQ(o.string("c", ""), "x");
    EXPECT_EQ(o.number("absent", 5.0), 5.0);
    std::string err = errorOf([&] { o.finish(); });
    EXPECT_EQ(err, "f.json: /thing/typo: unknown key 'typo' (expected one of: a, absent, b, c)");
}

TEST(JsonReader, TypeAndRangeErrorsNameThePointer) {
    nlohmann::json j = nlohmann::json::parse(R"({"n": -2, "v": [1, "x", 3], "s/k": true})");
    j["big"] = std::numeric_limits<double>::infinity();  // JSON text cannot hold it; a program can
    JsonObject o = JsonValue(j, "f.json", "").object();
    EXPECT_EQ(errorOf([&] { o.number("n", 0, 0.0); }), "f.json: /n: expected a finite number >= 0, got -2");
    EXPECT_EQ(errorOf([&] { o.vec3("v", Vec3()); }), "f.json: /v/1: expected a finite number, got the string \"x\"");
    EXPECT_EQ(errorOf([&] { o.rgb("n", Rgb()); }), "f.json: /n: expected a finite number >= 0 or [r, g, b], got -2");
    EXPECT_NE(errorOf([&] { o.number("big", 0); }).find("f.json: /big: expected a finite number"), std::string::npos);
    EXPECT_EQ(errorOf([&] { o.string("s/k", ""); }), "f.json: /s~1k: expected a string, got true");
    EXPECT_EQ(errorOf([&] { o.integer("n", 0, 0, 3); }), "f.json: /n: expected an integer in [0, 3], got -2");
}

TEST(JsonReader, SyntaxErrorsGiveLineAndColumn) {
    std::string err = errorOf([] { parseJsonText("{\n  \"a\": NaN\n}", "bad.json"); });
    EXPECT_EQ(err.rfind("bad.json: line 2, column ", 0), 0u) << err;
    EXPECT_EQ(err.find('\n'), std::string::npos);
}

}  // namespace
}  // namespace tyndall

namespace tyndall {
namespace {

// "plastic": the dielectric coat over diffuse (roughness, ior, metallic, roughness_texture); the
// keys stay errors where they do not apply, and "diffuse" stays exactly Lambertian.
TEST(SceneFile, PlasticMaterialKeys) {
    auto scene = [](const std::string& material) {
        return std::string(R"({"materials": [)") + material + R"(],
          "shapes": [{"type": "quad", "material": 0, "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
          "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1}],
          "cameras": [{"position": [0, 1, 4], "target": [0, 0, 0]}]})";
    };
    Scene s = test::loadText(scene(R"({"name": "p", "type": "plastic", "albedo": [0.2, 0.3, 0.4], "roughness": 0.3,
                                       "ior": 1.4, "metallic": 0.25})"),
                             SceneFormat::Json)
                  .scene;
    const Material& p = s.materials[0];
    EXPECT_EQ(p.type, MaterialType::Plastic);
    EXPECT_FLOAT_EQ(p.roughness, 0.3f);
    EXPECT_FLOAT_EQ(p.ior, 1.4f);
    EXPECT_FLOAT_EQ(p.metallic, 0.25f);
    EXPECT_TRUE(p.hasMetalMix());
    Scene d = test::loadText(scene(R"({"name": "d", "type": "plastic"})"), SceneFormat::Json).scene;
    EXPECT_FLOAT_EQ(d.materials[0].albedo.g, 0.8f);
    EXPECT_FLOAT_EQ(d.materials[0].ior, 1.5f);
    EXPECT_FALSE(d.materials[0].isRough());  // a smooth coat
    EXPECT_FALSE(d.materials[0].hasMetalMix());
    for (auto [material, says] : std::vector<std::pair<std::string, std::string>>{
             {R"({"name": "d", "roughness": 0.3})", "roughness applies to mirror, dielectric and plastic"},
             {R"({"name": "d", "ior": 1.3})", "ior applies to dielectric and plastic"},
             {R"({"name": "m", "type": "mirror", "metallic": 0.5})", "metallic applies to plastic materials only"},
             {R"({"name": "p", "type": "plastic", "ior": 0.8})", "/materials/0/ior"},
             {R"({"name": "p", "type": "plastic", "albedo": 1.5})", "a reflectance above 1 creates energy"},
             {R"({"name": "p", "type": "plastc"})", "expected one of diffuse, plastic, mirror"}}) {
        std::string err = test::errorOf([&] { test::loadText(scene(material), SceneFormat::Json); });
        EXPECT_NE(err.find(says), std::string::npos) << material << ": " << err;
    }
}

}  // namespace
}  // namespace tyndall
