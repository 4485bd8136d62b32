// Coated (plastic) vertices (docs/algorithm.md "Coated (plastic) vertices"): a rough plastic floor
// in fog under a spot light, seen where the spot's highlight is, with a diffuse wall behind that the
// floor lights. PPB (diffuse part from every stored photon, specular part from the delta-path
// photons plus the continuation through the specular lobe) against the reference path tracer
// (next-event estimation with the full BSDF, MIS with the mixture pdf): the highlight, the floor
// away from it and the wall agree. A smooth coat is checked the same way under a small area light.
// Planted bugs this catches: the specular part gathering every
// photon (the fog's light counted twice in the highlight), the diffuse part gathering only
// delta-path ones, photons not scattering off the coat's diffuse part (the wall too dark).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr int kSize = 32;
const Vec3 kHighlight{0.42f, 0.0f, 0.0f};   // where the spot's mirror image is seen on the floor
const Vec3 kWallSpot{-2.0f, 0.9f, 0.0f};     // where the second spot lights the wall
const Vec3 kReflection{-0.34f, 0.0f, 0.0f};  // where the floor reflects kWallSpot toward the camera

/// `areaLight`: a small lamp quad at the spot's place instead of the spot (a smooth coat's mirror
/// image of a point light is a caustic the path tracer cannot find: PPB, with photons, was 2% above
/// it on the wall and floor when this scene used the spot with a smooth coat).
Scene plasticFloorScene(float roughness, bool areaLight) {
    Scene s;
    s.name = "plastic-floor";
    s.source = "<test>";
    Material floor;
    floor.name = "plastic";
    floor.type = MaterialType::Plastic;
    floor.albedo = Rgb(0.25f, 0.15f, 0.1f);  // dark: the specular reflection is much of what is seen
    floor.roughness = roughness;
    Material wall;
    wall.name = "wall";
    wall.albedo = Rgb(0.6f);
    Material lamp;
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.0f);
    lamp.emission = Rgb(30.0f);
    s.materials = {floor, wall, lamp};
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.12f);
    fog.sigmaA = Rgb(0.02f);
    fog.g = 0.2f;
    s.media.push_back(fog);
    s.globalMedium = 0;
    s.meshes.push_back(makeQuad("floor", {-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 0));
    s.meshes.push_back(makeQuad("wall", {-2, 0, 2}, {0, 0, -4}, {0, 2.5f, 0}, 1));  // x = -2, facing +x
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-1.2f, 1.5f, 0.0f};
    spot.direction = normalize(kHighlight - spot.position);
    spot.cosOuterAngle = std::cos(25.0f * kPi / 180.0f);
    spot.cosInnerAngle = std::cos(18.0f * kPi / 180.0f);
    spot.intensity = Rgb(8.0f);
    // A second spot lights the wall where the floor's specular lobe shows it to the camera: light
    // the floor reflects that the continuation finds (through the wall's photons), not the
    // delta-path photons.
    Light wallSpot = spot;
    wallSpot.name = "wall spot";
    wallSpot.position = {0.3f, 2.2f, 0.0f};
    wallSpot.direction = normalize(kWallSpot - wallSpot.position);
    wallSpot.cosOuterAngle = std::cos(15.0f * kPi / 180.0f);
    wallSpot.cosInnerAngle = std::cos(10.0f * kPi / 180.0f);
    wallSpot.intensity = Rgb(12.0f);
    if (areaLight)  // 0.3 x 0.3, facing down
        s.meshes.push_back(makeQuad("lamp", {-1.35f, 1.5f, -0.15f}, {0.3f, 0, 0}, {0, 0, 0.3f}, 2));
    else
        s.lights = {spot, wallSpot};
    // The spot's mirror image (-1.2, -1.5, 0) seen from the camera crosses the floor at kHighlight.
    s.camera = Camera::lookAt({1.5f, 1.0f, 0.0f}, {-0.2f, 0.0f, 0.0f}, {0, 1, 0}, 60.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

struct Regions {
    double highlight = 0, reflection = 0, floor = 0, wall = 0, all = 0;
};

/// Mean green over the pixels whose centre ray hits the floor within 0.3 of kHighlight, within 0.3
/// of kReflection, the rest of the floor (further than 0.6 and 0.5 from them), the wall; and over
/// the whole image.
Regions regions(const Scene& s, const Image& img) {
    EmbreeScene rt(s);
    Regions sum, count;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            double v = img.at(x, y).g;
            sum.all += v;
            count.all += 1;
            SurfaceHit hit;
            Ray r = s.camera.generateRay(x + 0.5f, y + 0.5f, kSize, kSize, {0.5f, 0.5f});
            if (!rt.intersect(r, &hit)) continue;
            float d = length(hit.p - kHighlight), e = length(hit.p - kReflection);
            if (hit.mesh == 1) {
                sum.wall += v, count.wall += 1;
            } else if (d < 0.3f) {
                sum.highlight += v, count.highlight += 1;
            } else if (e < 0.3f) {
                sum.reflection += v, count.reflection += 1;
            } else if (d > 0.6f && e > 0.5f) {
                sum.floor += v, count.floor += 1;
            }
        }
    EXPECT_GT(count.highlight, 8);
    EXPECT_GT(count.wall, 40);
    EXPECT_GT(count.reflection, 8);
    EXPECT_GT(count.floor, 60);
    return {sum.highlight / count.highlight, sum.reflection / count.reflection, sum.floor / count.floor,
            sum.wall / count.wall, sum.all / count.all};
}

TEST(CoatedRender, PlasticFloorInFogAgreesWithThePathTracer) {
    for (float roughness : {0.3f, 0.0f}) {
        SCOPED_TRACE("roughness " + std::to_string(roughness));
        Scene s = plasticFloorScene(roughness, /*areaLight=*/roughness == 0.0f);
        EmbreeScene rt(s);
        ReferenceSettings rs;
        rs.width = rs.height = kSize;
        rs.samplesPerPixel = 128;
        rs.seed = 21;
        Image ref = ReferenceTracer(rt, rs).render().mean;
        RenderSettings ps;
        ps.width = ps.height = kSize;
        ps.photonsPerPass = 10000;
        ps.seed = 22;
        ps = withSceneRelativeRadii(ps, s);
        PassRenderer renderer(s, ps);
        Image ppb = test::renderPpbPasses(renderer, 0, 16);
        Regions r = regions(s, ref), p = regions(s, ppb);
        std::printf("roughness %.1f: highlight PPB %.4f ref %.4f (%.3f); reflection %.4f %.4f (%.3f); floor %.4f "
                    "%.4f (%.3f); wall %.4f %.4f (%.3f); image %.4f %.4f (%.3f)\n",
                    roughness, p.highlight, r.highlight, p.highlight / r.highlight, p.reflection, r.reflection,
                    p.reflection / r.reflection, p.floor, r.floor,
                    p.floor / r.floor, p.wall, r.wall, p.wall / r.wall, p.all, r.all, p.all / r.all);
        test::writeEvidence("coated_floor_ppb_" + std::to_string(int(roughness * 10)), ppb);
        test::writeEvidence("coated_floor_ref_" + std::to_string(int(roughness * 10)), ref);
        // With the smooth coat the "highlight" is the lamp's mirror image, a few pixels of emission
        // that 16 jittered paths per pixel (continuing with probability F ~ 0.1) sample too coarsely
        // to compare: PPB 1.17 of the reference there, the image mean 1.01.
        if (roughness > 0) {
            EXPECT_NEAR(p.highlight / r.highlight, 1.0, 0.06);
        }
        // The wall spot's reflection: 1.006 here (rough; 1.127 when the specular part gathers every
        // photon); other seeds gave 1.03, 1.04, 1.00 (rough) and 1.08, 1.06, 1.01 (smooth: its delta
        // reflection is what a few of the 16 paths per pixel continue to).
        EXPECT_NEAR(p.reflection / r.reflection, 1.0, roughness > 0 ? 0.07 : 0.12);
        EXPECT_NEAR(p.floor / r.floor, 1.0, 0.06);
        EXPECT_NEAR(p.wall / r.wall, 1.0, 0.06);
        EXPECT_NEAR(p.all / r.all, 1.0, 0.04);
    }
}

}  // namespace
}  // namespace tyndall
