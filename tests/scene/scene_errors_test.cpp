// Bad scene files: every kind of mistake gives one line that names the file and the place in it
// (JSON pointer, or glTF node/mesh/material/accessor with name and index), and never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>

#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

namespace fs = std::filesystem;
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

TEST(SceneErrors, ThinNeedsADielectric) {
    json j = validScene();
    j["materials"][1]["thin"] = true;
    EXPECT_EQ(errorOf([&] { loadSceneFile(writeTestFile("thin.json", j.dump())); }), "");
    j["materials"][0]["thin"] = true;
    expectError("thin-diffuse.json", j.dump(), "/materials/0/thin", "thin applies to dielectric materials only");
    j = validScene();
    j["materials"][1]["thin"] = true;
    j["materials"][1]["roughness"] = 0.3;  // a frosted pane
    EXPECT_EQ(errorOf([&] { loadSceneFile(writeTestFile("thin-rough.json", j.dump())); }), "");
    j["materials"][1]["thin"] = "yes";
    expectError("thin-type.json", j.dump(), "/materials/1/thin", "expected");
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
                "expected one of: albedo, albedo_texture, emission, emission_texture, ior, metallic, name, normal_scale, "
                "normal_texture, roughness, roughness_texture, texture_scale, thin, transmission, transmission_texture, type");
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

TEST(SceneErrors, MeshStraddlingAMedium) {
    // A glass ball half inside a smoke box: its outside would be smoke on one half, fog on the other.
    json j = validScene();
    j["materials"].push_back({{"name", "hull"}, {"type", "interface"}});
    j["media"].push_back({{"name", "smoke"}, {"sigma_s", 1}, {"inside", "smoke box"}});
    j["shapes"].push_back({{"type", "box"}, {"name", "smoke box"}, {"material", "hull"}, {"min", {0, 0, -1}},
                           {"max", {2, 2, 1}}});
    expectError("straddle.json", j.dump(), "mesh 'ball' (index 1)",
                "lies partly inside and partly outside mesh 'smoke box' (index 2)");
}

TEST(SceneErrors, ShapeExterior) {
    json j = validScene();
    j["shapes"][1]["exterior"] = "smog";
    expectError("exterior-name.json", j.dump(), "/shapes/1/exterior", "no medium named 'smog' (there are: 'fog')");
    j["shapes"][1]["exterior"] = 3;
    expectError("exterior-index.json", j.dump(), "/shapes/1/exterior", "");
    j["shapes"][1]["exterior"] = {1};
    expectError("exterior-type.json", j.dump(), "/shapes/1/exterior", "expected a medium name or index");
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
    expectError("missing-buffer.gltf", j.dump(), "buffers[0]: file 'missing.bin'",
                "not found in the glTF file's folder");
    j = b.json();  // the second of two buffers, its URI percent-encoded
    j["buffers"].push_back({{"byteLength", 4}, {"uri", "no%20such.bin"}});
    expectError("missing-second-buffer.gltf", j.dump(), "buffers[1]: file 'no such.bin'", "not found");
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
    // NaN and infinity inside the binary data (POSITION's view starts the buffer; its 2nd float).
    for (float bad : {NAN, INFINITY}) {
        GltfBuilder n = validGltf();
        std::memcpy(&n.bin[4], &bad, 4);
        expectError(std::isnan(bad) ? "nan-position.gltf" : "inf-position.gltf", n.text(),
                    "mesh 'box mesh' (index 0) primitive 0: POSITION: accessor 0", "contains a non-finite value");
    }
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

// ---- glTF: wrong JSON types (tinygltf would silently ignore each of them; gltf_json_check.h).

struct GltfTypeCase {
    const char* name;
    std::function<void(json&)> edit;  ///< applied to validGltfWithCamera().json()
    const char* place;                ///< the glTF path in the message
    const char* what;
};

GltfBuilder validGltfWithCamera() {
    GltfBuilder b = validGltf();
    b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
    b.addNode({{"name", "cam"}, {"camera", 0}, {"translation", {0, 1, 5}}});
    return b;
}

void expectGltfTypeErrors(const std::vector<GltfTypeCase>& cases) {
    for (const GltfTypeCase& c : cases) {
        json j = validGltfWithCamera().json();
        c.edit(j);
        expectError(std::string("type-") + c.name + ".gltf", j.dump(), std::string(": ") + c.place + ": ", c.what);
    }
}

const char* kIndex = "expected an index (an integer in [0, 2147483647])";

TEST(SceneErrors, GltfWrongTypesInScenesAndNodes) {
    expectGltfTypeErrors({
        {"scene", [](json& j) { j["scene"] = "0"; }, "scene", kIndex},
        {"scenes",
         [](json& j) {
             j["scenes"] = {{"nodes", {0}}};
         },
         "scenes", "expected an array of objects"},
        {"scene-nodes", [](json& j) { j["scenes"][0]["nodes"][1] = "1"; }, "scenes[0].nodes[1]", kIndex},
        {"nodes", [](json& j) { j["nodes"] = j["nodes"][0]; }, "nodes", "expected an array of objects"},
        {"node", [](json& j) { j["nodes"][0] = 3; }, "nodes[0]", "expected an object, got 3"},
        {"mesh-string", [](json& j) { j["nodes"][0]["mesh"] = "0"; }, "nodes[0].mesh",
         "expected an index (an integer in [0, 2147483647]), got the string \"0\""},
        {"mesh-float", [](json& j) { j["nodes"][0]["mesh"] = 0.0; }, "nodes[0].mesh", kIndex},
        {"mesh-wraps", [](json& j) { j["nodes"][0]["mesh"] = 4294967296ll; }, "nodes[0].mesh", kIndex},
        {"mesh-negative", [](json& j) { j["nodes"][0]["mesh"] = -1; }, "nodes[0].mesh", kIndex},
        {"camera", [](json& j) { j["nodes"][2]["camera"] = "cam"; }, "nodes[2].camera", kIndex},
        {"children", [](json& j) { j["nodes"][0]["children"] = 1; }, "nodes[0].children",
         "expected an array of indices, got 1"},
        {"child", [](json& j) { j["nodes"][0]["children"] = {"1"}; }, "nodes[0].children[0]", kIndex},
        {"translation", [](json& j) { j["nodes"][1]["translation"] = "x"; }, "nodes[1].translation",
         "expected an array of 3 numbers, got the string \"x\""},
        {"translation-length",
         [](json& j) {
             j["nodes"][1]["translation"] = {0, 3};
         },
         "nodes[1].translation", "expected an array of 3 numbers"},
        {"rotation",
         [](json& j) {
             j["nodes"][1]["rotation"] = {0, 0, 0, "1"};
         },
         "nodes[1].rotation[3]", "expected a number"},
        {"scale",
         [](json& j) {
             j["nodes"][1]["scale"] = {1, 1, 1, 1};
         },
         "nodes[1].scale", "expected an array of 3 numbers"},
        {"matrix", [](json& j) { j["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0}; },
         "nodes[0].matrix", "expected an array of 16 numbers"},
        {"node-extensions", [](json& j) { j["nodes"][1]["extensions"] = {1}; }, "nodes[1].extensions",
         "expected an object"},
        {"node-light-object", [](json& j) { j["nodes"][1]["extensions"]["KHR_lights_punctual"] = {0}; },
         "nodes[1].extensions.KHR_lights_punctual", "expected an object"},
        {"node-light", [](json& j) { j["nodes"][1]["extensions"]["KHR_lights_punctual"]["light"] = "0"; },
         "nodes[1].extensions.KHR_lights_punctual.light", kIndex},
        {"node-name", [](json& j) { j["nodes"][0]["name"] = 7; }, "nodes[0].name", "expected a string"},
        {"extensions-required", [](json& j) { j["extensionsRequired"] = "KHR_draco_mesh_compression"; },
         "extensionsRequired", "expected an array of strings"},
    });
}

TEST(SceneErrors, GltfWrongTypesInMeshes) {
    expectGltfTypeErrors({
        {"primitives", [](json& j) { j["meshes"][0]["primitives"] = json::object(); }, "meshes[0].primitives",
         "expected an array of objects"},
        {"attributes", [](json& j) { j["meshes"][0]["primitives"][0]["attributes"] = {0}; },
         "meshes[0].primitives[0].attributes", "expected an object"},
        {"position", [](json& j) { j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = "0"; },
         "meshes[0].primitives[0].attributes.POSITION", kIndex},
        {"indices", [](json& j) { j["meshes"][0]["primitives"][0]["indices"] = true; },
         "meshes[0].primitives[0].indices", "expected an index (an integer in [0, 2147483647]), got true"},
        {"material", [](json& j) { j["meshes"][0]["primitives"][0]["material"] = "paint"; },
         "meshes[0].primitives[0].material", kIndex},
        {"mode", [](json& j) { j["meshes"][0]["primitives"][0]["mode"] = 4.0; }, "meshes[0].primitives[0].mode",
         kIndex},
        {"targets", [](json& j) { j["meshes"][0]["primitives"][0]["targets"] = 1; }, "meshes[0].primitives[0].targets",
         "expected an array"},
    });
}

TEST(SceneErrors, GltfWrongTypesInAccessorsViewsBuffersAndImages) {
    expectGltfTypeErrors({
        {"count", [](json& j) { j["accessors"][0]["count"] = "8"; }, "accessors[0].count", "expected an integer >= 0"},
        {"count-negative", [](json& j) { j["accessors"][0]["count"] = -8; }, "accessors[0].count",
         "expected an integer >= 0, got -8"},
        {"component-type", [](json& j) { j["accessors"][0]["componentType"] = "FLOAT"; }, "accessors[0].componentType",
         kIndex},
        {"accessor-type", [](json& j) { j["accessors"][0]["type"] = 3; }, "accessors[0].type", "expected a string"},
        {"normalized", [](json& j) { j["accessors"][0]["normalized"] = 1; }, "accessors[0].normalized",
         "expected true or false"},
        {"accessor-view", [](json& j) { j["accessors"][0]["bufferView"] = {0}; }, "accessors[0].bufferView", kIndex},
        {"sparse",
         [](json& j) {
             j["accessors"][1]["sparse"] = {{"count", 1},
                                            {"indices", {{"bufferView", "0"}, {"componentType", 5125}}},
                                            {"values", {{"bufferView", 1}}}};
         },
         "accessors[1].sparse.indices.bufferView", kIndex},
        {"view-length", [](json& j) { j["bufferViews"][0]["byteLength"] = 96.5; }, "bufferViews[0].byteLength",
         "expected an integer >= 0"},
        {"view-buffer", [](json& j) { j["bufferViews"][0]["buffer"] = "0"; }, "bufferViews[0].buffer", kIndex},
        {"view-stride", [](json& j) { j["bufferViews"][0]["byteStride"] = "12"; }, "bufferViews[0].byteStride",
         "expected an integer >= 0"},
        {"buffer-uri", [](json& j) { j["buffers"][0]["uri"] = 5; }, "buffers[0].uri", "expected a string, got 5"},
        {"buffer-length", [](json& j) { j["buffers"][0]["byteLength"] = "96"; }, "buffers[0].byteLength",
         "expected an integer >= 0"},
        {"image-uri",
         [](json& j) {
             j["images"] = {{{"uri", 7}}};
         },
         "images[0].uri", "expected a string"},
    });
}

TEST(SceneErrors, GltfWrongTypesInMaterials) {
    auto ext = [](json& j) -> json& { return j["materials"][0]["extensions"]; };
    expectGltfTypeErrors({
        {"pbr", [](json& j) { j["materials"][0]["pbrMetallicRoughness"] = 0; }, "materials[0].pbrMetallicRoughness",
         "expected an object"},
        {"metallic", [](json& j) { j["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = "0"; },
         "materials[0].pbrMetallicRoughness.metallicFactor", "expected a number, got the string \"0\""},
        {"roughness", [](json& j) { j["materials"][0]["pbrMetallicRoughness"]["roughnessFactor"] = nullptr; },
         "materials[0].pbrMetallicRoughness.roughnessFactor", "expected a number, got null"},
        {"base-color",
         [](json& j) {
             j["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1};
         },
         "materials[0].pbrMetallicRoughness.baseColorFactor", "expected an array of 4 numbers"},
        {"texture",
         [](json& j) {
             j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", "0"}};
         },
         "materials[0].pbrMetallicRoughness.baseColorTexture.index", kIndex},
        {"emissive", [](json& j) { j["materials"][0]["emissiveFactor"] = "red"; }, "materials[0].emissiveFactor",
         "expected an array of 3 numbers"},
        {"alpha-mode", [](json& j) { j["materials"][0]["alphaMode"] = 1; }, "materials[0].alphaMode",
         "expected a string"},
        {"strength", [&](json& j) { ext(j)["KHR_materials_emissive_strength"]["emissiveStrength"] = "8"; },
         "materials[0].extensions.KHR_materials_emissive_strength.emissiveStrength", "expected a number"},
        {"transmission", [&](json& j) { ext(j)["KHR_materials_transmission"]["transmissionFactor"] = true; },
         "materials[0].extensions.KHR_materials_transmission.transmissionFactor", "expected a number, got true"},
        {"ior", [&](json& j) { ext(j)["KHR_materials_ior"]["ior"] = "1.5"; },
         "materials[0].extensions.KHR_materials_ior.ior", "expected a number"},
        {"volume", [&](json& j) { ext(j)["KHR_materials_volume"] = 1; }, "materials[0].extensions.KHR_materials_volume",
         "expected an object"},
        {"attenuation-color",
         [&](json& j) {
             ext(j)["KHR_materials_volume"]["attenuationColor"] = {1, 1};
         },
         "materials[0].extensions.KHR_materials_volume.attenuationColor", "expected an array of 3 numbers"},
        {"attenuation-distance", [&](json& j) { ext(j)["KHR_materials_volume"]["attenuationDistance"] = "far"; },
         "materials[0].extensions.KHR_materials_volume.attenuationDistance", "expected a number"},
    });
}

TEST(SceneErrors, GltfWrongTypesInCamerasAndLights) {
    auto light = [](json& j) -> json& { return j["extensions"]["KHR_lights_punctual"]["lights"][0]; };
    expectGltfTypeErrors({
        {"yfov", [](json& j) { j["cameras"][0]["perspective"]["yfov"] = "wide"; }, "cameras[0].perspective.yfov",
         "expected a number"},
        {"perspective", [](json& j) { j["cameras"][0]["perspective"] = {0.8}; }, "cameras[0].perspective",
         "expected an object"},
        {"camera-type", [](json& j) { j["cameras"][0]["type"] = 1; }, "cameras[0].type", "expected a string"},
        {"orthographic",
         [](json& j) {
             j["cameras"][0]["orthographic"] = {{"xmag", "1"}};
         },
         "cameras[0].orthographic.xmag", "expected a number"},
        {"intensity", [&](json& j) { light(j)["intensity"] = "bright"; },
         "extensions.KHR_lights_punctual.lights[0].intensity", "expected a number, got the string \"bright\""},
        {"color",
         [&](json& j) {
             light(j)["color"] = {1, 1};
         },
         "extensions.KHR_lights_punctual.lights[0].color", "expected an array of 3 numbers"},
        {"light-type", [&](json& j) { light(j)["type"] = 1; }, "extensions.KHR_lights_punctual.lights[0].type",
         "expected a string"},
        {"range", [&](json& j) { light(j)["range"] = "far"; }, "extensions.KHR_lights_punctual.lights[0].range",
         "expected a number"},
        {"spot",
         [&](json& j) {
             light(j)["spot"] = {{"outerConeAngle", "wide"}};
         },
         "extensions.KHR_lights_punctual.lights[0].spot.outerConeAngle", "expected a number"},
        {"lights", [](json& j) { j["extensions"]["KHR_lights_punctual"]["lights"] = json::object(); },
         "extensions.KHR_lights_punctual.lights", "expected an array of objects"},
    });
}

TEST(SceneErrors, GltfWrongTypesInAGlbJsonChunk) {
    GltfBuilder b = validGltf();
    json j = b.doc;
    j["buffers"] = {{{"byteLength", b.bin.size()}}};
    j["nodes"][0]["mesh"] = "0";
    expectError("type-mesh.glb", GltfBuilder::glbOf(j.dump(), b.bin), ": nodes[0].mesh: ", kIndex);
}

TEST(SceneErrors, GltfUnknownKeysExtrasAndExtensionsAreAllowed) {
    json j = validGltfWithCamera().json();
    j["nodes"][0]["extras"] = {{"mesh", "not Tyndall's"}};
    j["nodes"][0]["vendorKey"] = "x";
    j["nodes"][0]["extensions"]["EXT_something"] = {{"translation", "anything"}};
    j["materials"][0]["extensions"]["KHR_materials_clearcoat"] = {{"clearcoatFactor", "1"}};
    j["extras"] = 5;
    EXPECT_EQ(errorOf([&] { loadSceneFile(writeTestFile("type-extras.gltf", j.dump())); }), "");
}

// ---- glTF: buffers and images are read only from the glTF file's folder.

TEST(SceneErrors, GltfFilesOutsideItsFolderAreNotRead) {
    const fs::path root = fs::path(test::outputDir()) / "gltf-escape";
    fs::remove_all(root);
    fs::create_directories(root / "b");
    fs::create_directories(root / "bc");  // a sibling whose name starts with the base folder's
    GltfBuilder b = validGltf();
    for (const fs::path& p : {root / "outside.bin", root / "bc" / "data.bin", root / "b" / "inside.bin"})
        std::ofstream(p, std::ios::binary) << b.bin;
    std::ofstream(root / "outside.png", std::ios::binary) << "not decoded";
    std::error_code ec;
    fs::create_symlink(root / "outside.bin", root / "b" / "link.bin", ec);
    ASSERT_FALSE(ec) << ec.message();

    for (const std::string uri : {"inside.bin", "./inside.bin"})
        EXPECT_EQ(errorOf([&] {
                      loadSceneFile(writeTestFile("gltf-escape/b/in.gltf", b.jsonWithExternalBuffer(uri).dump()));
                  }),
                  "")
            << uri;
    for (const std::string& uri : std::vector<std::string>{"../outside.bin", "../bc/data.bin", "../b/../outside.bin",
                                                           "link.bin", (root / "outside.bin").string()})
        expectError("gltf-escape/b/out.gltf", b.jsonWithExternalBuffer(uri).dump(), "buffers[0]: file '" + uri + "'",
                    "not found in the glTF file's folder");
    json j = b.json();
    j["images"] = {{{"uri", "../outside.png"}}};
    expectError("gltf-escape/b/image.gltf", j.dump(), "image (index 0)", "file '../outside.png' not found");
}

TEST(SceneErrors, MissingAndUnknownFiles) {
    std::string err = errorOf([] { loadSceneFile(test::outputDir() + "/does-not-exist.json"); });
    EXPECT_NE(err.find("does-not-exist.json': no such file"), std::string::npos) << err;
    err = errorOf([] { loadSceneFile(test::outputDir()); });
    EXPECT_NE(err.find("unknown scene file type"), std::string::npos) << err;
}

}  // namespace
}  // namespace tyndall
