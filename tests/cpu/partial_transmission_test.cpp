// KHR_materials_transmission with transmissionTexture / a factor below 1: a pane that is, per
// vertex, the dielectric with probability t and the diffuse base otherwise. Lit from above by a
// directional light with nothing behind it, the pane's radiance is (1 - t) rho/pi E cos(theta):
// the diffuse share, the glass share seeing only black. Checked in PPB and in the reference path
// tracer where the texture's R is 0 (all diffuse), 1 (all glass) and with a uniform factor 0.5.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr float kPaneTheta = 30.0f * kPi / 180.0f;
constexpr float kPaneAlbedo = 0.7f;
constexpr float kPaneIrradiance = 2.0f;
constexpr int kPaneImageSize = 32;

/// Pane [-1, 1]^2 at y = 0 facing +y. `textured`: transmissionTexture 16 x 1, R = 0 on the left
/// half (x < 0), 1 on the right; else a uniform transmission `factor`.
Scene paneScene(bool textured, float factor) {
    Scene s;
    s.name = "pane";
    s.source = "<test>";
    Material pane;
    pane.name = "pane";
    pane.type = MaterialType::Dielectric;
    pane.albedo = Rgb(kPaneAlbedo);
    pane.transmission = factor;
    if (textured) {
        s.textures = std::make_shared<TextureStore>();
        std::vector<float> px;
        for (int x = 0; x < 16; ++x) px.push_back(x < 8 ? 0.0f : 1.0f);
        pane.transmissionTexture.texture = s.textures->addPixels(16, 1, 1, px, TextureEncoding::Linear,
                                                                 TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, "t");
    }
    s.materials = {pane};
    s.meshes.push_back(makeQuad("pane", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = Vec3(std::sin(kPaneTheta), -std::cos(kPaneTheta), 0.0f);
    sun.intensity = Rgb(kPaneIrradiance);
    s.lights.push_back(sun);
    s.camera = Camera::lookAt({0, 3.0f, 0.001f}, {0, 0, 0}, {0, 0, -1}, 45.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// Mean green of the pixels whose centre ray hits the pane with x in [x0, x1] (away from the
/// pane's edges in z too, where PPB's kernel loses half its support).
double regionMean(const Scene& s, const Image& img, float x0, float x1) {
    EmbreeScene rt(s);
    double sum = 0;
    int n = 0;
    for (int y = 0; y < kPaneImageSize; ++y)
        for (int x = 0; x < kPaneImageSize; ++x) {
            SurfaceHit hit;
            Ray r = s.camera.generateRay(x + 0.5f, y + 0.5f, kPaneImageSize, kPaneImageSize, {0.5f, 0.5f});
            if (rt.intersect(r, &hit) && hit.p.x >= x0 && hit.p.x <= x1 && std::abs(hit.p.z) < 0.85f) {
                sum += img.at(x, y).g;
                ++n;
            }
        }
    EXPECT_GT(n, 40);
    return sum / std::max(n, 1);
}

struct Renders {
    Image ref, ppb;
};
Renders render(const Scene& s) {
    ReferenceSettings rs;
    rs.width = rs.height = kPaneImageSize;
    rs.samplesPerPixel = 64;
    rs.seed = 11;
    EmbreeScene rt(s);
    Renders out;
    out.ref = ReferenceTracer(rt, rs).render().mean;
    RenderSettings ps;
    ps.width = ps.height = kPaneImageSize;
    ps.photonsPerPass = 40000;
    ps.seed = 12;
    // The default radii: with their surface radius capped at 2% of the scene's diagonal they
    // lose no light at the edges of the regions compared at this size.
    PassRenderer renderer(s, ps);
    out.ppb = test::renderPpbPasses(renderer, 0, 16);
    return out;
}

TEST(PartialTransmission, TheTextureChoosesBetweenTheDiffuseBaseAndTheGlass) {
    Scene s = paneScene(true, 1.0f);
    Renders r = render(s);
    const double diffuse = kPaneAlbedo / kPi * kPaneIrradiance * std::cos(kPaneTheta);
    double refL = regionMean(s, r.ref, -0.85f, -0.3f), refR = regionMean(s, r.ref, 0.3f, 0.85f);
    double ppbL = regionMean(s, r.ppb, -0.85f, -0.3f), ppbR = regionMean(s, r.ppb, 0.3f, 0.85f);
    std::printf("R = 0: reference %.4f PPB %.4f (expected %.4f); R = 1: reference %.4f PPB %.4f (expected 0)\n", refL,
                ppbL, diffuse, refR, ppbR);
    // Where R = 0 every vertex takes the diffuse base; where R = 1 the glass, which sees black.
    EXPECT_NEAR(refL / diffuse, 1.0, 0.02);
    EXPECT_NEAR(ppbL / diffuse, 1.0, 0.04);
    EXPECT_LT(refR, 1e-3 * diffuse);
    EXPECT_LT(ppbR, 1e-3 * diffuse);
}

TEST(PartialTransmission, AFactorOfOneHalfIsHalfDiffuse) {
    Scene s = paneScene(false, 0.5f);
    Renders r = render(s);
    const double half = 0.5 * kPaneAlbedo / kPi * kPaneIrradiance * std::cos(kPaneTheta);
    double ref = regionMean(s, r.ref, -0.85f, 0.85f), ppb = regionMean(s, r.ppb, -0.85f, 0.85f);
    std::printf("t = 0.5: reference %.4f PPB %.4f (expected %.4f)\n", ref, ppb, half);
    EXPECT_NEAR(ref / half, 1.0, 0.03);
    EXPECT_NEAR(ppb / half, 1.0, 0.04);
}

}  // namespace
}  // namespace tyndall
