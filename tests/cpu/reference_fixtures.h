#pragma once
// Scenes and helpers shared by the reference-tracer tests (self-checks, analytic scene,
// PPB-versus-reference consistency).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/accumulator.h"
#include "core/density_grid.h"
#include "core/image_io.h"
#include "core/mesh_builders.h"
#include "core/scene.h"
#include "cpu/pass_renderer.h"

namespace tyndall::test {

/// A density field rho(x) = a + b dot(x, axis) over the unit sphere (grid media): linear, so the
/// optical depth of any segment inside the sphere is its length times rho at its midpoint.
class LinearRampDensity : public DensityGrid {
public:
    LinearRampDensity(float a, float b, Vec3 axis) : m_a(a), m_b(b), m_axis(normalize(axis)) {}
    float density(const Vec3& p) const override {
        return bounds().contains(p) ? std::max(0.0f, m_a + m_b * dot(p, m_axis)) : 0.0f;
    }
    Bounds3 bounds() const override { return {Vec3(-1.01f), Vec3(1.01f)}; }
    float maxDensity() const override { return m_a + std::abs(m_b) * 1.01f * std::sqrt(3.0f); }
    float meanDensity() const override { return m_a; }

private:
    float m_a, m_b;
    Vec3 m_axis;
};

/// A sphere of radius `radius` at the origin filled with `medium`, `light` (a point or spot light,
/// normally at the centre), nothing else (vacuum outside). The hull is an index-matched Interface
/// (light passes straight through) unless `diffuseWall` makes it a diffuse inner wall of albedo
/// `wallAlbedo` (a closed room with the medium inside).
inline Scene makeMediumSphereScene(const Medium& medium, float radius, const Light& light, const Camera& camera,
                                   bool diffuseWall = false, Rgb wallAlbedo = Rgb(0.5f)) {
    Scene s;
    s.name = "medium-sphere";
    s.source = "<test scene>";
    Material hull;
    hull.name = diffuseWall ? "wall" : "hull";
    hull.type = diffuseWall ? MaterialType::Diffuse : MaterialType::Interface;
    hull.albedo = wallAlbedo;
    s.materials.push_back(hull);
    s.media.push_back(medium);
    TriangleMesh sphere = makeSphere("sphere", Vec3(0.0f), radius, 5, 0);
    sphere.interiorMedium = 0;
    sphere.exteriorMedium = kVacuum;
    s.meshes.push_back(sphere);
    s.lights.push_back(light);
    s.camera = camera;
    s.finalize();
    s.validate();
    return s;
}

/// The consistency scene: a 2 x 2 x 2 room full of fog, coloured walls, a spot light shining down
/// onto the floor (its cone misses both specular objects, so the reference can reach everything
/// it lights), a small area light on the ceiling, a mirror on the back wall and a glass sphere.
/// Secondary camera segments (through the mirror and the glass) gather beams on the CPU; primary
/// ones go through the beam rasterizer; diffuse hits use surface photons.
inline Scene makeConsistencyScene() {
    Scene s;
    s.name = "consistency-room";
    s.source = "<test scene>";
    auto material = [&](const char* name, MaterialType type, Rgb albedo, Rgb emission = Rgb(0.0f)) {
        Material m;
        m.name = name;
        m.type = type;
        m.albedo = albedo;
        m.emission = emission;
        s.materials.push_back(m);
        return int(s.materials.size() - 1);
    };
    int white = material("white", MaterialType::Diffuse, Rgb(0.7f));
    int red = material("red", MaterialType::Diffuse, Rgb(0.7f, 0.2f, 0.15f));
    int green = material("green", MaterialType::Diffuse, Rgb(0.2f, 0.6f, 0.3f));
    int mirror = material("mirror", MaterialType::Mirror, Rgb(0.9f));
    int glass = material("glass", MaterialType::Dielectric, Rgb(1.0f));
    int lamp = material("lamp", MaterialType::Diffuse, Rgb(0.5f), Rgb(3.0f, 2.8f, 2.4f));

    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.15f, 0.16f, 0.18f);
    fog.sigmaA = Rgb(0.02f);
    fog.g = 0.3f;
    s.media.push_back(fog);
    s.globalMedium = 0;

    // Room x in [-1, 1], y in [0, 2], z in [-1, 1]; walls face inward.
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white));
    s.meshes.push_back(makeQuad("ceiling", {-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white));
    s.meshes.push_back(makeQuad("back wall", {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white));
    s.meshes.push_back(makeQuad("front wall", {1, 0, 1}, {-2, 0, 0}, {0, 2, 0}, white));
    s.meshes.push_back(makeQuad("left wall", {-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, red));
    s.meshes.push_back(makeQuad("right wall", {1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green));
    s.meshes.push_back(makeQuad("mirror", {-0.9f, 0.3f, -0.99f}, {0.8f, 0, 0}, {0, 1.3f, 0}, mirror));
    s.meshes.push_back(makeSphere("glass sphere", {0.45f, 0.36f, -0.45f}, 0.3f, 3, glass));
    // Emits downward (the quad's normal is -y), slightly below the ceiling.
    s.meshes.push_back(makeQuad("lamp", {0.35f, 1.98f, 0.25f}, {0.4f, 0, 0}, {0, 0, 0.4f}, lamp));

    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-0.45f, 1.9f, -0.2f};
    spot.direction = normalize(Vec3(0.05f, -1.0f, 0.05f));
    spot.cosOuterAngle = std::cos(18.0f * kPi / 180.0f);
    spot.cosInnerAngle = std::cos(12.0f * kPi / 180.0f);
    spot.intensity = Rgb(6.0f, 5.6f, 4.8f);
    s.lights.push_back(spot);

    s.camera = Camera::lookAt({0.1f, 1.1f, 0.95f}, {-0.05f, 0.75f, -1.0f}, {0, 1, 0}, 70.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// Mean of `passes` PPB passes [firstPass, firstPass + passes) of `renderer`.
inline Image renderPpbPasses(const PassRenderer& renderer, uint64_t firstPass, uint64_t passes) {
    Accumulator acc(renderer.settings().width, renderer.settings().height);
    for (uint64_t p = firstPass; p < firstPass + passes; ++p) acc.addPass(renderer.renderPass(p));
    return acc.mean();
}

/// Writes `image` to TYNDALL_TEST_OUTPUT_DIR/<name>.exr (evidence for a failed test).
inline void writeEvidence(const std::string& name, const Image& image) {
    writeImage(std::string(TYNDALL_TEST_OUTPUT_DIR) + "/" + name + ".exr", image);
}

/// Per-pixel |a - b| (for the error image written on failure).
inline Image absDifference(const Image& a, const Image& b) {
    Image d(a.width, a.height);
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) d.pixels[i][c] = std::abs(a.pixels[i][c] - b.pixels[i][c]);
    return d;
}

}  // namespace tyndall::test
