// A textured Khronos model renders with its colours: GlassVaseFlowers (base-colour, metallic-
// roughness textures, alphaMode MASK foliage, an alphaMode BLEND vase, a transmissive vase), lit by
// the loader's headlight, PPB against the reference path tracer. Compared: the mean colour of the
// image's left half (the BLEND vase and its flowers). The right half holds the smooth
// transmissive vase, through which the reference cannot carry a point-like light (no next-event
// estimation through glass, cpu/reference_tracer.h) while PPB's photons can: excluded on purpose.
// Measured here (128x128, 32 passes of 40000 paths, 256 spp): PPB / reference = 0.995, 1.006, 0.982
// (1.000, 1.005, 0.989 with the flowers' normal map). The 1.20-1.25 once seen at 64x64 with 24 passes
// is noise: over eight PPB seeds at 64x64 x 24 passes the green ratio against a 1024-spp reference
// ranged 0.88-1.23 (mean 1.00, sd 0.11; the 0.001 surface radius makes a few photons into
// fireflies), so this test's 15% bound is only about 1.5 sd of a 24-pass run: do not cut it shorter.
// Planted bug: without
// the 1/alpha on photons stored on BLEND surfaces (cpu/photon_tracer.cpp) the image came out
// 0.66-0.80 of the reference (measured with `tyndall render` / `tyndall reference`).
// Skips when ../shared/assets is absent.
#include <gtest/gtest.h>

#include <filesystem>

#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "core/accumulator.h"
#include "loading/scene_file.h"

namespace tyndall {
namespace {

Rgb halfMean(const Image& img) {
    double s[3] = {0, 0, 0};
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width / 2; ++x)
            for (int c = 0; c < 3; ++c) s[c] += img.at(x, y)[c];
    double n = double(img.height) * (img.width / 2);
    return Rgb(float(s[0] / n), float(s[1] / n), float(s[2] / n));
}

TEST(KhronosTextured, GlassVaseFlowersColoursMatchTheReference) {
    const std::string path = std::string(TYNDALL_ASSETS_DIR) + "/gltf/GlassVaseFlowers/GlassVaseFlowers.glb";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "asset not found: " << path;
    SceneLoadOptions o;
    std::vector<std::string> warnings;
    o.warn = [&](const std::string& w) { warnings.push_back(w); };
    SceneFile f = loadSceneFile(path, o);
    for (const std::string& w : warnings) {
        EXPECT_EQ(w.find("baseColorTexture ignored"), std::string::npos) << w;
        EXPECT_EQ(w.find("alpha"), std::string::npos) << w;
    }
    const int size = 128;
    ReferenceSettings rs;
    rs.width = rs.height = size;
    rs.samplesPerPixel = 256;
    rs.seed = 5;
    EmbreeScene rt(f.scene);
    ReferenceImage ref = ReferenceTracer(rt, rs).render();

    RenderSettings ps;
    ps.width = ps.height = size;
    ps.photonsPerPass = 40000;
    ps.surfaceRadius = 0.001f;  // petals are a few millimetres wide
    ps.seed = 6;
    PassRenderer renderer(f.scene, ps);
    Accumulator acc(size, size);
    for (uint64_t pass = 0; pass < 32; ++pass) acc.addPass(renderer.renderPass(pass));
    Rgb p = halfMean(acc.mean()), r = halfMean(ref.mean);
    for (int c = 0; c < 3; ++c) {
        std::printf("channel %d: PPB %.6f reference %.6f ratio %.3f\n", c, p[c], r[c], p[c] / r[c]);
        EXPECT_GT(r[c], 0.0f);
        EXPECT_NEAR(p[c] / r[c], 1.0, 0.15) << "channel " << c;
    }
}

}  // namespace
}  // namespace tyndall
