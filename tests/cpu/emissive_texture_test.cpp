// An emissive texture, rendered: the emitted-radiance lookup is shared by PPB's camera paths, the
// reference path tracer and the light sampler, so here it is held to closed forms instead:
//   - the camera side: a textured emitter filling the view, each block of the texture seen at its
//     own radiance (emission x the sRGB-decoded texel, decoded here);
//   - the photon side: the mean emitted photon power is pi x area x the emission times the texture's
//     mean over the quad (bilinear with clamped edges averages to the mean of the texels).
#include <gtest/gtest.h>

#include <cmath>

#include "core/light_sampler.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

const Rgb kEmission(2.0f, 1.5f, 3.0f);
// 2 x 2 blocks of sRGB-encoded colours (top row first), each block 2 x 2 texels of a 4 x 4 image.
const float kBlocks[4][3] = {{0.9f, 0.2f, 0.1f}, {0.1f, 0.8f, 0.3f}, {0.2f, 0.3f, 1.0f}, {0.6f, 0.6f, 0.05f}};

double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

/// The unit quad at z = 0 facing +z (u along x, v along y: the image's top row at y = 0), emitting
/// kEmission x the texture; a narrow camera on +z sees nothing else.
Scene texturedEmitter() {
    Scene s;
    s.name = "textured-emitter";
    s.source = "<test>";
    s.textures = std::make_shared<TextureStore>();
    std::vector<float> px;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const float* c = kBlocks[(y / 2) * 2 + x / 2];
            px.insert(px.end(), {c[0], c[1], c[2]});
        }
    Material lamp;
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.0f);
    lamp.emission = kEmission;
    lamp.emissiveTexture.texture = s.textures->addPixels(4, 4, 3, px, TextureEncoding::Srgb, TextureWrap::ClampToEdge,
                                                         TextureWrap::ClampToEdge, "blocks");
    s.materials = {lamp};
    s.meshes.push_back(makeQuad("lamp", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0));
    s.camera = Camera::lookAt({0.5f, 0.5f, 5}, {0.5f, 0.5f, 0}, {0, 1, 0}, 2 * std::atan(0.45f / 5));
    s.finalize();
    s.validate();
    return s;
}

Rgb blockRadiance(int block) {
    Rgb r;
    for (int c = 0; c < 3; ++c) r[c] = kEmission[c] * float(srgbDecode(kBlocks[block][c]));
    return r;
}

TEST(EmissiveTexture, TheCameraSeesEachTexelsRadiance) {
    Scene s = texturedEmitter();
    RenderSettings ps;
    ps.width = ps.height = 16;
    ps.photonsPerPass = 500;
    ps.seed = 4;
    PassRenderer renderer(s, ps);
    Image img = test::renderPpbPasses(renderer, 0, 4);
    EmbreeScene rt(s);
    int checked = 0;
    for (int py = 0; py < 16; ++py)
        for (int px = 0; px < 16; ++px) {
            SurfaceHit hit;
            ASSERT_TRUE(rt.intersect(s.camera.generateRay(px + 0.5f, py + 0.5f, 16, 16, {0.5f, 0.5f}), &hit));
            // Inside a block, away from its edges by more than a texel centre plus half a pixel
            // (bilinear filtering between equal texels gives the block's colour exactly).
            const float u = hit.p.x, v = hit.p.y;
            auto inner = [](float t) { return std::abs(t - 0.25f) < 0.09f || std::abs(t - 0.75f) < 0.09f; };
            if (!inner(u) || !inner(v)) continue;
            const Rgb expected = blockRadiance((v < 0.5f ? 0 : 2) + (u < 0.5f ? 0 : 1));
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(img.at(px, py)[c], expected[c], 4e-3 * expected[c] + 1e-4)
                    << "pixel " << px << "," << py << " channel " << c;
            ++checked;
        }
    EXPECT_GE(checked, 16);
}

TEST(EmissiveTexture, PhotonPowerIsTheTexturedEmissionIntegrated) {
    Scene s = texturedEmitter();
    LightSampler sampler(s);
    Rgb mean(0.0f);
    for (int b = 0; b < 4; ++b) mean += blockRadiance(b) * 0.25f;
    const Rgb expected = mean * kPi;  // pi x area (1) x the mean radiance
    const int n = 200000;
    Rng rng(17, 3);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int k = 0; k < n; ++k) {
        EmittedPhoton e = sampler.sample(rng);
        for (int c = 0; c < 3; ++c) sum[c] += e.power[c], sum2[c] += double(e.power[c]) * e.power[c];
    }
    for (int c = 0; c < 3; ++c) {
        double m = sum[c] / n, sigma = std::sqrt(std::max(0.0, sum2[c] / n - m * m) / n);
        // 5 sigma (the spread of uniform points over four blocks: ~0.2% of the mean) + half floats.
        EXPECT_NEAR(m, expected[c], 5 * sigma + 2e-3 * expected[c]) << "channel " << c;
    }
}

}  // namespace
}  // namespace tyndall
