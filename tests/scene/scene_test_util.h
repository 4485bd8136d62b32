#pragma once
// Helpers for the scene-loading tests: a tiny glTF writer (embedded base64 buffer) so tests build
// exactly the file they need, loading from text with warnings captured, and error capture.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.h"
#include "loading/scene_file.h"
#include "tests/test_util.h"

namespace tyndall::test {

inline std::string base64(const std::string& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8) | uint8_t(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += k[(v >> s) & 63];
    }
    if (i + 1 == bytes.size()) {
        uint32_t v = uint8_t(bytes[i]) << 16;
        out += k[(v >> 18) & 63], out += k[(v >> 12) & 63], out += "==";
    } else if (i + 2 == bytes.size()) {
        uint32_t v = (uint8_t(bytes[i]) << 16) | (uint8_t(bytes[i + 1]) << 8);
        out += k[(v >> 18) & 63], out += k[(v >> 12) & 63], out += k[(v >> 6) & 63], out += "=";
    }
    return out;
}

/// Builds a glTF 2.0 JSON document with one embedded buffer.
struct GltfBuilder {
    nlohmann::json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scenes", nlohmann::json::array({nlohmann::json::object({{"nodes", nlohmann::json::array()}})})},
        {"scene", 0}};
    std::string bin;

    int addView(const void* data, size_t size) {
        while (bin.size() % 4) bin.push_back('\0');
        size_t offset = bin.size();
        bin.append(static_cast<const char*>(data), size);
        doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}});
        return int(doc["bufferViews"].size() - 1);
    }
    int addFloats(const std::vector<float>& v, const char* type) {
        int view = addView(v.data(), v.size() * 4);
        int n = std::strcmp(type, "SCALAR") == 0 ? 1 : type[3] - '0';
        doc["accessors"].push_back(
            {{"bufferView", view}, {"componentType", 5126}, {"count", v.size() / size_t(n)}, {"type", type}});
        return int(doc["accessors"].size() - 1);
    }
    int addIndices(const std::vector<uint32_t>& v) {
        int view = addView(v.data(), v.size() * 4);
        doc["accessors"].push_back(
            {{"bufferView", view}, {"componentType", 5125}, {"count", v.size()}, {"type", "SCALAR"}});
        return int(doc["accessors"].size() - 1);
    }
    /// A mesh with one triangle primitive; returns the mesh index.
    int addMesh(const std::string& name, const std::vector<float>& positions, const std::vector<uint32_t>& indices,
                int material = -1) {
        nlohmann::json prim = {{"attributes", {{"POSITION", addFloats(positions, "VEC3")}}},
                               {"indices", addIndices(indices)}};
        if (material >= 0) prim["material"] = material;
        doc["meshes"].push_back({{"name", name}, {"primitives", {prim}}});
        return int(doc["meshes"].size() - 1);
    }
    /// The unit cube [-0.5, 0.5]^3, closed, outward.
    int addCube(const std::string& name, int material = -1) {
        std::vector<float> p;
        for (int i = 0; i < 8; ++i)
            p.insert(p.end(), {(i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f});
        std::vector<uint32_t> idx = {0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4,
                                     2, 6, 7, 2, 7, 3, 0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6};
        return addMesh(name, p, idx, material);
    }
    int addMaterial(const nlohmann::json& m) {
        doc["materials"].push_back(m);
        return int(doc["materials"].size() - 1);
    }
    /// Adds a node; `root` puts it in the scene's node list.
    int addNode(const nlohmann::json& node, bool root = true) {
        doc["nodes"].push_back(node);
        int i = int(doc["nodes"].size() - 1);
        if (root) doc["scenes"][0]["nodes"].push_back(i);
        return i;
    }
    int addLight(const nlohmann::json& light) {
        doc["extensions"]["KHR_lights_punctual"]["lights"].push_back(light);
        doc["extensionsUsed"] = {"KHR_lights_punctual"};
        return int(doc["extensions"]["KHR_lights_punctual"]["lights"].size() - 1);
    }
    nlohmann::json json() const {
        nlohmann::json j = doc;
        if (!bin.empty())
            j["buffers"] = {
                {{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
        return j;
    }
    std::string text() const { return json().dump(); }
    /// The document with its buffer in an external file `uri` (write bin to it beside the .gltf).
    nlohmann::json jsonWithExternalBuffer(const std::string& uri) const {
        nlohmann::json j = doc;
        j["buffers"] = {{{"byteLength", bin.size()}, {"uri", uri}}};
        return j;
    }
    /// A .glb: the document (its buffer without a URI) in the JSON chunk, the bytes in the BIN chunk.
    std::string glb() const {
        nlohmann::json j = doc;
        if (!bin.empty()) j["buffers"] = {{{"byteLength", bin.size()}}};
        return glbOf(j.dump(), bin);
    }
    /// A .glb of `jsonText` and `binary` (each chunk padded to 4 bytes; no BIN chunk when empty).
    static std::string glbOf(std::string jsonText, std::string binary) {
        while (jsonText.size() % 4) jsonText.push_back(' ');
        while (binary.size() % 4) binary.push_back('\0');
        auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
        uint32_t total = 12 + 8 + uint32_t(jsonText.size()) + (binary.empty() ? 0 : 8 + uint32_t(binary.size()));
        std::string out = "glTF" + u32(2) + u32(total) + u32(uint32_t(jsonText.size())) + "JSON" + jsonText;
        if (!binary.empty()) out += u32(uint32_t(binary.size())) + std::string("BIN\0", 4) + binary;
        return out;
    }
};

/// Loads scene text in `format` with warnings collected into `warnings` (may be null).
inline SceneFile loadText(const std::string& text, SceneFormat format, std::vector<std::string>* warnings = nullptr,
                          const std::string& camera = "", const std::string& file = "test.gltf") {
    SceneLoadOptions o;
    o.camera = camera;
    o.warn = [warnings](const std::string& w) {
        if (warnings) warnings->push_back(w);
    };
    return loadSceneData(text, format, file, "", o);
}

/// The message of the Error `f` throws ("" if it does not throw; other exceptions fail the test).
inline std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// Writes `text` to <test output>/<name> and returns the path.
inline std::string writeTestFile(const std::string& name, const std::string& text) {
    std::string path = outputDir() + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

/// Field-by-field equality of two scenes (within `tol` for floats), density grids excepted.
inline void expectSameScene(const Scene& a, const Scene& b, float tol) {
    auto near3 = [&](const Vec3& x, const Vec3& y, const std::string& what) {
        EXPECT_NEAR(x.x, y.x, tol) << what;
        EXPECT_NEAR(x.y, y.y, tol) << what;
        EXPECT_NEAR(x.z, y.z, tol) << what;
    };
    auto nearRgb = [&](const Rgb& x, const Rgb& y, const std::string& what) {
        EXPECT_NEAR(x.r, y.r, tol) << what;
        EXPECT_NEAR(x.g, y.g, tol) << what;
        EXPECT_NEAR(x.b, y.b, tol) << what;
    };
    EXPECT_EQ(a.name, b.name);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const Material &x = a.materials[i], &y = b.materials[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type) << x.name;
        nearRgb(x.albedo, y.albedo, x.name);
        nearRgb(x.emission, y.emission, x.name);
        EXPECT_NEAR(x.ior, y.ior, tol) << x.name;
    }
    ASSERT_EQ(a.media.size(), b.media.size());
    for (size_t i = 0; i < a.media.size(); ++i) {
        EXPECT_EQ(a.media[i].name, b.media[i].name);
        nearRgb(a.media[i].sigmaS, b.media[i].sigmaS, a.media[i].name);
        nearRgb(a.media[i].sigmaA, b.media[i].sigmaA, a.media[i].name);
        EXPECT_NEAR(a.media[i].g, b.media[i].g, tol);
    }
    EXPECT_EQ(a.globalMedium, b.globalMedium);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const TriangleMesh &x = a.meshes[i], &y = b.meshes[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.material, y.material) << x.name;
        EXPECT_EQ(x.interiorMedium, y.interiorMedium) << x.name;
        EXPECT_EQ(x.exteriorMedium, y.exteriorMedium) << x.name;
        EXPECT_EQ(x.indices, y.indices) << x.name;
        ASSERT_EQ(x.positions.size(), y.positions.size()) << x.name;
        ASSERT_EQ(x.normals.size(), y.normals.size()) << x.name;
        for (size_t k = 0; k < x.positions.size(); ++k) near3(x.positions[k], y.positions[k], x.name);
        for (size_t k = 0; k < x.normals.size(); ++k) near3(x.normals[k], y.normals[k], x.name);
    }
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
        const Light &x = a.lights[i], &y = b.lights[i];
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.type, y.type) << x.name;
        near3(x.position, y.position, x.name);
        near3(x.direction, y.direction, x.name);
        nearRgb(x.intensity, y.intensity, x.name);
        EXPECT_NEAR(x.cosInnerAngle, y.cosInnerAngle, tol) << x.name;
        EXPECT_NEAR(x.cosOuterAngle, y.cosOuterAngle, tol) << x.name;
    }
    near3(a.camera.position, b.camera.position, "camera");
    near3(a.camera.forward, b.camera.forward, "camera");
    near3(a.camera.up, b.camera.up, "camera");
    EXPECT_NEAR(a.camera.yFov, b.camera.yFov, tol);
    EXPECT_NEAR(a.camera.lensRadius, b.camera.lensRadius, tol);
    EXPECT_NEAR(a.camera.focusDistance, b.camera.focusDistance, tol);
    EXPECT_EQ(a.emitters.size(), b.emitters.size());
}

}  // namespace tyndall::test
