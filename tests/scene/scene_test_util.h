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
#include "core/scene_file.h"
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

}  // namespace tyndall::test
