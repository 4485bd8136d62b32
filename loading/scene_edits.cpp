#include "loading/scene_edits.h"

#include <cmath>

#include "core/error.h"
#include "loading/json_reader.h"

namespace tyndall {

namespace {
nlohmann::json vec(const Vec3& v) { return {v.x, v.y, v.z}; }
nlohmann::json rgb(const Rgb& c) { return {c.r, c.g, c.b}; }

/// Arrays of the edits must match the scene one to one, by name, so that an edited base is noticed:
/// `apply(entry, item)` reads each entry (its "name" already checked) into the scene's item, and
/// the entry is finished after it. `what`: the array's name ("lights"), `one`: an item's ("light").
template <class T, class Apply>
void applyMatching(const JsonValue& list, std::vector<T>& items, const char* what, const char* one, Apply apply) {
    std::vector<JsonValue> entries = list.elements();
    const size_t count = items.size();
    if (entries.size() != count)
        list.fail("expected " + std::to_string(count) + " " + what + " (the base scene has " + std::to_string(count) +
                  "), got " + std::to_string(entries.size()));
    for (size_t i = 0; i < count; ++i) {
        JsonObject o = entries[i].object();
        T& item = items[i];
        std::string name = o.require("name").string();
        if (name != item.name)
            o.fail(std::string(one) + " " + std::to_string(i) + " of the base scene is '" + item.name + "', not '" +
                   name + "'");
        apply(o, item);
        o.finish();
    }
}
}  // namespace

nlohmann::json sceneEdits(const Scene& scene) {
    nlohmann::json j;
    const Camera& c = scene.camera;
    j["camera"] = {{"position", vec(c.position)}, {"forward", vec(c.forward)},     {"up", vec(c.up)},
                   {"y_fov", c.yFov},             {"lens_radius", c.lensRadius}, {"focus_distance", c.focusDistance}};
    j["lights"] = nlohmann::json::array();
    for (const Light& l : scene.lights)
        j["lights"].push_back({{"name", l.name},
                               {"position", vec(l.position)},
                               {"direction", vec(l.direction)},
                               {"intensity", rgb(l.intensity)}});
    j["media"] = nlohmann::json::array();
    for (const Medium& m : scene.media)
        j["media"].push_back({{"name", m.name},
                              {"sigma_s", rgb(m.sigmaS)},
                              {"sigma_a", rgb(m.sigmaA)},
                              {"g", m.g},
                              {"emission_scale", m.emissionScale}});
    if (scene.environment)
        j["environment"] = {{"scale", scene.environment->scale()}, {"rotate", scene.environment->rotation()}};
    return j;
}

nlohmann::json twinSceneEdits(const Scene& edited, const Scene& twin) {
    if (twin.media.size() != edited.media.size())
        throw Error("twin scene '" + twin.name + "' has " + std::to_string(twin.media.size()) + " media, its base '" +
                    edited.name + "' " + std::to_string(edited.media.size()));
    nlohmann::json j = sceneEdits(edited);
    j["media"] = sceneEdits(twin)["media"];
    for (size_t i = 0; i < twin.media.size(); ++i) j["media"][i]["emission_scale"] = edited.media[i].emissionScale;
    return j;
}

void applySceneEdits(Scene& scene, const nlohmann::json& edits, const std::string& where) {
    JsonObject top = JsonValue(edits, where, "/edits").object();
    auto camera = top.get("camera"), lights = top.get("lights"), media = top.get("media");
    auto environment = top.get("environment");
    top.finish();
    if (camera) {
        JsonObject o = camera->object();
        Vec3 p = o.require("position").vec3(), f = o.require("forward").direction(), up = o.require("up").direction();
        if (!(length(cross(normalize(f), normalize(up))) > 1e-4f)) o.fail("'up' is parallel to 'forward'");
        float fov = float(o.require("y_fov").number(1e-5, 3.12));
        Camera c = Camera::lookAt(p, p + f, up, fov);
        c.lensRadius = float(o.number("lens_radius", 0.0, 0.0));
        c.focusDistance = float(o.number("focus_distance", 1.0, 1e-6));
        o.finish();
        scene.camera = c;
    }
    if (lights) {
        applyMatching(*lights, scene.lights, "lights", "light", [](JsonObject& o, Light& l) {
            l.position = o.require("position").vec3();
            l.direction = normalize(o.require("direction").direction());
            l.intensity = o.require("intensity").rgb();
        });
    }
    if (media) {
        applyMatching(*media, scene.media, "media", "medium", [](JsonObject& o, Medium& m) {
            m.sigmaS = o.require("sigma_s").rgb();
            m.sigmaA = o.require("sigma_a").rgb();
            m.g = float(o.require("g").number(-0.999, 0.999));
            m.emissionScale = float(o.number("emission_scale", 1.0, 0.0, 1e6));
            Rgb t = m.sigmaT();
            if (!(t.r > 0 || t.g > 0 || t.b > 0)) o.fail("sigma_s + sigma_a must not be 0");
            if (m.density && (std::abs(t.r - t.g) > 1e-5f * t.r || std::abs(t.r - t.b) > 1e-5f * t.r))
                o.fail("a density-grid medium needs grey extinction (sigma_s + sigma_a equal in r, g, b)");
        });
    }
    if (environment) {
        JsonObject o = environment->object();
        if (!scene.environment) o.fail("the base scene has no environment");
        scene.environment->setScale(float(o.require("scale").number(0.0, 1e30)));
        scene.environment->setRotation(float(o.require("rotate").number(-1e6, 1e6)));
        o.finish();
    }
}

nlohmann::json viewFileJson(const std::string& name, const std::string& base, const std::string& baseCamera,
                            const nlohmann::json& edits, const nlohmann::json& render) {
    return {{"name", name}, {"base", base}, {"base_camera", baseCamera}, {"edits", edits}, {"render", render}};
}

bool isViewFile(const nlohmann::json& doc) { return doc.is_object() && doc.contains("base"); }

}  // namespace tyndall
