#pragma once
// Small scenes shared by renderer-level tests.
#include "loading/mesh_builders.h"
#include "core/scene.h"

namespace tyndall::test {

/// A volumetric caustic in a small foggy box: a spot light above a glass sphere focuses a cone of
/// light below it (focus ~0.45 under the centre); dark diffuse walls; the camera looks at the cone.
inline Scene causticScene(float sigmaS = 0.5f, float sigmaA = 0.1f, float g = 0.0f) {
    Scene s;
    s.name = "test-caustic";
    s.source = "<test>";
    Material wall;
    wall.name = "wall";
    wall.albedo = Rgb(0.25f);
    Material glass;
    glass.name = "glass";
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.5f;
    glass.albedo = Rgb(1.0f);
    s.materials = {wall, glass};
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(sigmaS);
    fog.sigmaA = Rgb(sigmaA);
    fog.g = g;
    s.media.push_back(fog);
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
