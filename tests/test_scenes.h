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

}  // namespace tyndall::test
