// Textures through OpenImageIO's TextureSystem: texel values at known uv, sRGB decoding, wrap
// modes, the footprint filter, and every glTF texture slot (embedded PNG via data URI and via a
// buffer view, TEXCOORD_1, KHR_texture_transform) read back through evalSurface.
#include <gtest/gtest.h>

#include "core/material_eval.h"
#include "core/texture.h"
#include "tests/scene/png_bytes.h"
#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

using test::GltfBuilder;

constexpr float kHalfTol = 2e-3f;  // textures are stored as half floats

/// 4x4 texels, texel (x, y) = (x/4, y/4, (x+y)/8), alpha 1 - x/8.
std::vector<float> rampPixels() {
    std::vector<float> px;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) px.insert(px.end(), {x / 4.0f, y / 4.0f, (x + y) / 8.0f, 1.0f - x / 8.0f});
    return px;
}
Vec2 texelCentre(int x, int y, int n = 4) { return {(x + 0.5f) / n, (y + 0.5f) / n}; }

TEST(TextureStore, TexelCentresReadTheirTexelsTopRowFirst) {
    TextureStore store;
    int t = store.addPixels(4, 4, 4, rampPixels(), TextureEncoding::Linear, TextureWrap::Repeat, TextureWrap::Repeat,
                            "ramp");
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            auto v = store.lookup(t, texelCentre(x, y), 0.0f);
            EXPECT_NEAR(v[0], x / 4.0f, kHalfTol) << x << "," << y;
            EXPECT_NEAR(v[1], y / 4.0f, kHalfTol) << x << "," << y;  // v grows downward, as in glTF
            EXPECT_NEAR(v[2], (x + y) / 8.0f, kHalfTol);
            EXPECT_NEAR(v[3], 1.0f - x / 8.0f, kHalfTol);
        }
    }
}

TEST(TextureStore, SrgbIsDecodedToLinearOnceAtLoad) {
    TextureStore store;
    std::vector<float> grey(2 * 2, 0.5f);
    int s = store.addPixels(2, 2, 1, grey, TextureEncoding::Srgb, TextureWrap::Repeat, TextureWrap::Repeat, "srgb");
    int l = store.addPixels(2, 2, 1, grey, TextureEncoding::Linear, TextureWrap::Repeat, TextureWrap::Repeat, "lin");
    auto vs = store.lookup(s, {0.5f, 0.5f}, 0.0f), vl = store.lookup(l, {0.5f, 0.5f}, 0.0f);
    EXPECT_NEAR(vs[0], 0.214041f, kHalfTol);  // IEC 61966-2-1 of 0.5
    EXPECT_NEAR(vs[2], 0.214041f, kHalfTol);  // grey replicated to RGB
    EXPECT_NEAR(vs[3], 1.0f, kHalfTol);       // alpha stays linear, 1 when absent
    EXPECT_NEAR(vl[0], 0.5f, kHalfTol);
    // An 8-bit PNG decoded from memory: 128 -> 0.2158605 (sRGB), alpha 64 -> 0.25098 (linear).
    std::string png = test::pngBytes(1, 1, 4, {128, 128, 128, 64});
    int p = store.addEncoded(std::vector<unsigned char>(png.begin(), png.end()), "image/png", "", TextureEncoding::Srgb,
                             TextureWrap::Repeat, TextureWrap::Repeat, "png");
    auto vp = store.lookup(p, {0.5f, 0.5f}, 0.0f);
    EXPECT_NEAR(vp[1], 0.2158605f, kHalfTol);
    EXPECT_NEAR(vp[3], 64.0f / 255.0f, kHalfTol);
}

TEST(TextureStore, WrapModesFollowGltfSamplers) {
    TextureStore store;
    auto add = [&](TextureWrap w) {
        return store.addPixels(4, 4, 4, rampPixels(), TextureEncoding::Linear, w, w, "ramp");
    };
    int rep = add(TextureWrap::Repeat), clamp = add(TextureWrap::ClampToEdge), mirror = add(TextureWrap::MirroredRepeat);
    Vec2 outside{1.0f + texelCentre(0, 0).x, 0.5f / 4};  // one period to the right of texel 0
    EXPECT_NEAR(store.lookup(rep, outside, 0)[0], 0.0f, kHalfTol);
    EXPECT_NEAR(store.lookup(clamp, outside, 0)[0], 0.75f, kHalfTol);   // the last texel
    EXPECT_NEAR(store.lookup(mirror, outside, 0)[0], 0.75f, kHalfTol);  // mirrored: texel 3
    Vec2 further{1.0f + texelCentre(1, 0).x, 0.5f / 4};
    EXPECT_NEAR(store.lookup(rep, further, 0)[0], 0.25f, kHalfTol);
    EXPECT_NEAR(store.lookup(mirror, further, 0)[0], 0.5f, kHalfTol);  // texel 2
}

TEST(TextureStore, AWideFootprintAveragesTheChecker) {
    TextureStore store;
    std::vector<float> checker;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) checker.push_back(((x / 4 + y / 4) & 1) ? 1.0f : 0.0f);
    int t = store.addPixels(64, 64, 1, checker, TextureEncoding::Linear, TextureWrap::Repeat, TextureWrap::Repeat,
                            "checker");
    float sharp = store.lookup(t, texelCentre(1, 1, 64), 0.0f)[0];
    float blurred = store.lookup(t, texelCentre(1, 1, 64), 0.5f)[0];
    EXPECT_NEAR(sharp, 0.0f, kHalfTol);
    EXPECT_NEAR(blurred, 0.5f, 0.05f);  // a footprint of half the image reads a coarse mip level
    EXPECT_GT(store.stats().fileBytes, 0u);
}

TEST(TextureStore, UndecodableBytesAreAnErrorNamingThePlace) {
    TextureStore store;
    std::string msg = test::errorOf([&] {
        store.addEncoded({'n', 'o', 't'}, "image/png", "", TextureEncoding::Srgb, TextureWrap::Repeat,
                         TextureWrap::Repeat, "scene.gltf: material 'm': baseColorTexture");
    });
    EXPECT_NE(msg.find("scene.gltf: material 'm': baseColorTexture: cannot decode"), std::string::npos) << msg;
}

TEST(TextureTransform, MatchesKhrTextureTransformExample) {
    // The extension's reference: offset, then rotation, then scale, T * R * S.
    TextureTransform t = TextureTransform::fromOffsetRotationScale({0.5f, 0.25f}, 0.5f * kPi, {2.0f, 3.0f});
    Vec2 r = t.apply({1.0f, 0.0f});  // S: (2, 0); R(90): (cos*2 + sin*0, -sin*2 + cos*0) = (0, -2); + offset
    EXPECT_NEAR(r.x, 0.5f, 1e-5f);
    EXPECT_NEAR(r.y, -1.75f, 1e-5f);
    EXPECT_NEAR(t.scale(), std::sqrt(6.0f), 1e-5f);
}

// ---- glTF slots end to end.

/// 2x2 PNG, texels (top row first) a, b / c, d, each RGB(A).
std::string png2x2(std::vector<uint8_t> px, int channels) { return test::pngBytes(2, 2, channels, px); }

struct TexturedQuad {
    Scene scene;
    std::vector<std::string> warnings;
};

/// The unit quad in the xy plane, facing +z. TEXCOORD_0 = (x, 1 - y) (image top at y = 1);
/// TEXCOORD_1 = (1 - x, 1 - y) (mirrored in u).
TexturedQuad texturedQuad() {
    GltfBuilder b;
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<float> uv0 = {0, 1, 1, 1, 1, 0, 0, 0};
    std::vector<float> uv1 = {1, 1, 0, 1, 0, 0, 1, 0};
    std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
    nlohmann::json prim = {{"attributes",
                            {{"POSITION", b.addFloats(pos, "VEC3")},
                             {"TEXCOORD_0", b.addFloats(uv0, "VEC2")},
                             {"TEXCOORD_1", b.addFloats(uv1, "VEC2")}}},
                           {"indices", b.addIndices(idx)},
                           {"material", 0}};
    b.doc["meshes"].push_back({{"name", "quad"}, {"primitives", {prim}}});
    b.addNode({{"name", "quad"}, {"mesh", 0}});
    // base colour: sRGB red/green/blue/white with alpha, as a data URI.
    std::string base = png2x2({255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255, 255, 255, 255, 0}, 4);
    // emissive: 128 grey / 255 ... in a buffer view with a mimeType (as .glb files store them).
    std::string emissive = png2x2({128, 128, 128, 255, 255, 0, 0, 0, 0, 0, 0, 0}, 3);
    int view = b.addView(emissive.data(), emissive.size());
    // metallicRoughness (linear): G = roughness, B = metallic.
    std::string mr = png2x2({0, 51, 255, 0, 102, 0, 0, 153, 255, 0, 204, 0}, 3);
    b.doc["images"] = {{{"uri", "data:image/png;base64," + test::base64(base)}},
                       {{"bufferView", view}, {"mimeType", "image/png"}},
                       {{"uri", "data:image/png;base64," + test::base64(mr)}}};
    b.doc["samplers"] = {{{"wrapS", 33071}, {"wrapT", 33071}}};
    b.doc["textures"] = {{{"source", 0}, {"sampler", 0}}, {{"source", 1}}, {{"source", 2}}};
    // metallicRoughness reads texCoord 1 through the extension, shifted by half the image in v.
    nlohmann::json transform = {{"texCoord", 1}, {"offset", {0.0, 0.5}}};
    nlohmann::json mrInfo = {{"index", 2}, {"texCoord", 0}};
    mrInfo["extensions"]["KHR_texture_transform"] = transform;
    nlohmann::json pbr = {{"baseColorFactor", {1.0, 1.0, 0.5, 1.0}},
                          {"baseColorTexture", {{"index", 0}}},
                          {"metallicFactor", 1.0},
                          {"roughnessFactor", 0.5}};
    pbr["metallicRoughnessTexture"] = mrInfo;
    nlohmann::json mat = {{"name", "textured"}, {"emissiveFactor", {1.0, 0.5, 1.0}}};
    mat["emissiveTexture"] = {{"index", 1}};
    mat["pbrMetallicRoughness"] = pbr;
    b.addMaterial(mat);
    int l = b.addLight({{"type", "point"}, {"intensity", 683.0}});
    b.addNode({{"name", "lamp"}, {"translation", {0, 0, 5}}, {"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}});
    b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_texture_transform"};
    TexturedQuad q;
    q.scene = test::loadText(b.text(), SceneFormat::Gltf, &q.warnings).scene;
    return q;
}

/// evalSurface at world point (x, y) of the quad.
SurfacePoint at(const Scene& s, float x, float y) {
    const TriangleMesh& m = s.meshes[0];
    // Triangle 0 = (0,0),(1,0),(1,1): p = b1 (1,0) + b2 (1,1) -> b2 = y, b1 = x - y; triangle 1 = (0,0),(1,1),(0,1).
    if (x >= y) return evalSurface(s, m, 0, x - y, y, 0.0f);
    return evalSurface(s, m, 1, x, y - x, 0.0f);
}

TEST(GltfTextures, EverySlotIsSampledAtItsTexcoords) {
    TexturedQuad q = texturedQuad();
    const Scene& s = q.scene;
    ASSERT_TRUE(s.textures);
    EXPECT_EQ(s.textures->size(), 3u);
    for (const std::string& w : q.warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
    const float r128 = srgbToLinear(128 / 255.0f);
    // Image texel (col, row) sits at uv0 ((col + .5)/2, (row + .5)/2), i.e. world x = u, y = 1 - v.
    SurfacePoint tl = at(s, 0.25f, 0.75f), tr = at(s, 0.75f, 0.75f), bl = at(s, 0.25f, 0.25f),
                 br = at(s, 0.75f, 0.25f);
    // baseColor = factor (1, 1, 0.5) x sRGB-decoded texel; alpha = texel alpha (linear).
    EXPECT_NEAR(tl.baseColor.r, 1.0f, kHalfTol);
    EXPECT_NEAR(tl.baseColor.g, 0.0f, kHalfTol);
    EXPECT_NEAR(tr.baseColor.g, 1.0f, kHalfTol);
    EXPECT_NEAR(tr.alpha, 128 / 255.0f, kHalfTol);
    EXPECT_NEAR(bl.baseColor.b, 0.5f, kHalfTol);
    EXPECT_NEAR(br.baseColor.r, 1.0f, kHalfTol);
    EXPECT_NEAR(br.alpha, 0.0f, kHalfTol);
    // emissive = factor (1, 0.5, 1) x sRGB texel.
    EXPECT_NEAR(tl.emission.r, r128, kHalfTol);
    EXPECT_NEAR(tl.emission.g, 0.5f * r128, kHalfTol);
    EXPECT_NEAR(tr.emission.b, 0.0f, kHalfTol);
    EXPECT_NEAR(tr.emission.r, 1.0f, kHalfTol);
    EXPECT_NEAR(bl.emission.r, 0.0f, kHalfTol);
    // metallicRoughness through TEXCOORD_1 = (1 - x, 1 - y) + (0, 0.5), clamp-free default wrap
    // (repeat): world (0.25, 0.75) -> uv (0.75, 0.75) -> texel (1, 1) = (0, 204, 0): roughness
    // 0.5 x 0.8, metallic 0.
    EXPECT_NEAR(tl.roughness, 0.5f * 0.8f, kHalfTol);
    EXPECT_NEAR(tl.metallic, 0.0f, kHalfTol);
    // world (0.75, 0.75) -> uv (0.25, 0.75) -> texel (0, 1) = (0, 153, 255).
    EXPECT_NEAR(tr.roughness, 0.5f * 0.6f, kHalfTol);
    EXPECT_NEAR(tr.metallic, 1.0f, kHalfTol);
    // world (0.75, 0.25) -> uv (0.25, 1.25) -> repeat -> texel (0, 0) = (0, 51, 255).
    EXPECT_NEAR(br.roughness, 0.5f * 0.2f, kHalfTol);
    EXPECT_NEAR(br.metallic, 1.0f, kHalfTol);
}

TEST(GltfTextures, ClampSamplerHoldsTheEdgeTexel) {
    TexturedQuad q = texturedQuad();
    const TriangleMesh& m = q.scene.meshes[0];
    const Material& mat = q.scene.materials[size_t(m.material)];
    // uv (1.4, 0.25) with CLAMP_TO_EDGE reads the top-right texel (green).
    auto v = q.scene.textures->lookup(mat.baseColorTexture.texture, {1.4f, 0.25f}, 0.0f);
    EXPECT_NEAR(v[1], 1.0f, kHalfTol);
    EXPECT_NEAR(v[0], 0.0f, kHalfTol);
}

}  // namespace
}  // namespace tyndall
