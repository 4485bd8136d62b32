#pragma once
// Small scenes with density-grid media for the heterogeneous tests, plus rendering helpers.
#include <cmath>
#include <memory>
#include <string>

#include "core/accumulator.h"
#include "core/image_io.h"
#include "core/mesh_builders.h"
#include "core/scene.h"
#include "core/settings.h"
#include "cpu/pass_renderer.h"

namespace tyndall::test {

struct GridRoom {
    Vec3 lo{-1.0f}, hi{1.0f};  ///< the closed room (inward walls); its interior is the global medium
    Rgb wallAlbedo{0.0f};
    Vec3 light{0.0f, 0.5f, 0.0f};
    Rgb intensity{1.0f};  ///< point light, W/sr
    Vec3 eye{0.0f, 0.0f, 0.9f};
    Vec3 target{0.0f, 0.0f, 0.0f};
    float yFovDegrees = 50.0f;
};

/// A closed diffuse room filled with `medium` (the scene's global medium), one point light, one
/// pinhole camera; finalized and validated.
inline Scene makeGridRoomScene(const GridRoom& r, const Medium& medium, const std::string& name) {
    Scene s;
    s.name = name;
    s.source = "<test scene>";
    Material wall;
    wall.name = "wall";
    wall.albedo = r.wallAlbedo;
    s.materials.push_back(wall);
    s.meshes.push_back(makeBox("room", r.lo, r.hi, 0, /*inward=*/true));
    s.media.push_back(medium);
    s.globalMedium = 0;
    Light l;
    l.name = "light";
    l.type = LightType::Point;
    l.position = r.light;
    l.intensity = r.intensity;
    s.lights.push_back(l);
    s.camera = Camera::lookAt(r.eye, r.target, {0, 1, 0}, r.yFovDegrees * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// Renders `passes` passes into a fresh accumulator.
inline Accumulator renderPasses(const Scene& scene, const RenderSettings& settings, uint64_t passes) {
    PassRenderer renderer(scene, settings);
    Accumulator acc(settings.width, settings.height);
    for (uint64_t p = 0; p < passes; ++p) acc.addPass(renderer.renderPass(p));
    return acc;
}

}  // namespace tyndall::test
