// Bad scene files: every kind of mistake gives one line that names the file and the place in it
// (JSON pointer, or glTF node/mesh/material/accessor with name and index), and never a crash.
#include <gtest/gtest.h>

#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

using nlohmann::json;
using test::errorOf;
using test::GltfBuilder;
using test::writeTestFile;

/// Writes `text` as `name`, loads it, and checks the one-line error names the file, `place` and `what`.
void expectError(const std::string& name, const std::string& text, const std::string& place, const std::string& what) {
    std::string path = writeTestFile(name, text);
    std::string err = errorOf([&] { loadSceneFile(path); });
    SCOPED_TRACE(name + ": " + err);
    ASSERT_FALSE(err.empty()) << "no error";
    EXPECT_NE(err.find(path), std::string::npos) << "does not name the file";
    EXPECT_NE(err.find(place), std::string::npos) << "does not name the place '" << place << "'";
    EXPECT_NE(err.find(what), std::string::npos) << "does not say '" << what << "'";
    EXPECT_EQ(err.find('\n'), std::string::npos) << "not one line";
}

json validScene() {
    return json::parse(R"({
      "materials": [{"name": "white"}, {"name": "glass", "type": "dielectric", "ior": 1.5}],
      "media": [{"name": "fog", "sigma_s": 0.1, "sigma_a": 0.01}],
      "global_medium": "fog",
      "shapes": [
        {"type": "quad", "name": "floor", "material": "white", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]},
        {"type": "sphere", "name": "ball", "material": "glass", "center": [0, 1, 0], "radius": 0.5}
      ],
      "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1}],
      "cameras": [{"position": [0, 1, 4], "target": [0, 1, 0]}]
    })");
}

TEST(SceneErrors, ValidBaseSceneLoads) {
    EXPECT_EQ(errorOf([] { loadSceneFile(writeTestFile("valid.json", validScene().dump())); }), "");
}

TEST(SceneErrors, JsonSyntax) {
    expectError("syntax.json", "{\n  \"materials\": [\n    {\"name\": \"a\",}\n  ]\n}", "line 3, column",
                "syntax error");
    expectError("nan.json", "{\"media\": [{\"name\": \"f\", \"sigma_s\": NaN}]}", "line 1, column", "syntax error");
    expectError("empty.json", "", "line 1, column 1", "");
    expectError("top.json", "[1, 2]", "top level", "expected an object");
}

TEST(SceneErrors, UnknownKeys) {
    json j = validScene();
    j["materialz"] = json::array();
    expectError("unknown-top.json", j.dump(), "/materialz", "unknown key 'materialz'");
    j = validScene();
    j["materials"][0]["albdo"] = 0.5;
    expectError("unknown-material-key.json", j.dump(), "/materials/0/albdo",
                "expected one of: albedo, emission, ior, name, type");
    j = validScene();
    j["shapes"][1]["radios"] = 1;
    expectError("unknown-shape-key.json", j.dump(), "/shapes/1/radios", "unknown key");
    // A misspelt key is reported as such, not through its consequence (an unused medium, a
    // medium with no coefficients).
    j = validScene();
    j["global_meduim"] = j["global_medium"];
    j.erase("global_medium");
    expectError("unknown-before-unused.json", j.dump(), "/global_meduim", "unknown key");
    j = validScene();
    j["media"][0] = {{"name", "fog"}, {"sigma_S", 0.1}};
    expectError("unknown-before-vacuum.json", j.dump(), "/media/0/sigma_S", "unknown key");
    j = validScene();
    j["render"] = {{"passez", 3}};
    expectError("unknown-render-key.json", j.dump(), "/render/passez", "unknown render setting");
}

TEST(SceneErrors, WrongTypes) {
    json j = validScene();
    j["materials"][0]["albedo"] = "red";
    expectError("type-albedo.json", j.dump(), "/materials/0/albedo", "expected a finite number >= 0 or [r, g, b]");
    j = validScene();
    j["shapes"][0]["corner"] = {1, 2};
    expectError("type-corner.json", j.dump(), "/shapes/0/corner", "expected [x, y, z]");
    j = validScene();
    j["lights"][0]["type"] = "laser";
    expectError("type-light.json", j.dump(), "/lights/0/type", "expected one of point, spot, directional");
    j = validScene();
    j["shapes"][1]["subdivisions"] = 2.5;
    expectError("type-int.json", j.dump(), "/shapes/1/subdivisions", "expected an integer");
    j = validScene();
    j["render"] = {{"passes", "many"}};
    expectError("type-render.json", j.dump(), "/render/passes", "expected an integer");
}

TEST(SceneErrors, NonFiniteAndNegativeCoefficients) {
    json j = validScene();
    j["media"][0]["sigma_s"] = -0.5;
    expectError("negative-sigma.json", j.dump(), "/media/0/sigma_s", "expected a finite number >= 0");
    j = validScene();
    j["media"][0]["sigma_a"] = {0.1, -0.1, 0.1};
    expectError("negative-channel.json", j.dump(), "/media/0/sigma_a/1", "expected a finite number >= 0");
    std::string text = validScene().dump();
    text.replace(text.find("\"intensity\":1"), 13, "\"intensity\":1e999");  // overflows to infinity
    expectError("infinite.json", text, "line 1, column", "'1e999' is not a finite number");
    j = validScene();
    j["media"][0]["g"] = 1.0;
    expectError("g.json", j.dump(), "/media/0/g", "in [-0.999, 0.999]");
    j = validScene();
    j["materials"][0]["albedo"] = 1.5;
    expectError("albedo-energy.json", j.dump(), "/materials/0/albedo", "above 1");
}

TEST(SceneErrors, IndexAndNameReferences) {
    json j = validScene();
    j["shapes"][0]["material"] = 7;
    expectError("material-index.json", j.dump(), "/shapes/0/material", "expected an integer in [0, 1], got 7");
    j = validScene();
    j["shapes"][0]["material"] = "whit";
    expectError("material-name.json", j.dump(), "/shapes/0/material",
                "no material named 'whit' (there are: 'white', 'glass')");
    j = validScene();
    j["global_medium"] = "smog";
    expectError("medium-name.json", j.dump(), "/global_medium", "no medium named 'smog'");
    j = validScene();
    j["media"].push_back({{"name", "ink"}, {"sigma_s", 1}, {"inside", 5}});
    expectError("mesh-index.json", j.dump(), "/media/1/inside", "expected an integer in [0, 1], got 5");
    j = validScene();
    j["media"].push_back({{"name", "ink"}, {"sigma_s", 1}, {"inside", "bal"}});
    expectError("mesh-name.json", j.dump(), "/media/1/inside", "no mesh named 'bal'");
}

TEST(SceneErrors, MediumOnAnOpenMesh) {
    json j = validScene();
    j["media"].push_back({{"name", "ink"}, {"sigma_s", 1}, {"inside", {"ball", "floor"}}});
    expectError("open-mesh.json", j.dump(), "/media/1/inside/1",
                "mesh 'floor' (index 0) is not closed: a medium needs a closed, consistently oriented mesh");
}

TEST(SceneErrors, StructuralMistakes) {
    json j = validScene();
    j["materials"].push_back({{"name", "white"}});
    expectError("duplicate-material.json", j.dump(), "/materials/2", "already defined at /materials/0");
    j = validScene();
    j["media"].push_back({{"name", "unused"}, {"sigma_s", 1}});
    expectError("unused-medium.json", j.dump(), "medium 'unused'", "is not used");
    j = validScene();
    j["media"][0]["density"] = {{"file", "smoke.vdb"}, {"grid", "density"}};
    expectError("density.json", j.dump(), "/media/0/density/file", "no such file");  // more in tests/vdb
    j = validScene();
    j["shapes"][1].erase("radius");
    expectError("missing-key.json", j.dump(), "/shapes/1", "missing required key 'radius'");
    j = validScene();
    j["cameras"][0]["direction"] = {0, 0, -1};
    expectError("camera-target-direction.json", j.dump(), "/cameras/0", "exactly one of 'target' and 'direction'");
    j = validScene();
    j["shapes"][1]["subdivisions"] = 30;
    expectError("subdivisions.json", j.dump(), "/shapes/1/subdivisions", "in [0, 8]");
    j = validScene();
    j["lights"] = json::array();
    expectError("no-light.json", j.dump(), "scene", "no lights");
    j = validScene();
    j["gltf"] = "nowhere.glb";
    expectError("missing-gltf.json", j.dump(), "/gltf", "nowhere.glb' does not exist");
}

// ---- glTF

GltfBuilder validGltf() {
    GltfBuilder b;
    int mat = b.addMaterial({{"name", "paint"}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}});
    b.addNode({{"name", "box"}, {"mesh", b.addCube("box mesh", mat)}});
    int l = b.addLight({{"name", "bulb"}, {"type", "point"}, {"intensity", 100.0}});
    b.addNode(
        {{"name", "lamp"}, {"translation", {0, 3, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}});
    return b;
}

TEST(SceneErrors, ValidBaseGltfLoads) {
    EXPECT_EQ(errorOf([] { loadSceneFile(writeTestFile("valid.gltf", validGltf().text())); }), "");
}

TEST(SceneErrors, GltfMissingBufferAndImage) {
    GltfBuilder b = validGltf();
    json j = b.json();
    j["buffers"][0]["uri"] = "missing.bin";
    expectError("missing-buffer.gltf", j.dump(), "buffer file 'missing.bin'", "not found");
    j = b.json();
    j["images"] = {{{"name", "label"}, {"uri", "missing.png"}}};
    expectError("missing-image.gltf", j.dump(), "image 'label' (index 0)", "file 'missing.png' not found");
}

TEST(SceneErrors, GltfIndicesOutOfRange) {
    GltfBuilder b = validGltf();
    json j = b.json();
    j["nodes"][0]["mesh"] = 5;
    expectError("node-mesh.gltf", j.dump(), "node 'box' (index 0)", "mesh index 5 out of range");
    j = b.json();
    j["meshes"][0]["primitives"][0]["material"] = 9;
    expectError("prim-material.gltf", j.dump(), "mesh 'box mesh' (index 0) primitive 0",
                "material index 9 out of range");
    j = b.json();
    j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 42;
    expectError("accessor.gltf", j.dump(), "primitive 0: POSITION", "accessor index 42 out of range");
    j = b.json();
    j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = 3;
    expectError("light-index.gltf", j.dump(), "node 'lamp' (index 1)", "light index 3 out of range");
    j = b.json();
    j["nodes"][0]["children"] = {7};
    expectError("child.gltf", j.dump(), "node 'box' (index 0)", "child index 7 out of range");
    j = b.json();
    j["nodes"][0]["children"] = {0};
    expectError("cycle.gltf", j.dump(), "node 'box' (index 0)", "reached twice");
    j = b.json();
    j["nodes"].push_back({{"children", {0}}});
    j["nodes"].push_back({{"children", {0}}});
    expectError("two-parents.gltf", j.dump(), "node 'box' (index 0)", "more than one parent");
    j = b.json();
    j["scene"] = 3;
    expectError("scene-index.gltf", j.dump(), "default scene index 3", "out of range");
}

TEST(SceneErrors, GltfBadData) {
    GltfBuilder b = validGltf();
    json j = b.json();
    j["bufferViews"][0]["byteLength"] = 100000;
    expectError("view-overrun.gltf", j.dump(), "bufferView 0", "lie outside buffer 0");
    j = b.json();
    j["accessors"][0]["count"] = 500;
    expectError("accessor-overrun.gltf", j.dump(), "accessor 0", "do not fit bufferView 0");
    // Vertex index 99 in a cube of 8 vertices: rewrite the index buffer through a sparse accessor.
    GltfBuilder c = validGltf();
    uint32_t bad[] = {99};
    uint32_t where[] = {0};
    int vi = c.addView(where, 4), vv = c.addView(bad, 4);
    c.doc["accessors"][1]["sparse"] = {
        {"count", 1}, {"indices", {{"bufferView", vi}, {"componentType", 5125}}}, {"values", {{"bufferView", vv}}}};
    expectError("vertex-index.gltf", c.text(), "mesh 'box mesh' (index 0) primitive 0",
                "vertex index 99 out of range (8 vertices)");
    j = b.json();
    j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, -1, 1, 1};
    expectError("base-color.gltf", j.dump(), "material 'paint' (index 0)", "baseColorFactor must lie in [0, 1]");
    j = b.json();
    j["materials"][0]["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1}};
    j["materials"][0]["extensions"]["KHR_materials_volume"] = {{"attenuationDistance", -1}};
    expectError("attenuation.gltf", j.dump(), "material 'paint' (index 0)", "attenuationDistance must be > 0");
    j = b.json();
    j["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = -5;
    expectError("light-intensity.gltf", j.dump(), "light 'bulb' (index 0, node 1)",
                "intensity must be a finite number >= 0");
    std::string text = b.text();
    text.replace(text.find("\"translation\":[0,3,0]"), 21, "\"translation\":[0,1e999,0]");
    expectError("translation.gltf", text, "line 1, column", "'1e999' is not a finite number");
    j = b.json();
    j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    expectError("draco.gltf", j.dump(), "requires glTF extension KHR_draco_mesh_compression", "cannot read");
    expectError("not-json.gltf", "{\"asset\": ", "not valid glTF", "");
    expectError("truncated.glb", std::string("glTF\x02\0\0\0\xff\0\0\0", 12), "not valid glTF", "");
}

TEST(SceneErrors, MissingAndUnknownFiles) {
    std::string err = errorOf([] { loadSceneFile(test::outputDir() + "/does-not-exist.json"); });
    EXPECT_NE(err.find("does-not-exist.json': no such file"), std::string::npos) << err;
    err = errorOf([] { loadSceneFile(test::outputDir()); });
    EXPECT_NE(err.find("unknown scene file type"), std::string::npos) << err;
}

}  // namespace
}  // namespace tyndall
