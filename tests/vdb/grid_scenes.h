#pragma once
// Small scenes with density-grid media for the heterogeneous tests, plus rendering helpers.
#include <cmath>
#include <memory>
#include <string>

#include "core/accumulator.h"
#include "core/image_io.h"
#include "loading/mesh_builders.h"
#include "core/scene.h"
#include "core/settings.h"
#include "loading/vdb_grid.h"
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

/// The room for the real smoke plume ../shared/assets/vdb/openusd/smoke_000002.vdb.
inline GridRoom smoke000002Room() {
    GridRoom room;
    room.lo = Vec3(-2.0f, 0.0f, -2.5f);
    room.hi = Vec3(2.0f, 3.5f, 2.5f);
    room.wallAlbedo = Rgb(0.25f);
    room.light = Vec3(1.4f, 3.2f, 1.0f);
    room.intensity = Rgb(12.0f);
    room.eye = Vec3(0.0f, 1.6f, 2.4f);
    room.target = Vec3(0.0f, 1.5f, 0.0f);
    room.yFovDegrees = 60.0f;
    return room;
}

/// The plume of smoke_000002.vdb (`path`) standing in smoke000002Room(): the file is z-up, ~6.6 x
/// 6.5 x 10.4 units; it is turned y-up (y' = z, z' = -y), scaled by 0.3 and stood on the floor.
inline Scene makeSmoke000002Room(const std::string& path) {
    Affine3 turn;
    turn.m[0][0] = 0.3f;
    turn.m[1][1] = 0.0f, turn.m[1][2] = 0.3f;
    turn.m[2][1] = -0.3f, turn.m[2][2] = 0.0f;
    VdbGridSource src;
    src.file = path;
    src.transform = turn;
    Bounds3 b = VdbDensityGrid::load(src)->bounds();
    Vec3 shift = Vec3(0.0f, 0.05f, 0.0f) - Vec3(b.center().x, b.lo.y, b.center().z);
    for (int i = 0; i < 3; ++i) src.transform.m[i][3] = shift[i];
    Medium smoke;
    smoke.name = "smoke";
    smoke.sigmaS = Rgb(4.0f, 3.8f, 3.6f);
    smoke.sigmaA = Rgb(0.5f, 0.7f, 0.9f);
    smoke.g = 0.3f;
    smoke.density = VdbDensityGrid::load(src);
    return makeGridRoomScene(smoke000002Room(), smoke, "smoke_000002 room");
}

/// Renders `passes` passes into a fresh accumulator.
inline Accumulator renderPasses(const Scene& scene, const RenderSettings& settings, uint64_t passes) {
    PassRenderer renderer(scene, settings);
    Accumulator acc(settings.width, settings.height);
    for (uint64_t p = 0; p < passes; ++p) acc.addPass(renderer.renderPass(p));
    return acc;
}

}  // namespace tyndall::test
