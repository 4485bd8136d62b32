// Texture forms the other texture tests leave out:
//   - grey + alpha images (2 channels), from PNG bytes and from raw pixels: the grey channel is the
//     colour of all three (sRGB-decoded), the second channel the alpha (linear), not green;
//   - KHR_texture_transform at an angle with unequal scales and an offset, where every entry of the
//     2x3 matrix matters (the extension's example at 90 degrees zeroes the cosines, and its one
//     probe point (1, 0) never reads the v column): against T * R * S multiplied out here, with
//     R = [[cos, sin], [-sin, cos]] in glTF's v-down uv (the reading of Babylon.js, three.js, Blender
//     and the TextureTransformTest sample model: KhronosGroup/glTF#1563), directly and
//     through the glTF loader.
#include <gtest/gtest.h>

#include <cmath>

#include "core/material_eval.h"
#include "core/texture.h"
#include "tests/scene/png_bytes.h"
#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

constexpr float kHalfTol = 2e-3f;  // textures are stored as half floats

double srgbDecode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(TextureForms, GreyAlphaImagesGiveGreyColourAndLinearAlpha) {
    TextureStore store;
    // 2 x 1 texels: (grey 200, alpha 51), (grey 30, alpha 255).
    std::string png = test::pngBytes(2, 1, 2, {200, 51, 30, 255});
    int p = store.addEncoded(std::vector<unsigned char>(png.begin(), png.end()), "image/png", "", TextureEncoding::Srgb,
                             TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, "grey-alpha png");
    int r = store.addPixels(2, 1, 2, {200 / 255.0f, 0.2f, 30 / 255.0f, 1.0f}, TextureEncoding::Srgb,
                            TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, "grey-alpha pixels");
    for (int t : {p, r}) {
        SCOPED_TRACE(t == p ? "png" : "pixels");
        auto a = store.lookup(t, {0.25f, 0.5f}, 0.0f), b = store.lookup(t, {0.75f, 0.5f}, 0.0f);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(a[c], srgbDecode(200 / 255.0), kHalfTol) << "channel " << c;
            EXPECT_NEAR(b[c], srgbDecode(30 / 255.0), kHalfTol) << "channel " << c;
        }
        EXPECT_NEAR(a[3], 0.2f, kHalfTol) << "alpha is linear";
        EXPECT_NEAR(b[3], 1.0f, kHalfTol);
    }
}

/// T * R * S of KHR_texture_transform as 3x3 matrices multiplied out, rows 0 and 1.
std::array<double, 6> khrMatrix(double ox, double oy, double rot, double sx, double sy) {
    const double c = std::cos(rot), s = std::sin(rot);
    const double T[3][3] = {{1, 0, ox}, {0, 1, oy}, {0, 0, 1}};
    const double R[3][3] = {{c, s, 0}, {-s, c, 0}, {0, 0, 1}};
    const double S[3][3] = {{sx, 0, 0}, {0, sy, 0}, {0, 0, 1}};
    double TR[3][3] = {}, M[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) TR[i][j] += T[i][k] * R[k][j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) M[i][j] += TR[i][k] * S[k][j];
    return {M[0][0], M[0][1], M[0][2], M[1][0], M[1][1], M[1][2]};
}

constexpr double kOx = 0.1, kOy = -0.2, kRot = 0.3, kSx = 2.0, kSy = 0.7;

void expectKhr(const TextureTransform& t) {
    const auto m = khrMatrix(kOx, kOy, kRot, kSx, kSy);
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(t.m[size_t(i)], m[size_t(i)], 1e-6) << "entry " << i;
    for (Vec2 uv : {Vec2{0.3f, 0.8f}, Vec2{1.0f, 0.0f}, Vec2{0.0f, 1.0f}, Vec2{-0.6f, 0.25f}}) {
        Vec2 r = t.apply(uv);
        EXPECT_NEAR(r.x, m[0] * uv.x + m[1] * uv.y + m[2], 1e-6);
        EXPECT_NEAR(r.y, m[3] * uv.x + m[4] * uv.y + m[5], 1e-6);
    }
    EXPECT_NEAR(t.scale(), std::sqrt(kSx * kSy), 1e-6) << "sqrt |det|";
}

TEST(TextureForms, TransformAtAnAngleMatchesTRSMultipliedOut) {
    expectKhr(TextureTransform::fromOffsetRotationScale({float(kOx), float(kOy)}, float(kRot), {float(kSx), float(kSy)}));
}

TEST(TextureForms, GltfTransformAtAnAngleReachesTheMaterialAndItsLookups) {
    test::GltfBuilder b;
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<float> uv0 = {0, 1, 1, 1, 1, 0, 0, 0};
    std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
    nlohmann::json prim = {{"attributes", {{"POSITION", b.addFloats(pos, "VEC3")}, {"TEXCOORD_0", b.addFloats(uv0, "VEC2")}}},
                           {"indices", b.addIndices(idx)},
                           {"material", 0}};
    b.doc["meshes"].push_back({{"name", "quad"}, {"primitives", {prim}}});
    b.addNode({{"name", "quad"}, {"mesh", 0}});
    // A 4 x 4 linear ramp (emissive: sRGB-encoded), repeated: R = column / 3 * 255, G = row / 3 * 255.
    std::vector<uint8_t> px;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) px.insert(px.end(), {uint8_t(x * 85), uint8_t(y * 85), 0});
    std::string png = test::pngBytes(4, 4, 3, px);
    b.doc["images"] = {{{"uri", "data:image/png;base64," + test::base64(png)}}};
    b.doc["samplers"] = {{{"wrapS", 10497}, {"wrapT", 10497}, {"magFilter", 9728}}};
    b.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};
    nlohmann::json info = {{"index", 0}};
    info["extensions"]["KHR_texture_transform"] = {{"offset", {kOx, kOy}}, {"rotation", kRot}, {"scale", {kSx, kSy}}};
    nlohmann::json mat = {{"name", "glow"}, {"emissiveFactor", {1.0, 1.0, 1.0}}, {"emissiveTexture", info}};
    b.addMaterial(mat);
    b.doc["extensionsUsed"] = {"KHR_texture_transform"};
    Scene s = test::loadText(b.text(), SceneFormat::Gltf).scene;
    ASSERT_EQ(s.materials.size(), 1u);
    const TextureRef& ref = s.materials[0].emissiveTexture;
    ASSERT_TRUE(ref.present());
    expectKhr(ref.transform);
    // evalSurface reads the emission at the transformed uv: at a point of the quad whose
    // transformed uv lands on a texel centre (modulo the repeat), the texel's value.
    const auto m = khrMatrix(kOx, kOy, kRot, kSx, kSy);
    const double det = m[0] * m[4] - m[1] * m[3];
    int checked = 0;
    for (int tx = 0; tx < 4; ++tx)
        for (int ty = 0; ty < 4; ++ty)
            for (int kx = -3; kx <= 3; ++kx)
                for (int ky = -3; ky <= 3; ++ky) {
                    // Target uv' = a texel centre shifted by whole repeats, solved for uv.
                    const double u2 = (tx + 0.5) / 4 + kx - m[2], v2 = (ty + 0.5) / 4 + ky - m[5];
                    const double u = (m[4] * u2 - m[1] * v2) / det, v = (-m[3] * u2 + m[0] * v2) / det;
                    if (u < 0.02 || u > 0.98 || v < 0.02 || v > 0.98) continue;  // off the quad
                    const float x = float(u), y = float(1 - v);                  // TEXCOORD_0 = (x, 1 - y)
                    const TriangleMesh& mesh = s.meshes[0];
                    SurfacePoint sp =
                        x >= y ? evalSurface(s, mesh, 0, x - y, y, 0.0f) : evalSurface(s, mesh, 1, x, y - x, 0.0f);
                    EXPECT_NEAR(sp.emission.r, srgbDecode(tx * 85 / 255.0), 4 * kHalfTol) << "texel " << tx << "," << ty;
                    EXPECT_NEAR(sp.emission.g, srgbDecode(ty * 85 / 255.0), 4 * kHalfTol) << "texel " << tx << "," << ty;
                    ++checked;
                }
    EXPECT_GE(checked, 8) << "too few probe points on the quad";
}

}  // namespace
}  // namespace tyndall
