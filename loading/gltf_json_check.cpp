#include "loading/gltf_json_check.h"

#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "loading/json_reader.h"

namespace tyndall {

namespace {

using nlohmann::json;

/// Walks one glTF document; `path` arguments are glTF-style ("nodes[3].translation").
class GltfJsonChecker {
public:
    explicit GltfJsonChecker(std::string file) : m_file(std::move(file)) {}

    void document(const json& root);

private:
    [[noreturn]] void expected(const json& v, const std::string& path, const std::string& what) const {
        // Numbers as written (0.0 is not an index, 4294967296 is not 4.29497e+09).
        std::string got = v.is_number() ? v.dump() : JsonValue(v, m_file, path).describe();
        throw Error(m_file + ": " + path + ": expected " + what + ", got " + got);
    }
    static std::string at(const std::string& path, const char* key) {
        return path.empty() ? std::string(key) : path + "." + key;
    }
    static std::string at(const std::string& path, size_t i) { return path + "[" + std::to_string(i) + "]"; }
    static const json* member(const json& obj, const char* key) {
        auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

    /// `obj.key` as an object, nullptr when absent.
    const json* object(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (v && !v->is_object()) expected(*v, at(path, key), "an object");
        return v;
    }
    void index(const json& v, const std::string& path) const {
        bool ok = (v.is_number_unsigned() && v.get<uint64_t>() <= uint64_t(INT32_MAX)) ||
                  (v.is_number_integer() && !v.is_number_unsigned() && v.get<int64_t>() >= 0 &&
                   v.get<int64_t>() <= INT32_MAX);
        if (!ok) expected(v, path, "an index (an integer in [0, 2147483647])");
    }
    void index(const json& obj, const char* key, const std::string& path) const {
        if (const json* v = member(obj, key)) index(*v, at(path, key));
    }
    /// A byte offset, length, stride or element count: a non-negative integer.
    void size(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (v && !(v->is_number_unsigned() || (v->is_number_integer() && v->get<int64_t>() >= 0)))
            expected(*v, at(path, key), "an integer >= 0");
    }
    void number(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (v && !v->is_number()) expected(*v, at(path, key), "a number");
    }
    void string(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (v && !v->is_string()) expected(*v, at(path, key), "a string");
    }
    void boolean(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (v && !v->is_boolean()) expected(*v, at(path, key), "true or false");
    }
    /// An array of exactly `n` numbers (vectors, quaternions, matrices, colours).
    void numbers(const json& obj, const char* key, size_t n, const std::string& path) const {
        const json* v = member(obj, key);
        if (!v) return;
        std::string p = at(path, key);
        if (!v->is_array() || v->size() != n) expected(*v, p, "an array of " + std::to_string(n) + " numbers");
        for (size_t i = 0; i < n; ++i)
            if (!(*v)[i].is_number()) expected((*v)[i], at(p, i), "a number");
    }
    void indexArray(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (!v) return;
        std::string p = at(path, key);
        if (!v->is_array()) expected(*v, p, "an array of indices");
        for (size_t i = 0; i < v->size(); ++i) index((*v)[i], at(p, i));
    }
    void stringArray(const json& obj, const char* key, const std::string& path) const {
        const json* v = member(obj, key);
        if (!v) return;
        std::string p = at(path, key);
        if (!v->is_array()) expected(*v, p, "an array of strings");
        for (size_t i = 0; i < v->size(); ++i)
            if (!(*v)[i].is_string()) expected((*v)[i], at(p, i), "a string");
    }
    /// Calls `each(element, path)` for every element of the array of objects `obj.key`.
    template <typename Each>
    void objects(const json& obj, const char* key, const std::string& path, Each each) const {
        const json* v = member(obj, key);
        if (!v) return;
        std::string p = at(path, key);
        if (!v->is_array()) expected(*v, p, "an array of objects");
        for (size_t i = 0; i < v->size(); ++i) {
            if (!(*v)[i].is_object()) expected((*v)[i], at(p, i), "an object");
            each((*v)[i], at(p, i));
        }
    }
    void textureInfo(const json& obj, const char* key, const std::string& path) const {
        if (const json* t = object(obj, key, path)) index(*t, "index", at(path, key));
    }

    void node(const json& n, const std::string& p) const;
    void primitive(const json& prim, const std::string& p) const;
    void accessor(const json& a, const std::string& p) const;
    void material(const json& m, const std::string& p) const;
    void camera(const json& c, const std::string& p) const;
    void light(const json& l, const std::string& p) const;

    std::string m_file;
};

void GltfJsonChecker::document(const json& root) {
    if (!root.is_object()) expected(root, "top level", "a glTF object");
    index(root, "scene", "");
    objects(root, "scenes", "", [&](const json& s, const std::string& p) {
        string(s, "name", p);
        indexArray(s, "nodes", p);
    });
    objects(root, "nodes", "", [&](const json& n, const std::string& p) { node(n, p); });
    objects(root, "meshes", "", [&](const json& m, const std::string& p) {
        string(m, "name", p);
        objects(m, "primitives", p, [&](const json& prim, const std::string& pp) { primitive(prim, pp); });
    });
    objects(root, "accessors", "", [&](const json& a, const std::string& p) { accessor(a, p); });
    objects(root, "bufferViews", "", [&](const json& v, const std::string& p) {
        string(v, "name", p);
        index(v, "buffer", p);
        size(v, "byteOffset", p);
        size(v, "byteLength", p);
        size(v, "byteStride", p);
    });
    objects(root, "buffers", "", [&](const json& b, const std::string& p) {
        string(b, "name", p);
        string(b, "uri", p);
        size(b, "byteLength", p);
    });
    objects(root, "images", "", [&](const json& im, const std::string& p) {
        string(im, "name", p);
        string(im, "uri", p);
        string(im, "mimeType", p);
        index(im, "bufferView", p);
    });
    objects(root, "materials", "", [&](const json& m, const std::string& p) { material(m, p); });
    objects(root, "cameras", "", [&](const json& c, const std::string& p) { camera(c, p); });
    stringArray(root, "extensionsUsed", "");
    stringArray(root, "extensionsRequired", "");
    if (const json* ext = object(root, "extensions", ""))
        if (const json* lights = object(*ext, "KHR_lights_punctual", "extensions"))
            objects(*lights, "lights", "extensions.KHR_lights_punctual",
                    [&](const json& l, const std::string& p) { light(l, p); });
}

void GltfJsonChecker::node(const json& n, const std::string& p) const {
    string(n, "name", p);
    index(n, "mesh", p);
    index(n, "camera", p);
    index(n, "skin", p);
    indexArray(n, "children", p);
    numbers(n, "matrix", 16, p);
    numbers(n, "translation", 3, p);
    numbers(n, "rotation", 4, p);
    numbers(n, "scale", 3, p);
    if (const json* ext = object(n, "extensions", p))
        if (const json* l = object(*ext, "KHR_lights_punctual", at(p, "extensions")))
            index(*l, "light", at(p, "extensions.KHR_lights_punctual"));
}

void GltfJsonChecker::primitive(const json& prim, const std::string& p) const {
    if (const json* attrs = object(prim, "attributes", p))
        for (auto it = attrs->begin(); it != attrs->end(); ++it)
            index(it.value(), at(p, "attributes") + "." + it.key());
    index(prim, "indices", p);
    index(prim, "material", p);
    index(prim, "mode", p);
    if (const json* t = member(prim, "targets"); t && !t->is_array())
        expected(*t, at(p, "targets"), "an array of objects");
}

void GltfJsonChecker::accessor(const json& a, const std::string& p) const {
    string(a, "name", p);
    index(a, "bufferView", p);
    size(a, "byteOffset", p);
    index(a, "componentType", p);
    boolean(a, "normalized", p);
    size(a, "count", p);
    string(a, "type", p);
    if (const json* s = object(a, "sparse", p)) {
        std::string sp = at(p, "sparse");
        size(*s, "count", sp);
        if (const json* i = object(*s, "indices", sp)) {
            index(*i, "bufferView", at(sp, "indices"));
            index(*i, "byteOffset", at(sp, "indices"));  // an int to tinygltf
            index(*i, "componentType", at(sp, "indices"));
        }
        if (const json* v = object(*s, "values", sp)) {
            index(*v, "bufferView", at(sp, "values"));
            index(*v, "byteOffset", at(sp, "values"));
        }
    }
}

void GltfJsonChecker::material(const json& m, const std::string& p) const {
    string(m, "name", p);
    if (const json* pbr = object(m, "pbrMetallicRoughness", p)) {
        std::string pp = at(p, "pbrMetallicRoughness");
        numbers(*pbr, "baseColorFactor", 4, pp);
        number(*pbr, "metallicFactor", pp);
        number(*pbr, "roughnessFactor", pp);
        textureInfo(*pbr, "baseColorTexture", pp);
        textureInfo(*pbr, "metallicRoughnessTexture", pp);
    }
    numbers(m, "emissiveFactor", 3, p);
    string(m, "alphaMode", p);
    textureInfo(m, "normalTexture", p);
    textureInfo(m, "occlusionTexture", p);
    textureInfo(m, "emissiveTexture", p);
    const json* ext = object(m, "extensions", p);
    if (!ext) return;
    std::string ep = at(p, "extensions");
    if (const json* e = object(*ext, "KHR_materials_emissive_strength", ep))
        number(*e, "emissiveStrength", at(ep, "KHR_materials_emissive_strength"));
    if (const json* e = object(*ext, "KHR_materials_transmission", ep)) {
        number(*e, "transmissionFactor", at(ep, "KHR_materials_transmission"));
        textureInfo(*e, "transmissionTexture", at(ep, "KHR_materials_transmission"));
    }
    if (const json* e = object(*ext, "KHR_materials_ior", ep)) number(*e, "ior", at(ep, "KHR_materials_ior"));
    if (const json* e = object(*ext, "KHR_materials_volume", ep)) {
        std::string vp = at(ep, "KHR_materials_volume");
        number(*e, "thicknessFactor", vp);
        number(*e, "attenuationDistance", vp);
        numbers(*e, "attenuationColor", 3, vp);
    }
}

void GltfJsonChecker::camera(const json& c, const std::string& p) const {
    string(c, "name", p);
    string(c, "type", p);
    if (const json* persp = object(c, "perspective", p))
        for (const char* k : {"yfov", "znear", "zfar", "aspectRatio"}) number(*persp, k, at(p, "perspective"));
    if (const json* ortho = object(c, "orthographic", p))
        for (const char* k : {"xmag", "ymag", "znear", "zfar"}) number(*ortho, k, at(p, "orthographic"));
}

void GltfJsonChecker::light(const json& l, const std::string& p) const {
    string(l, "name", p);
    string(l, "type", p);
    numbers(l, "color", 3, p);
    number(l, "intensity", p);
    number(l, "range", p);
    if (const json* spot = object(l, "spot", p)) {
        number(*spot, "innerConeAngle", at(p, "spot"));
        number(*spot, "outerConeAngle", at(p, "spot"));
    }
}

uint32_t readU32(const std::string& b, size_t at) {
    uint32_t v;
    std::memcpy(&v, b.data() + at, 4);  // glb is little-endian, as is every platform Tyndall builds on
    return v;
}

}  // namespace

nlohmann::json gltfJsonOf(const std::string& bytes, bool binary) {
    if (!binary) return json::parse(bytes, nullptr, /*allow_exceptions=*/false);
    // 12-byte header, then the first chunk: its length, type "JSON", the JSON text.
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || readU32(bytes, 16) != 0x4E4F534Au)
        return json::value_t::discarded;
    size_t length = readU32(bytes, 12);
    if (length > bytes.size() - 20) return json::value_t::discarded;
    return json::parse(bytes.begin() + 20, bytes.begin() + 20 + std::ptrdiff_t(length), nullptr, false);
}

void checkGltfJson(const nlohmann::json& root, const std::string& file) {
    GltfJsonChecker(file).document(root);
}

}  // namespace tyndall
