// Direct light by shadow rays (cpu/direct_light.h, docs/algorithm.md "Direct light by shadow rays").
//
// 1. Next-event estimation alone against closed forms, on a diffuse floor: a point light in
//    homogeneous fog (E = I cos / d^2 exp(-sigma_t d), exact: one deterministic sample), a spot
//    light inside, in the smoothstep band of and outside its cone, a directional light through fog
//    clipped to the scene bounds, a square area light (the exact form factor of a parallel square,
//    Monte Carlo mean within 4 standard errors), an alpha-masked occluder (cut-out half passes,
//    opaque half blocks) and a normal-mapped hit (the shading cosine max(0, wi . ns), not the
//    geometric one).
// 2. PPB with direct light where photons and shadow rays meet, against the in-tree path tracer or
//    PPB with photons only: fog and diffuse walls round a point light (the walls' direct light from
//    shadow rays, their indirect light and the fog from photons), an area light seen by the floor
//    only in a mirror (photons through the mirror must still be stored), a point light half behind
//    a glass slab (the caustic half from photons, the open half from shadow rays).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/light_sampler.h"
#include "cpu/direct_light.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr float kSigmaT = 0.35f;  // fog of the closed-form tests: sigma_s 0.25 + sigma_a 0.1

/// A diffuse floor y = 0 over x, z in [-5, 5] facing up, and a small marker quad at y = 3 in the
/// corner x, z in [4, 5] so the scene bounds (where the global medium exists) reach y = 3 without
/// anything above the floor's middle. `fog`: a homogeneous global medium of extinction kSigmaT.
Scene floorScene(bool fog, const std::vector<Light>& lights) {
    Scene s;
    s.name = "floor";
    s.source = "<test>";
    Material white;
    white.name = "white";
    white.albedo = Rgb(0.5f);
    s.materials.push_back(white);
    s.meshes.push_back(makeQuad("floor", {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, 0));
    s.meshes.push_back(makeQuad("marker", {4, 3, 4}, {1, 0, 0}, {0, 0, 1}, 0));
    if (fog) {
        Medium m;
        m.name = "fog";
        m.sigmaS = Rgb(0.25f);
        m.sigmaA = Rgb(0.1f);
        s.media.push_back(m);
        s.globalMedium = 0;
    }
    s.lights = lights;
    s.camera = Camera::lookAt({0, 1, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f);
    return s;
}

/// The floor hit at (x, 0, z), seen from above.
SurfaceHit floorHit(float x, float z) {
    SurfaceHit hit;
    hit.mesh = 0;
    hit.p = {x, 0, z};
    hit.ng = hit.ns = {0, 1, 0};
    hit.t = 1;
    return hit;
}

/// One NEE estimate at the floor point (x, 0, z) (delta lights in homogeneous media: exact).
float directAt(const Scene& scene, float x, float z, uint64_t key = 0) {
    EmbreeScene rt(scene);
    LightSampler lights(scene);
    DirectLight dl(rt, lights);
    SurfaceHit hit = floorHit(x, z);
    Rng rng = Rng::forKey(1, 0, key, StreamPurpose::Test);
    return dl.diffuse(hit, hitSide(hit, {0, -1, 0}), scene.globalMedium, rng, false).g;
}

using test::pointLight;

TEST(DirectLight, PowerHeuristicIsFiniteAndSumsToOneAtEveryScale) {
    // Pdfs of 1.9e19 and more came from nearly smooth GGX glass under a sky map: their squares
    // overflow a float, and the weight was inf / inf (NaN pixels in the path tracer's image).
    for (float a : {1e-30f, 0.08f, 1.0f, 3e4f, 1.9e19f, 2.8e19f, 1e38f}) {
        for (float b : {1e-30f, 0.08f, 1.0f, 3e4f, 1.9e19f, 1e38f}) {
            const float wa = powerHeuristic(a, b), wb = powerHeuristic(b, a);
            ASSERT_TRUE(std::isfinite(wa)) << a << " " << b;
            EXPECT_NEAR(wa + wb, 1.0f, 1e-6f) << a << " " << b;
            const double exact = double(a) * a / (double(a) * a + double(b) * b);
            EXPECT_NEAR(wa, exact, 1e-6) << a << " " << b;
        }
    }
    EXPECT_EQ(powerHeuristic(2e19f, 0.08f), 1.0f);
    EXPECT_EQ(powerHeuristic(0.0f, 1.0f), 0.0f);
    EXPECT_EQ(powerHeuristic(1.0f, 0.0f), 1.0f);
    EXPECT_EQ(powerHeuristic(kInfinity, 1.0f), 1.0f);
    EXPECT_EQ(powerHeuristic(1.0f, kInfinity), 0.0f);
}

TEST(DirectLight, PointLightInFogGivesICosOverDistanceSquaredTimesTransmittance) {
    const Vec3 light{0.4f, 2.0f, -0.3f};
    Scene s = floorScene(true, {pointLight(light, 3.0f)});
    s.finalize();
    for (Vec3 p : {Vec3(0, 0, 0), Vec3(1.5f, 0, 0.5f), Vec3(-2.0f, 0, -1.0f)}) {
        Vec3 toLight = light - p;
        float d = length(toLight), cosine = toLight.y / d;
        float expected = 3.0f * cosine / (d * d) * std::exp(-kSigmaT * d);
        EXPECT_NEAR(directAt(s, p.x, p.z), expected, 1e-4f * expected) << p.x << " " << p.z;
    }
    // The same light in vacuum: no transmittance (the fog's factor is 0.4-0.5 here, so a shadow ray
    // without transmittance fails the check above by far more than its tolerance).
    Scene vacuum = floorScene(false, {pointLight(light, 3.0f)});
    vacuum.finalize();
    Vec3 toLight = light;
    float d = length(toLight);
    EXPECT_NEAR(directAt(vacuum, 0, 0), 3.0f * (toLight.y / d) / (d * d), 1e-4f);
}

TEST(DirectLight, SpotLightFollowsItsConeAndSmoothstepFalloff) {
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {0, 2, 0};
    spot.direction = {0, -1, 0};
    spot.cosInnerAngle = std::cos(20.0f * kPi / 180.0f);
    spot.cosOuterAngle = std::cos(40.0f * kPi / 180.0f);
    spot.intensity = Rgb(5.0f);
    Scene s = floorScene(true, {spot});
    s.finalize();
    // Inside the inner cone, in the band (30 degrees off axis), and outside (50 degrees).
    for (float degrees : {10.0f, 30.0f, 50.0f}) {
        float x = 2.0f * std::tan(degrees * kPi / 180.0f);
        float d = std::sqrt(x * x + 4.0f), cosine = 2.0f / d;
        float t = (cosine - spot.cosOuterAngle) / (spot.cosInnerAngle - spot.cosOuterAngle);
        float falloff = degrees < 20 ? 1.0f : degrees > 40 ? 0.0f : t * t * (3 - 2 * t);
        float expected = 5.0f * falloff * cosine / (d * d) * std::exp(-kSigmaT * d);
        EXPECT_NEAR(directAt(s, x, 0), expected, 1e-4f * expected + 1e-7f) << degrees;
        if (degrees == 30.0f) {
            EXPECT_GT(falloff, 0.1f);
        }
    }
}

TEST(DirectLight, DirectionalLightCrossesTheFogUpToTheSceneBounds) {
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = normalize(Vec3(-0.6f, -0.8f, 0.0f));
    sun.intensity = Rgb(2.0f);
    Scene s = floorScene(true, {sun});
    s.finalize();
    // From (0, 0, 0) toward the sun (0.6, 0.8, 0): the bounds' top y = 3 is 3.75 away.
    float expected = 2.0f * 0.8f * std::exp(-kSigmaT * 3.75f);
    EXPECT_NEAR(directAt(s, 0, 0), expected, 1e-4f * expected);
}

TEST(DirectLight, SquareAreaLightMatchesItsFormFactor) {
    // A square of side a, radiance Le, facing down at height h over the point: E = 4 Le X/sqrt(1+X^2)
    // atan(X/sqrt(1+X^2)) with X = a / (2h) (four corner rectangles of the parallel-plate form factor).
    const float a = 0.8f, h = 1.0f, Le = 2.0f;
    Scene s = floorScene(false, {});
    Material lamp;
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.0f);
    lamp.emission = Rgb(Le);
    s.materials.push_back(lamp);
    s.meshes.push_back(makeQuad("lamp", {-a / 2, h, -a / 2}, {a, 0, 0}, {0, 0, a}, 1));
    s.finalize();
    EmbreeScene rt(s);
    LightSampler lights(s);
    DirectLight dl(rt, lights);
    SurfaceHit hit = floorHit(0, 0);
    const HitSide side = hitSide(hit, {0, -1, 0});
    const int n = 40000;
    double sum = 0, sum2 = 0;
    Rng rng = Rng::forKey(2, 0, 0, StreamPurpose::Test);
    for (int k = 0; k < n; ++k) {
        double e = dl.diffuse(hit, side, kVacuum, rng, false).g;
        sum += e, sum2 += e * e;
    }
    double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    double X = a / (2 * h), q = X / std::sqrt(1 + X * X);
    double expected = 4 * Le * q * std::atan(q);
    std::printf("area light: NEE %.5f +- %.5f, form factor %.5f (point-light limit Le a^2/h^2 = %.5f)\n", mean, se,
                expected, Le * a * a / (h * h));
    EXPECT_LT(se, 0.005 * expected) << "too noisy to test";
    EXPECT_NEAR(mean, expected, 4 * se);
}

TEST(DirectLight, AlphaMaskedOccluderCastsItsOpaqueHalfOnly) {
    const Vec3 light{0, 2, 0};
    Scene s = floorScene(false, {pointLight(light, 1.0f)});
    s.textures = std::make_shared<TextureStore>();
    std::vector<float> px;  // alpha 0 for u < 0.5 (x < 0), 1 beyond
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) px.insert(px.end(), {1.0f, 1.0f, 1.0f, x < 4 ? 0.0f : 1.0f});
    Material leaf;
    leaf.name = "leaf";
    leaf.alphaMode = AlphaMode::Mask;
    leaf.baseColorTexture.texture = s.textures->addPixels(8, 8, 4, px, TextureEncoding::Linear,
                                                          TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, "alpha");
    s.materials.push_back(leaf);
    // u along +x over x in [-1, 1] at y = 1 (v along z).
    s.meshes.push_back(makeQuad("leaf", {-1, 1, -1}, {2, 0, 0}, {0, 0, 2}, 1));
    s.finalize();
    for (float x : {-0.8f, -0.4f}) {  // shadow rays cross the leaf at x / 2 < 0: cut out, lit
        float d = std::sqrt(x * x + 4.0f + 0.09f);  // to the light from (x, 0, 0.3); cos = 2 / d
        EXPECT_NEAR(directAt(s, x, 0.3f), 2.0f / (d * d * d), 1e-4f) << x;
        EXPECT_GT(directAt(s, x, 0.3f), 0.05f);
    }
    for (float x : {0.4f, 0.8f}) EXPECT_EQ(directAt(s, x, 0.3f), 0.0f) << x;  // opaque half: shadowed
}

TEST(DirectLight, OccludedQueryGivesTheClosestHitLoopsTransmittanceBitForBit) {
    // Where every surface blocks (no Interface, no alpha), shadowTransmittance asks one occluded
    // query; with an Interface quad anywhere in the scene it walks closest hits. A quad where no
    // shadow ray below goes makes the second scene take the loop: every answer, lit or blocked by
    // the box, in fog and in vacuum, must be the same bits.
    for (bool fog : {true, false}) {
        Scene opaque = floorScene(fog, {pointLight({0.3f, 2.5f, -0.2f}, 1.0f)});
        opaque.meshes.push_back(makeBox("blocker", {-0.6f, 0.8f, -0.5f}, {0.2f, 1.2f, 0.4f}, 0));
        Scene crossed = opaque;
        Material interface;
        interface.name = "interface";
        interface.type = MaterialType::Interface;
        crossed.materials.push_back(interface);
        crossed.meshes.push_back(makeQuad("portal", {4.2f, 2.5f, 4.2f}, {0.3f, 0, 0}, {0, 0, 0.3f}, 1));
        opaque.finalize();
        crossed.finalize();
        EmbreeScene fast(opaque), loop(crossed);
        ASSERT_TRUE(fast.everySurfaceBlocks());
        ASSERT_FALSE(loop.everySurfaceBlocks());
        Rng rng(21, 3);
        int lit = 0, blocked = 0;
        for (int i = 0; i < 400; ++i) {
            const Vec3 p{4.0f * rng.uniform() - 2.0f, 1e-3f, 4.0f * rng.uniform() - 2.0f};
            DirectLightSample ls;
            ls.point = i % 2 ? Vec3(0.3f, 2.5f, -0.2f) : Vec3(rng.uniform() - 0.5f, 2.0f + rng.uniform(), rng.uniform());
            ls.distance = length(ls.point - p);
            ls.wi = (ls.point - p) / ls.distance;
            ls.delta = true;
            ls.source = 0;
            Rng a(7, uint64_t(i)), b(7, uint64_t(i));
            const Rgb ta = shadowTransmittance(fast, p, ls, opaque.globalMedium, a);
            const Rgb tb = shadowTransmittance(loop, p, ls, crossed.globalMedium, b);
            ASSERT_EQ(std::memcmp(&ta, &tb, sizeof ta), 0) << i << ": " << ta.g << " vs " << tb.g;
            lit += ta.g > 0;
            blocked += ta.isBlack();
        }
        EXPECT_GT(lit, 100);
        EXPECT_GT(blocked, 20);
    }
}

TEST(DirectLight, NormalMappedHitUsesTheShadingCosine) {
    const Vec3 light{1.5f, 1.0f, 0.0f};
    Scene s = floorScene(false, {pointLight(light, 1.0f)});
    s.finalize();
    EmbreeScene rt(s);
    LightSampler lights(s);
    DirectLight dl(rt, lights);
    SurfaceHit hit = floorHit(0, 0);
    const float d = length(light);
    const Vec3 wi = light / d;
    for (Vec3 ns : {normalize(Vec3(0.5f, 1.0f, 0.0f)), normalize(Vec3(-0.5f, 1.0f, 0.0f)),
                    normalize(Vec3(-2.0f, 1.0f, 0.0f))}) {
        hit.ns = ns;
        Rng rng = Rng::forKey(3, 0, 0, StreamPurpose::Test);
        float e = dl.diffuse(hit, hitSide(hit, {0, -1, 0}), kVacuum, rng, false).g;
        float shading = std::max(0.0f, dot(wi, ns)), geometric = wi.y;
        EXPECT_NEAR(e, shading / (d * d), 1e-5f) << ns.x;
        EXPECT_GT(std::abs(shading - geometric), 0.1f * geometric);  // the two cosines differ here
        // The same factor as the photon gather's weight (shadingCosineRatio x the geometric cosine).
        EXPECT_NEAR(diffuseCosine(hitSide(hit, {0, -1, 0}), wi),
                    shadingCosineRatio(hitSide(hit, {0, -1, 0}), wi) * geometric, 1e-6f);
    }
}

// ---- 2. PPB with direct light where photons and shadow rays meet ----

/// Means of PPB (direct light on and off) and of the reference over the pixels whose primary ray
/// hits mesh `mesh`, with the PPB standard errors from independent batches of passes.
struct RegionMeans {
    double on = 0, off = 0, reference = 0, seOn = 0, seOff = 0, seReference = 0;
};

RegionMeans compareRegion(const Scene& scene, int size, int mesh, uint32_t photons, int batches, int passesPerBatch,
                          uint32_t referenceSpp) {
    std::vector<int> meshes = test::pixelMeshes(scene, size);
    RegionMeans r;
    auto ppb = [&](bool directLight, double* mean, double* se) {
        // Constant radii (a 1.5% surface kernel); the kernel's bias (photons missing beyond the
        // floor's edges) is within the tolerances below.
        const RenderSettings ps = test::constantRadiusSettings(size, photons, 77, directLight, 0.03f);
        const test::RegionEstimate e = test::ppbRegionMeans(scene, ps, batches, passesPerBatch, meshes, {mesh})[0];
        *mean = e.mean;
        *se = e.se;
    };
    ppb(true, &r.on, &r.seOn);
    ppb(false, &r.off, &r.seOff);
    if (referenceSpp > 0) {
        ReferenceSettings rs;
        rs.width = rs.height = size;
        rs.samplesPerPixel = referenceSpp;
        rs.seed = 99;
        EmbreeScene rt(scene);
        ReferenceImage ref = ReferenceTracer(rt, rs).render();
        r.reference = test::meanOverPixels(ref.mean, meshes, mesh);
        double var = 0;
        int n = 0;
        for (size_t i = 0; i < meshes.size(); ++i)
            if (meshes[i] == mesh) var += ref.varianceOfMean.pixels[i].g, ++n;
        r.seReference = n ? std::sqrt(var) / n : 0;  // pixels independent
    }
    std::printf("region of mesh %d: direct on %.5f +- %.5f, off %.5f +- %.5f, reference %.5f +- %.5f\n", mesh, r.on,
                r.seOn, r.off, r.seOff, r.reference, r.seReference);
    return r;
}

TEST(DirectLightPpb, FogAndWallsAgreeWithThePathTracer) {
    // A closed 2-unit box of albedo-0.5 walls full of fog (optical depth ~0.8 across) round a point
    // light: the walls' direct light comes from shadow rays, their indirect light and the fog from
    // photons. Counting the direct photons too adds ~50% to the walls; a shadow ray without
    // transmittance ~35%.
    const Scene s = test::makeFogBoxWithLamp(Rgb(0.3f), Rgb(0.1f), 0.0f, {0.3f, 0.7f, 0.2f}, 1.4f);
    RegionMeans r = compareRegion(s, 16, 0, 4000, 8, 4, 256);
    const double se = std::sqrt(r.seOn * r.seOn + r.seReference * r.seReference);
    EXPECT_LT(se, 0.02 * r.reference) << "too noisy to test";
    // 4 standard errors plus 3% for the indirect photons' kernel bias at the box's edges.
    EXPECT_NEAR(r.on / r.reference, 1.0, (4 * se) / r.reference + 0.03);
    EXPECT_NEAR(r.off / r.reference, 1.0, (4 * std::sqrt(r.seOff * r.seOff + r.seReference * r.seReference)) / r.reference + 0.04);
}

TEST(DirectLightPpb, LightSeenOnlyInAMirrorStillLightsTheFloor) {
    // An area light facing up under a mirror ceiling: the floor sees the light only in the mirror
    // (its shadow rays reach the light's back), so all its light comes from photons that met the
    // mirror; they must still be stored with direct light on.
    Scene s;
    s.name = "mirror-light";
    s.source = "<test>";
    Material white, mirror, lamp;
    white.name = "white";
    white.albedo = Rgb(0.6f);
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    mirror.albedo = Rgb(0.9f);
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.0f);
    lamp.emission = Rgb(4.0f);
    s.materials = {white, mirror, lamp};
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    s.meshes.push_back(makeQuad("mirror", {-1, 1.5f, -1}, {2, 0, 0}, {0, 0, 2}, 1));
    s.meshes.push_back(makeQuad("lamp", {-0.3f, 1.0f, 0.3f}, {0.6f, 0, 0}, {0, 0, -0.6f}, 2));  // faces up
    s.camera = Camera::lookAt({0, 0.9f, 2.2f}, {0, 0, -0.2f}, {0, 1, 0}, 0.9f);
    s.finalize();
    s.validate();
    RegionMeans r = compareRegion(s, 16, 0, 16000, 8, 4, 4096);
    const double se = std::sqrt(r.seOn * r.seOn + r.seReference * r.seReference);
    EXPECT_GT(r.reference, 0.01);
    // The path tracer finds this light only by hitting it after the mirror: its noise dominates.
    EXPECT_LT(se, 0.03 * r.reference) << "too noisy to test";
    EXPECT_NEAR(r.on / r.reference, 1.0, (4 * se) / r.reference + 0.03);
}

TEST(DirectLightPpb, PointLightHalfBehindGlassAgreesWithPhotonsOnly) {
    // A point light over a floor, a glass slab under half of it: the open half is lit by shadow
    // rays, the other half by the caustic of photons through the glass (which the path tracer
    // cannot render: the reference here is PPB with photons only). Regions: the floor seen by the
    // camera, whole.
    Scene s;
    s.name = "glass-half";
    s.source = "<test>";
    Material white, glass;
    white.name = "white";
    white.albedo = Rgb(0.6f);
    glass.name = "glass";
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.5f;
    glass.albedo = Rgb(1.0f);
    s.materials = {white, glass};
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    s.meshes.push_back(makeBox("slab", {0.0f, 0.5f, -1.0f}, {1.0f, 0.7f, 1.0f}, 1));
    s.lights.push_back(pointLight({0.0f, 1.2f, 0.0f}, 1.0f));
    s.camera = Camera::lookAt({0, 1.8f, 1.6f}, {0, 0, -0.1f}, {0, 1, 0}, 1.0f);
    s.finalize();
    s.validate();
    RegionMeans r = compareRegion(s, 16, 0, 40000, 8, 4, 0);
    const double se = std::sqrt(r.seOn * r.seOn + r.seOff * r.seOff);
    EXPECT_LT(se, 0.03 * r.off) << "too noisy to test";  // the caustic's photons dominate
    EXPECT_NEAR(r.on / r.off, 1.0, (4 * se) / r.off + 0.02);
}

TEST(DirectLightPpb, TwoColouredLightsAgreeWithThePathTracerAndTheirChoiceConvergesFasterThanOneOverPasses) {
    // A white floor under an orange and a blue point light, both lighting every pixel: each shadow
    // ray goes to one of them, chosen by what it sends into the pixel's colour and cosine, with
    // the pixel's light-choice sequence over the passes (core/pixel_jitter.h). The floor's mean
    // agrees with the path tracer (4 standard errors + 1%: the photons' kernel carries only the
    // little light the marker quad sends back). With the path length capped at 2 nothing but the
    // shadow rays and the film jitter (both low-discrepancy over the passes) is left, so a pixel's
    // variance over seeds falls faster than 1/passes: with the choice drawn independently per pass
    // the slope is about -1 (measured -1.08), here below -1.25 (measured -1.42).
    Light orange = test::pointLight({-0.8f, 0.9f, 0.0f}, 1.0f), blue = test::pointLight({1.2f, 1.5f, 0.8f}, 1.0f);
    orange.intensity = Rgb(3.0f, 2.2f, 1.2f);
    blue.intensity = Rgb(1.2f, 1.4f, 4.0f);
    Scene s = floorScene(false, {orange, blue});
    s.camera = Camera::lookAt({0, 3, 2}, {0, 0, 0}, {0, 1, 0}, 0.8f);
    s.finalize();
    s.validate();
    RegionMeans r = compareRegion(s, 16, 0, 4000, 8, 4, 256);
    const double se = std::sqrt(r.seOn * r.seOn + r.seReference * r.seReference);
    EXPECT_LT(se, 0.01 * r.reference) << "too noisy to test";
    EXPECT_NEAR(r.on / r.reference, 1.0, (4 * se) / r.reference + 0.01);

    RenderSettings ps;
    ps.width = ps.height = 8;
    ps.photonsPerPass = 16;
    ps.maxPathLength = 2;
    ps.radius = 0.03f;
    ps.surfaceRadius = 0.06f;
    ps.radiusOffset = 1000000000000ull;
    ps.photonAngle = 0;
    EXPECT_LT(test::varianceSlopeOverPasses(s, ps, 48, 300), -1.25);
}

}  // namespace
}  // namespace tyndall
