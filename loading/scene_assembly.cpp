#include "loading/scene_assembly.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "loading/scene_environment.h"

namespace tyndall {

WarnOnce::WarnOnce(std::function<void(const std::string&)> sink) : m_sink(std::move(sink)) {
    if (!m_sink) m_sink = [](const std::string& line) { std::fprintf(stderr, "tyndall: warning: %s\n", line.c_str()); };
}

void WarnOnce::operator()(const std::string& kind, const std::string& message) {
    if (m_seen.insert(kind).second) m_sink(message);
}

std::vector<int> meshesNamed(const Scene& scene, const std::string& name) {
    std::vector<int> out;
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const std::string& n = scene.meshes[i].name;
        bool primitive = n.size() > name.size() + 1 && n.compare(0, name.size(), name) == 0 && n[name.size()] == '#' &&
                         n.find_first_not_of("0123456789", name.size() + 1) == std::string::npos;
        if (n == name || primitive) out.push_back(int(i));
    }
    return out;
}

Camera frameBounds(const Bounds3& bounds) {
    const float fov = 40.0f * kPi / 180.0f;
    Vec3 center = bounds.empty() ? Vec3(0.0f) : bounds.center();
    float radius = bounds.empty() ? 1.0f : std::max(0.5f * length(bounds.diagonal()), 1e-3f);
    float distance = radius / std::sin(0.5f * fov) * 1.05f;
    Vec3 eye = center + normalize(Vec3(0.0f, 0.3f, 1.0f)) * distance;
    return Camera::lookAt(eye, center, {0, 1, 0}, fov);
}

void checkTriangleBudget(size_t n, const SceneLoadOptions& options, const std::string& where) {
    if (n > options.maxTriangles)
        throw Error(where + ": the scene exceeds the limit of " + std::to_string(options.maxTriangles) + " triangles");
}

namespace {

int selectCamera(const std::vector<NamedCamera>& cameras, const std::string& selector, const std::string& file) {
    if (selector.empty()) return 0;
    for (size_t i = 0; i < cameras.size(); ++i)
        if (cameras[i].name == selector) return int(i);
    bool digits = selector.find_first_not_of("0123456789") == std::string::npos && selector.size() < 9;
    if (digits && std::stoul(selector) < cameras.size()) return int(std::stoul(selector));
    std::string list;
    for (size_t i = 0; i < cameras.size(); ++i)
        list += (i ? ", " : "") + std::to_string(i) + " '" + cameras[i].name + "'";
    throw Error(file + ": --camera " + selector + ": no such camera (this scene has: " + list + ")");
}

}  // namespace

SceneFile finishScene(SceneDraft draft, const std::string& file, const SceneLoadOptions& options, WarnOnce& warn) {
    Scene& scene = draft.scene;
    scene.source = file;
    checkTriangleBudget(scene.triangleCount(), options, file);

    SceneFile out;
    if (draft.cameras.empty()) {
        Bounds3 b;
        for (const TriangleMesh& m : scene.meshes)
            for (const Vec3& p : m.positions) b.extend(p);
        draft.cameras.push_back({"automatic", frameBounds(b)});
    }
    for (const NamedCamera& c : draft.cameras) out.cameras.push_back(c.name), out.cameraViews.push_back(c.camera);
    scene.camera = draft.cameras[size_t(selectCamera(draft.cameras, options.camera, file))].camera;

    if (!options.environment.empty())
        scene.environment = loadEnvironmentImage(options.environment, "--environment", warn, options.budget.get());
    scene.finalize();
    if (draft.headlightWhenDark && scene.lights.empty() && scene.emitters.empty() && !scene.environment &&
        !scene.bounds.empty()) {
        // A spot at the camera aimed at the scene's bounding sphere, about 1 W/m^2 at its centre.
        Vec3 toCenter = scene.bounds.center() - scene.camera.position;
        float d = length(toCenter), r = 0.5f * length(scene.bounds.diagonal());
        Light head;
        head.name = "headlight";
        head.position = scene.camera.position;
        head.intensity = Rgb(std::max(d * d, 1e-6f));
        if (d > 1.05f * r) {
            head.type = LightType::Spot;
            head.direction = toCenter / d;
            float halfAngle = std::min(1.15f * std::asin(r / d), 1.4f);
            head.cosOuterAngle = std::cos(halfAngle);
            head.cosInnerAngle = std::cos(0.85f * halfAngle);
        } else {
            head.type = LightType::Point;  // the camera is inside the scene's bounds
        }
        scene.lights.push_back(head);
        warn("headlight", file + ": no lights and no emissive materials: added a light at the camera");
    }
    scene.validate();
    out.scene = std::move(scene);
    return out;
}

}  // namespace tyndall
