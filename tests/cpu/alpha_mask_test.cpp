// alphaMode MASK and BLEND through Embree's intersection filter: camera rays (intersect), photons
// (intersectRaw) and shadow rays (occluded) pass through the cut-out half of a textured quad and
// stop at the opaque half; BLEND lets a fraction 1 - alpha through.
#include <gtest/gtest.h>

#include "core/material_eval.h"
#include "cpu/embree_scene.h"
#include "loading/mesh_builders.h"

namespace tyndall {
namespace {

/// A unit quad in z = 0 (u along x, v along y) whose alpha texture is 0 for u < 0.5, 1 beyond,
/// and a backstop quad at z = -1.
Scene maskScene(AlphaMode mode, float factorAlpha = 1.0f) {
    Scene s;
    s.name = "alpha";
    s.source = "<test>";
    s.textures = std::make_shared<TextureStore>();
    std::vector<float> px;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) px.insert(px.end(), {1.0f, 1.0f, 1.0f, x < 4 ? 0.0f : 1.0f});
    Material leaf;
    leaf.name = "leaf";
    leaf.alphaMode = mode;
    leaf.alpha = factorAlpha;
    leaf.baseColorTexture.texture = s.textures->addPixels(8, 8, 4, px, TextureEncoding::Linear, TextureWrap::ClampToEdge,
                                                          TextureWrap::ClampToEdge, "alpha");
    Material wall;
    wall.name = "wall";
    s.materials = {leaf, wall};
    s.meshes.push_back(makeQuad("leaf", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0));
    s.meshes.push_back(makeQuad("backstop", {-1, -1, -1}, {3, 0, 0}, {0, 3, 0}, 1));
    Light l;
    l.name = "l";
    l.position = {0, 0, 5};
    s.lights.push_back(l);
    s.finalize();
    s.validate();
    return s;
}

TEST(AlphaMask, CameraPhotonAndShadowRaysPassTheCutOut) {
    Scene s = maskScene(AlphaMode::Mask);
    EmbreeScene rt(s);
    for (float x : {0.1f, 0.3f, 0.45f}) {  // cut out: every query reaches the backstop
        Ray r{{x, 0.5f, 2.0f}, {0, 0, -1}};
        SurfaceHit hit;
        ASSERT_TRUE(rt.intersect(r, &hit));
        EXPECT_EQ(hit.mesh, 1) << x;
        RTCRayHit rh;
        initRayHit(rh, r.o, r.d);
        ASSERT_TRUE(rt.intersectRaw(rh));
        EXPECT_EQ(rh.hit.geomID, 1u) << x;
        EXPECT_FALSE(rt.occluded(Ray{r.o, r.d, 0.0f, 2.5f})) << x;  // stops before the backstop
    }
    for (float x : {0.55f, 0.7f, 0.9f}) {  // opaque
        Ray r{{x, 0.5f, 2.0f}, {0, 0, -1}};
        SurfaceHit hit;
        ASSERT_TRUE(rt.intersect(r, &hit));
        EXPECT_EQ(hit.mesh, 0) << x;
        EXPECT_TRUE(rt.occluded(Ray{r.o, r.d, 0.0f, 2.5f})) << x;
    }
}

TEST(AlphaMask, OpaqueModeIgnoresAlpha) {
    Scene s = maskScene(AlphaMode::Opaque);
    EmbreeScene rt(s);
    SurfaceHit hit;
    ASSERT_TRUE(rt.intersect(Ray{{0.2f, 0.5f, 2.0f}, {0, 0, -1}}, &hit));
    EXPECT_EQ(hit.mesh, 0);
}

TEST(AlphaBlend, AFractionOneMinusAlphaGetsThrough) {
    Scene s = maskScene(AlphaMode::Blend, 0.3f);  // opaque half: alpha 0.3
    EmbreeScene rt(s);
    int through = 0;
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        // Tilted left by up to 0.06 over the 2 units to the quad: every ray lands on u in [0.59, 0.95].
        float x = 0.65f + 0.3f * (k % 200) / 200.0f, y = 0.05f + 0.9f * (k / 200) / 100.0f;
        SurfaceHit hit;
        ASSERT_TRUE(rt.intersect(Ray{{x, y, 2.0f}, normalize(Vec3(-0.005f * (k % 7), 0.0f, -1.0f))}, &hit));
        through += hit.mesh == 1;
    }
    double p = double(through) / n, sigma = std::sqrt(0.7 * 0.3 / n);
    EXPECT_NEAR(p, 0.7, 5 * sigma);
}

}  // namespace
}  // namespace tyndall
