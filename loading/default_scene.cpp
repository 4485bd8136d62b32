#include "loading/default_scene.h"

#include <nlohmann/json.hpp>

#include "loading/mesh_builders.h"

namespace tyndall {

Scene makeDefaultScene() {
    Scene s;
    s.name = "caustic-box";
    s.source = "<built-in default scene>";

    auto material = [&](const std::string& name, MaterialType type, Rgb albedo, float ior = 1.5f) {
        Material m;
        m.name = name;
        m.type = type;
        m.albedo = albedo;
        m.ior = ior;
        s.materials.push_back(m);
        return int(s.materials.size() - 1);
    };
    int white = material("white", MaterialType::Diffuse, Rgb(0.45f, 0.444f, 0.432f));
    int red = material("red", MaterialType::Diffuse, Rgb(0.42f, 0.108f, 0.084f));
    int teal = material("teal", MaterialType::Diffuse, Rgb(0.084f, 0.30f, 0.288f));
    int mirror = material("mirror", MaterialType::Mirror, Rgb(0.92f));
    int glass = material("glass", MaterialType::Dielectric, Rgb(1.0f), 1.5f);
    int frame = material("frame", MaterialType::Diffuse, Rgb(0.08f));

    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.06f);
    fog.sigmaA = Rgb(0.009f);
    fog.g = 0.25f;
    s.media.push_back(fog);
    s.globalMedium = 0;

    // Room: x in [-2, 2], y in [0, 3], z in [-2.5, 2.5]; walls face inward.
    const float X = 2.0f, Y = 3.0f, Z = 2.5f;
    s.meshes.push_back(makeQuad("floor", {-X, 0, Z}, {2 * X, 0, 0}, {0, 0, -2 * Z}, white));
    s.meshes.push_back(makeQuad("ceiling", {-X, Y, -Z}, {2 * X, 0, 0}, {0, 0, 2 * Z}, white));
    s.meshes.push_back(makeQuad("back wall", {-X, 0, -Z}, {2 * X, 0, 0}, {0, Y, 0}, white));
    s.meshes.push_back(makeQuad("front wall", {X, 0, Z}, {-2 * X, 0, 0}, {0, Y, 0}, white));
    s.meshes.push_back(makeQuad("left wall", {-X, 0, Z}, {0, 0, -2 * Z}, {0, Y, 0}, red));
    s.meshes.push_back(makeQuad("right wall", {X, 0, -Z}, {0, 0, 2 * Z}, {0, Y, 0}, teal));

    // A mirror on the back wall, right of centre, slightly in front of it, with a dark frame.
    s.meshes.push_back(makeQuad("mirror frame", {0.45f, 0.35f, -Z + 0.005f}, {1.3f, 0, 0}, {0, 2.1f, 0}, frame));
    s.meshes.push_back(makeQuad("mirror", {0.5f, 0.4f, -Z + 0.01f}, {1.2f, 0, 0}, {0, 2.0f, 0}, mirror));

    // The glass sphere on a slim pedestal.
    const Vec3 sphereCenter{-0.35f, 1.15f, -0.7f};
    const float sphereRadius = 0.42f;
    s.meshes.push_back(makeSphere("glass sphere", sphereCenter, sphereRadius, 5, glass));
    s.meshes.push_back(makeCylinder("pedestal", {-0.35f, 0.0f, -0.7f}, {-0.35f, 0.72f, -0.7f}, 0.05f, 24, frame));

    // Small bright spot, high on the left, aimed through the sphere.
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-1.75f, 2.85f, 0.4f};
    spot.direction = normalize(sphereCenter - spot.position);
    float dist = length(sphereCenter - spot.position);
    float halfAngle = std::atan(sphereRadius * 1.08f / dist);  // nearly all of it through the sphere
    spot.cosOuterAngle = std::cos(halfAngle);
    spot.cosInnerAngle = std::cos(0.8f * halfAngle);
    spot.intensity = Rgb(150.0f, 130.0f, 100.0f);
    s.lights.push_back(spot);

    // A dim fill so the room reads: a weak warm point light near the front ceiling.
    Light fill;
    fill.name = "fill";
    fill.type = LightType::Point;
    fill.position = {1.2f, 2.7f, 1.6f};
    fill.intensity = Rgb(0.35f, 0.33f, 0.3f);
    s.lights.push_back(fill);

    s.camera = Camera::lookAt({0.35f, 1.45f, 2.35f}, {-0.2f, 1.05f, -1.0f}, {0, 1, 0}, 62.0f * kPi / 180.0f);
    s.finalize();
    return s;
}

nlohmann::json defaultSceneRender() { return {{"surface_radius", 0.3}}; }

}  // namespace tyndall
