// Normal maps in rendering: a floor whose normal map tilts the left half toward a directional
// light and the right half away is brighter on the left by cos(theta - a) / cos(theta + a), in PPB
// (surface photons weighted by the light-side cosine ratio) and in the reference path tracer; a
// flat map renders bit-identically to no map; and light reflected off a normal-mapped floor onto a
// wall agrees between PPB and the path tracer (Veach's adjoint factor on photon paths).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr float kLightTheta = 40.0f * kPi / 180.0f;  // light's angle from the floor's normal
constexpr float kTilt = 20.0f * kPi / 180.0f;   // normal map tilt
constexpr float kFloorAlbedo = 0.8f;
constexpr float kLightIrradiance = 3.0f;  // W/m^2 perpendicular to the light

enum class Map { None, Flat, Split, TowardLight };

/// Floor [-1, 1]^2 at y = 0 facing +y (u along +x, so the map's +x is world +x); a directional
/// light travelling along (sin theta, -cos theta, 0), i.e. coming from -x. `wall`: a back wall in
/// z = -1 facing +z, parallel to the light (no direct light: only what the floor reflects).
Scene floorScene(Map map, bool wall) {
    Scene s;
    s.name = "normal-mapped floor";
    s.source = "<test>";
    Material floor;
    floor.name = "floor";
    floor.albedo = Rgb(kFloorAlbedo);
    if (map != Map::None) {
        s.textures = std::make_shared<TextureStore>();
        // 16 x 1 texels: left 8 tilted toward -x (the light) by kTilt, right 8 toward +x.
        auto texel = [](float tx) { return std::array<float, 3>{0.5f + 0.5f * tx, 0.5f, 0.5f + 0.5f * std::cos(kTilt)}; };
        std::vector<float> px;
        for (int x = 0; x < 16; ++x) {
            std::array<float, 3> t = map == Map::Flat          ? std::array<float, 3>{0.5f, 0.5f, 1.0f}
                                     : map == Map::TowardLight ? texel(-std::sin(kTilt))
                                                               : texel(x < 8 ? -std::sin(kTilt) : std::sin(kTilt));
            px.insert(px.end(), t.begin(), t.end());
        }
        floor.normalTexture.texture = s.textures->addPixels(16, 1, 3, px, TextureEncoding::Linear,
                                                            TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, "normals");
    }
    Material white;
    white.name = "white";
    white.albedo = Rgb(kFloorAlbedo);
    s.materials = {floor, white};
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    if (wall) s.meshes.push_back(makeQuad("wall", {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, 1));
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = Vec3(std::sin(kLightTheta), -std::cos(kLightTheta), 0.0f);
    sun.intensity = Rgb(kLightIrradiance);
    s.lights.push_back(sun);
    s.camera = wall ? Camera::lookAt({0, 1.0f, 3.2f}, {0, 0.7f, 0}, {0, 1, 0}, 50.0f * kPi / 180.0f)
                    : Camera::lookAt({0, 3.0f, 0.001f}, {0, 0, 0}, {0, 0, -1}, 45.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

constexpr int kImageSize = 32;

/// Pixels whose centre ray hits `mesh` with world x in [x0, x1], away from the floor's front and
/// back edges (where jittered samples fall off it and PPB's kernel loses half its support).
std::vector<int> pixelsOn(const Scene& s, int mesh, float x0, float x1) {
    EmbreeScene rt(s);
    std::vector<int> out;
    for (int y = 0; y < kImageSize; ++y)
        for (int x = 0; x < kImageSize; ++x) {
            SurfaceHit hit;
            Ray r = s.camera.generateRay(x + 0.5f, y + 0.5f, kImageSize, kImageSize, {0.5f, 0.5f});
            if (rt.intersect(r, &hit) && hit.mesh == mesh && hit.p.x >= x0 && hit.p.x <= x1 &&
                (mesh != 0 || std::abs(hit.p.z) < 0.85f))
                out.push_back(y * kImageSize + x);
        }
    return out;
}

double mean(const Image& img, const std::vector<int>& px) {
    double sum = 0;
    for (int i : px) sum += img.pixels[size_t(i)].g;
    return sum / double(px.size());
}

ReferenceImage reference(const Scene& s, uint32_t spp) {
    ReferenceSettings rs;
    rs.width = rs.height = kImageSize;
    rs.samplesPerPixel = spp;
    rs.seed = 7;
    EmbreeScene rt(s);
    return ReferenceTracer(rt, rs).render();
}

Image ppb(const Scene& s, uint64_t passes, uint32_t photons) {
    RenderSettings ps;
    ps.width = ps.height = kImageSize;
    ps.photonsPerPass = photons;
    ps.seed = 3;
    // The default radii: with their surface radius capped at 2% of the scene's diagonal they
    // lose no light at the edges of the regions compared at this size.
    PassRenderer renderer(s, ps);
    return test::renderPpbPasses(renderer, 0, passes);
}

TEST(NormalMapRender, TheSideTiltedTowardTheLightIsBrighterByTheCosineRatio) {
    Scene s = floorScene(Map::Split, false);
    const std::vector<int> lit = pixelsOn(s, 0, -0.85f, -0.3f), unlit = pixelsOn(s, 0, 0.3f, 0.85f);
    ASSERT_GT(lit.size(), 50u);
    ASSERT_GT(unlit.size(), 50u);
    const double expectLit = kFloorAlbedo / kPi * kLightIrradiance * std::cos(kLightTheta - kTilt);
    const double expectUnlit = kFloorAlbedo / kPi * kLightIrradiance * std::cos(kLightTheta + kTilt);
    const double ratio = std::cos(kLightTheta - kTilt) / std::cos(kLightTheta + kTilt);  // 1.88

    Image ref = reference(s, 16).mean;
    std::printf("reference: lit %.4f (expected %.4f), unlit %.4f (expected %.4f)\n", mean(ref, lit), expectLit,
                mean(ref, unlit), expectUnlit);
    EXPECT_NEAR(mean(ref, lit) / expectLit, 1.0, 0.005);
    EXPECT_NEAR(mean(ref, unlit) / expectUnlit, 1.0, 0.005);
    EXPECT_NEAR(mean(ref, lit) / mean(ref, unlit) / ratio, 1.0, 0.01);

    Image img = ppb(s, 16, 40000);
    std::printf("PPB: lit %.4f, unlit %.4f, ratio %.4f (expected %.4f)\n", mean(img, lit), mean(img, unlit),
                mean(img, lit) / mean(img, unlit), ratio);
    // Kernel blur at the floor's edges is kept out by the regions; the rest is photon noise (~1%).
    EXPECT_NEAR(mean(img, lit) / expectLit, 1.0, 0.04);
    EXPECT_NEAR(mean(img, unlit) / expectUnlit, 1.0, 0.04);
    EXPECT_NEAR(mean(img, lit) / mean(img, unlit) / ratio, 1.0, 0.05);
    if (::testing::Test::HasFailure()) {
        test::writeEvidence("normal_map_split_ppb", img);
        test::writeEvidence("normal_map_split_reference", ref);
    }
}

TEST(NormalMapRender, AFlatMapRendersExactlyAsNoMap) {
    for (bool wall : {false, true}) {
        Scene none = floorScene(Map::None, wall), flat = floorScene(Map::Flat, wall);
        Image a = ppb(none, 2, 3000), b = ppb(flat, 2, 3000);
        Image ra = reference(none, 2).mean, rb = reference(flat, 2).mean;
        size_t differ = 0, refDiffer = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) {
                differ += a.pixels[i][c] != b.pixels[i][c];
                refDiffer += ra.pixels[i][c] != rb.pixels[i][c];
            }
        EXPECT_EQ(differ, 0u) << "PPB, wall " << wall;
        EXPECT_EQ(refDiffer, 0u) << "reference, wall " << wall;
        EXPECT_GT(mean(a, pixelsOn(none, 0, -1, 1)), 0.1);  // not two black images
    }
}

TEST(NormalMapRender, LightReflectedOffANormalMappedFloorAgreesWithThePathTracer) {
    // The wall sees only light the floor reflects. Photons bouncing off the floor carry the
    // adjoint factor cos(theta - a) / cos(theta) = 1.23 here; without it PPB's wall is 19% dark.
    Scene s = floorScene(Map::TowardLight, true);
    const std::vector<int> wall = pixelsOn(s, 1, -0.8f, 0.8f), floor = pixelsOn(s, 0, -0.8f, 0.8f);
    ASSERT_GT(wall.size(), 100u);
    ASSERT_GT(floor.size(), 50u);
    ReferenceImage ref = reference(s, 256);
    Image img = ppb(s, 16, 20000);
    const double w = mean(img, wall) / mean(ref.mean, wall), f = mean(img, floor) / mean(ref.mean, floor);
    std::printf("PPB / reference: wall %.4f (%.4f vs %.4f), floor %.4f\n", w, mean(img, wall), mean(ref.mean, wall), f);
    EXPECT_NEAR(w, 1.0, 0.05);
    EXPECT_NEAR(f, 1.0, 0.04);
    if (::testing::Test::HasFailure()) {
        test::writeEvidence("normal_map_wall_ppb", img);
        test::writeEvidence("normal_map_wall_reference", ref.mean);
    }
}

}  // namespace
}  // namespace tyndall
