#pragma once
// Small scenes shared by renderer-level tests.
#include "loading/mesh_builders.h"
#include "core/scene.h"

namespace tyndall::test {

/// A material of `type` (the other parameters at their defaults: ior 1.5, opaque, untextured).
inline Material makeMaterial(const char* name, MaterialType type, Rgb albedo, Rgb emission = Rgb(0.0f)) {
    Material m;
    m.name = name;
    m.type = type;
    m.albedo = albedo;
    m.emission = emission;
    return m;
}

/// Appends makeMaterial(...) to `s`; returns its index.
inline int addMaterial(Scene& s, const char* name, MaterialType type, Rgb albedo, Rgb emission = Rgb(0.0f)) {
    s.materials.push_back(makeMaterial(name, type, albedo, emission));
    return int(s.materials.size() - 1);
}

/// A homogeneous medium (Henyey-Greenstein `g`).
inline Medium homogeneousMedium(Rgb sigmaS, Rgb sigmaA, float g = 0.0f, const char* name = "fog") {
    Medium m;
    m.name = name;
    m.sigmaS = sigmaS;
    m.sigmaA = sigmaA;
    m.g = g;
    return m;
}

/// A volumetric caustic in a small foggy box: a spot light above a glass sphere focuses a cone of
/// light below it (focus ~0.45 under the centre); dark diffuse walls; the camera looks at the cone.
inline Scene causticScene(float sigmaS = 0.5f, float sigmaA = 0.1f, float g = 0.0f) {
    Scene s;
    s.name = "test-caustic";
    s.source = "<test>";
    addMaterial(s, "wall", MaterialType::Diffuse, Rgb(0.25f));
    addMaterial(s, "glass", MaterialType::Dielectric, Rgb(1.0f));  // ior 1.5
    s.media.push_back(homogeneousMedium(Rgb(sigmaS), Rgb(sigmaA), g));
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("room", {-1.5f, -1.5f, -1.5f}, {1.5f, 1.5f, 1.5f}, 0, /*inward=*/true));
    s.meshes.push_back(makeSphere("ball", {0, 0, 0}, 0.3f, 4, 1));
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {0, 1.4f, 0};
    spot.direction = {0, -1, 0};
    spot.cosOuterAngle = std::cos(0.25f);
    spot.cosInnerAngle = std::cos(0.2f);
    spot.intensity = Rgb(20.0f);
    s.lights.push_back(spot);
    s.camera = Camera::lookAt({0, -0.3f, 1.4f}, {0, -0.45f, 0}, {0, 1, 0}, 0.9f);
    s.finalize();
    return s;
}

/// A directional light (the sun) shining along `direction` with `irradiance`.
inline Light sun(Vec3 direction, Rgb irradiance) {
    Light l;
    l.name = "sun";
    l.type = LightType::Directional;
    l.direction = normalize(direction);
    l.intensity = irradiance;
    return l;
}

/// A sun over two boxes of fog on a floor: the left one's hull an index-matched Interface (the
/// sun's photons cross it still direct: their first beams are left out and the shadow rays carry
/// that light), the right one's a rough dielectric (photons refracted into it are no longer
/// direct: their beams stay, and the shadow rays from inside it are blocked), or only the left one.
/// The camera looks down on both; a floor wider than 3 fills the rest of the view.
inline Scene sunOverFogBoxes(bool refracting, float floorHalf = 3.0f) {
    Scene s;
    s.name = "sun-fog-boxes";
    s.source = "<test scene>";
    const int floor = addMaterial(s, "floor", MaterialType::Diffuse, Rgb(0.15f));
    const int hull = addMaterial(s, "hull", MaterialType::Interface, Rgb(1.0f));
    const int glass = addMaterial(s, "rough water", MaterialType::Dielectric, Rgb(1.0f));
    s.materials[size_t(glass)].ior = 1.33f;
    s.materials[size_t(glass)].roughness = 0.7f;
    s.media.push_back(homogeneousMedium(Rgb(0.9f, 0.8f, 0.7f), Rgb(0.3f, 0.4f, 0.5f), 0.5f));
    s.media.push_back(s.media[0]);  // the right box's: sealed by its hull (no sun sample drawn there)
    s.meshes.push_back(makeQuad("floor", {-floorHalf, 0, floorHalf}, {2 * floorHalf, 0, 0}, {0, 0, -2 * floorHalf}, floor));
    TriangleMesh left = makeBox("left fog", {-1.3f, 0.001f, -0.6f}, {-0.1f, 1.0f, 0.6f}, hull);
    left.interiorMedium = 0;
    s.meshes.push_back(left);
    TriangleMesh right = makeBox("right fog", {0.1f, 0.001f, -0.6f}, {1.3f, 1.0f, 0.6f}, glass);
    right.interiorMedium = 1;
    if (refracting) s.meshes.push_back(right);
    s.lights.push_back(sun({0.2f, -0.7f, 0.7f}, Rgb(2.0f, 1.9f, 1.7f)));
    s.camera = Camera::lookAt({0.0f, 2.4f, 2.6f}, {0.0f, 0.4f, 0.0f}, {0, 1, 0}, 50.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// A 2.5-unit room of white (albedo 0.6) walls filled with thin fog (sigma_s 0.1), a unit point
/// light off-centre under the ceiling, the camera inside looking at the back wall.
inline Scene wallsFogBox() {
    Scene s;
    s.name = "walls-fog-box";
    s.source = "<test>";
    addMaterial(s, "white", MaterialType::Diffuse, Rgb(0.6f));
    s.media.push_back(homogeneousMedium(Rgb(0.1f), Rgb(0.0f)));
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("room", Vec3(-1.25f), Vec3(1.25f), 0, true));
    Light bulb;
    bulb.name = "bulb";
    bulb.type = LightType::Point;
    bulb.position = Vec3(0.3f, 1.05f, 0.6f);
    bulb.intensity = Rgb(1.0f);
    s.lights.push_back(bulb);
    s.camera = Camera::lookAt(Vec3(0, 0, 1.2f), Vec3(0, 0, -1.25f), {0, 1, 0}, 60.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

}  // namespace tyndall::test
