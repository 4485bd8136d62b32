// Scene representation: procedural meshes are closed and outward, finalize() resolves media and
// area lights, validate() names the offending element, the light sampler's expected power is the
// scene's emitted power, and the default scene is well formed.
#include "core/scene.h"

#include <gtest/gtest.h>

#include "loading/default_scene.h"
#include "core/error.h"
#include "core/light_sampler.h"
#include "loading/mesh_builders.h"

using namespace tyndall;

namespace {
// Signed volume by the divergence theorem: positive for closed, outward-oriented meshes.
double signedVolume(const TriangleMesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t)
        v += dot(m.vertex(t, 0), cross(m.vertex(t, 1), m.vertex(t, 2))) / 6.0;
    return v;
}
}  // namespace

TEST(MeshBuilders, ClosedAndOutward) {
    TriangleMesh box = makeBox("b", {0, 0, 0}, {1, 2, 3}, 0);
    EXPECT_TRUE(box.isClosed());
    EXPECT_NEAR(signedVolume(box), 6.0, 1e-5);
    EXPECT_NEAR(signedVolume(makeBox("b", {0, 0, 0}, {1, 2, 3}, 0, true)), -6.0, 1e-5);
    TriangleMesh sphere = makeSphere("s", {1, 2, 3}, 0.5f, 4, 0);
    EXPECT_TRUE(sphere.isClosed());
    EXPECT_NEAR(signedVolume(sphere), 4.0 / 3.0 * kPi * 0.125, 0.01 * 4.0 / 3.0 * kPi * 0.125);
    for (size_t i = 0; i < sphere.positions.size(); ++i)
        ASSERT_NEAR(dot(sphere.normals[i], normalize(sphere.positions[i] - Vec3(1, 2, 3))), 1.0f, 1e-5);
    TriangleMesh cyl = makeCylinder("c", {0, 0, 0}, {0, 2, 0}, 0.5f, 64, 0);
    EXPECT_TRUE(cyl.isClosed());
    EXPECT_NEAR(signedVolume(cyl), kPi * 0.25 * 2, 0.01 * kPi * 0.5);
    EXPECT_FALSE(makeQuad("q", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0).isClosed());
}

TEST(Scene, FinalizeResolvesMediaAndEmitters) {
    Scene s;
    s.name = "t";
    s.source = "<test>";
    s.materials = {Material{}, Material{"glass", MaterialType::Dielectric}};
    s.materials[0].emission = Rgb(2.0f);
    s.media.push_back(Medium{});
    s.globalMedium = 0;
    s.meshes.push_back(makeQuad("lamp", {0, 0, 0}, {1, 0, 0}, {0, 2, 0}, 0));
    s.meshes.push_back(makeSphere("ball", {0, 0, 3}, 1.0f, 2, 1));
    s.finalize();
    EXPECT_EQ(s.meshes[0].exteriorMedium, 0);
    EXPECT_EQ(s.meshes[0].interiorMedium, 0);       // opaque: interior = exterior
    EXPECT_EQ(s.meshes[1].interiorMedium, kVacuum);  // glass holds no fog by default
    ASSERT_EQ(s.emitters.size(), 2u);
    EXPECT_NEAR(s.emitters[0].area + s.emitters[1].area, 2.0f, 1e-6);
    EXPECT_NO_THROW(s.validate());
    LightSampler sampler(s);
    EXPECT_NEAR(sampler.totalPower().r, 2.0f * kPi * 2.0f, 1e-4);  // Le * pi * area
}

TEST(Scene, ValidateNamesTheOffendingElement) {
    Scene base = makeDefaultScene();
    auto expectError = [&](Scene s, const std::string& needle) {
        try {
            s.validate();
            ADD_FAILURE() << "no error for " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    Scene s = base;
    s.media[0].sigmaS = Rgb(-1.0f);
    expectError(s, "medium 'fog' (index 0)");
    s = base;
    s.media[0].g = 1.0f;
    expectError(s, "phase asymmetry");
    s = base;
    s.meshes[2].indices.push_back(999);
    s.meshes[2].indices.push_back(0);
    s.meshes[2].indices.push_back(1);
    expectError(s, "mesh 'back wall' (index 2): vertex index 999 out of range");
    s = base;
    s.meshes[0].interiorMedium = kVacuum;  // floor quad would bound a medium
    expectError(s, "mesh 'floor' (index 0): bounds a medium but is not a closed");
    s = base;
    s.lights[0].intensity.g = std::nanf("");
    expectError(s, "light 'spot' (index 0)");
    s = base;
    s.lights.clear();
    expectError(s, "no lights");
}

TEST(LightSampler, ExpectedPhotonPowerIsEmittedPower) {
    Scene s = makeDefaultScene();
    LightSampler sampler(s);
    Rgb expected = sampler.totalPower();
    Rng rng(3, 3);
    double sum[3] = {0, 0, 0};
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
        EmittedPhoton e = sampler.sample(rng);
        ASSERT_NEAR(length(e.ray.d), 1.0f, 1e-4);
        for (int c = 0; c < 3; ++c) sum[c] += e.power[c];
    }
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c] / n / expected[c], 1.0, 0.01) << c;
    // Spot power: numerical integral of the falloff over the sphere.
    const Light& spot = s.lights[0];
    double numeric = 0;
    const int m = 200000;
    for (int i = 0; i < m; ++i) {
        float mu = -1.0f + 2.0f * (i + 0.5f) / m;
        numeric += spot.intensity.r * spot.spotFalloff(mu) * 2 * kPi * (2.0 / m);
    }
    EXPECT_NEAR(LightSampler::lightPower(spot, s.bounds).r / numeric, 1.0, 1e-3);
}

TEST(DefaultScene, IsValidWithFogGlassMirrorAndASpot) {
    Scene s = makeDefaultScene();
    EXPECT_NO_THROW(s.validate());
    bool glass = false, mirror = false;
    for (const auto& m : s.meshes) {
        glass |= s.materialOf(int(&m - s.meshes.data())).type == MaterialType::Dielectric && m.isClosed();
        mirror |= s.materialOf(int(&m - s.meshes.data())).type == MaterialType::Mirror;
    }
    EXPECT_TRUE(glass);
    EXPECT_TRUE(mirror);
    EXPECT_GE(s.globalMedium, 0);
    EXPECT_EQ(s.lights[0].type, LightType::Spot);
}
