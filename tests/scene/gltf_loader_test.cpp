// glTF -> Scene: node transforms, cameras and --camera selection, KHR_lights_punctual units,
// primitives, volumes, the headlight, and the material mapping table (mapGltfMaterial).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "loading/gltf_material_mapping.h"
#include "core/photometry.h"
#include "tests/scene/png_bytes.h"
#include "tests/scene/scene_test_util.h"

namespace tyndall {
namespace {

using test::GltfBuilder;
using test::loadText;

void expectNear(const Vec3& a, const Vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

const float kSqrtHalf = std::sqrt(0.5f);

/// One light so that scenes validate without the headlight.
void addSomeLight(GltfBuilder& b) {
    int l = b.addLight({{"type", "point"}, {"intensity", 683.0}});
    b.addNode(
        {{"name", "lamp"}, {"translation", {0, 10, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}});
}

TEST(GltfLoader, NodeHierarchyComposesTranslationRotationScale) {
    GltfBuilder b;
    int mesh = b.addMesh("tri", {1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 1, 2});
    // child: scale 2, then 90 degrees about +y, then the parent's translation (1, 2, 3).
    int child = b.addNode(
        {{"name", "child"}, {"mesh", mesh}, {"scale", {2, 2, 2}}, {"rotation", {0, kSqrtHalf, 0, kSqrtHalf}}}, false);
    b.addNode({{"name", "parent"}, {"translation", {1, 2, 3}}, {"children", {child}}});
    // The same through a column-major matrix: translation (5, 0, 0), uniform scale 3.
    b.addNode({{"name", "matrix node"}, {"mesh", mesh}, {"matrix", {3, 0, 0, 0, 0, 3, 0, 0, 0, 0, 3, 0, 5, 0, 0, 1}}});
    addSomeLight(b);
    Scene s = loadText(b.text(), SceneFormat::Gltf).scene;
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.meshes[0].name, "child");
    // R_y(90) maps (x, y, z) -> (z, y, -x).
    expectNear(s.meshes[0].positions[0], {1 + 0, 2 + 0, 3 - 2});
    expectNear(s.meshes[0].positions[1], {1 + 0, 2 + 2, 3 + 0});
    expectNear(s.meshes[0].positions[2], {1 + 2, 2 + 0, 3 + 0});
    EXPECT_EQ(s.meshes[1].name, "matrix node");
    expectNear(s.meshes[1].positions[0], {8, 0, 0});
    expectNear(s.meshes[1].positions[2], {5, 0, 3});
}

TEST(GltfLoader, MirroringTransformKeepsMeshesOutward) {
    GltfBuilder b;
    int cube = b.addCube("cube");
    b.addNode({{"name", "mirrored"}, {"mesh", cube}, {"scale", {-1, 2, 1}}});
    addSomeLight(b);
    Scene s = loadText(b.text(), SceneFormat::Gltf).scene;
    const TriangleMesh& m = s.meshes[0];
    EXPECT_TRUE(m.isClosed());
    double volume = 0;  // divergence theorem: positive for outward normals
    for (size_t t = 0; t < m.triangleCount(); ++t) volume += dot(m.vertex(t, 0), m.geometricNormal(t)) / 6.0;
    EXPECT_NEAR(volume, 2.0, 1e-5);
}

TEST(GltfLoader, CamerasFollowTheirNodesAndAreSelectable) {
    GltfBuilder b;
    b.doc["cameras"] = {{{"name", "wide"}, {"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}},
                        {{"name", "tele"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.25}, {"znear", 0.1}}}}};
    b.addNode({{"name", "front"}, {"camera", 0}, {"translation", {0, 1, 5}}});
    // Rotated 90 degrees about +y: looks along R(0, 0, -1) = (-1, 0, 0).
    b.addNode(
        {{"name", "side"}, {"camera", 1}, {"translation", {4, 1, 0}}, {"rotation", {0, kSqrtHalf, 0, kSqrtHalf}}});
    int cube = b.addCube("cube");
    b.addNode({{"mesh", cube}});
    addSomeLight(b);

    SceneFile first = loadText(b.text(), SceneFormat::Gltf);
    ASSERT_EQ(first.cameras, (std::vector<std::string>{"front", "side"}));
    expectNear(first.scene.camera.position, {0, 1, 5});
    expectNear(first.scene.camera.forward, {0, 0, -1});
    expectNear(first.scene.camera.up, {0, 1, 0});
    EXPECT_NEAR(first.scene.camera.yFov, 1.0f, 1e-6f);

    for (std::string selector : {"side", "1"}) {
        Camera c = loadText(b.text(), SceneFormat::Gltf, nullptr, selector).scene.camera;
        expectNear(c.position, {4, 1, 0});
        expectNear(c.forward, {-1, 0, 0});
        expectNear(c.right, {0, 0, -1});
        EXPECT_NEAR(c.yFov, 0.25f, 1e-6f);
    }
    std::string err = test::errorOf([&] { loadText(b.text(), SceneFormat::Gltf, nullptr, "top"); });
    EXPECT_NE(err.find("test.gltf: --camera top: no such camera"), std::string::npos) << err;
    EXPECT_NE(err.find("0 'front', 1 'side'"), std::string::npos) << err;
}

TEST(GltfLoader, NoCameraFramesTheScene) {
    GltfBuilder b;
    int cube = b.addCube("cube");
    b.addNode({{"mesh", cube}, {"translation", {10, 0, 0}}});
    addSomeLight(b);
    SceneFile f = loadText(b.text(), SceneFormat::Gltf);
    ASSERT_EQ(f.cameras, std::vector<std::string>{"automatic"});
    // The cube's centre (10, 0, 0) projects to the image centre.
    float x, y, depth;
    ASSERT_TRUE(f.scene.camera.project({10, 0, 0}, 100, 100, &x, &y, &depth));
    EXPECT_NEAR(x, 50.0f, 0.5f);
    EXPECT_NEAR(y, 50.0f, 0.5f);
}

TEST(GltfLoader, PunctualLightsConvertCandelaAndLuxAt683LumensPerWatt) {
    GltfBuilder b;
    int point =
        b.addLight({{"name", "bulb"}, {"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 683.0 * 4}});
    int sun = b.addLight({{"name", "sun"}, {"type", "directional"}, {"intensity", 1366.0}});
    int spot = b.addLight({{"name", "spot"},
                           {"type", "spot"},
                           {"intensity", 68.3},
                           {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}});
    b.addNode({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", point}}}}}});
    // Rotated -90 degrees about x: -z turns to -y (straight down).
    b.addNode(
        {{"rotation", {-kSqrtHalf, 0, 0, kSqrtHalf}}, {"extensions", {{"KHR_lights_punctual", {{"light", sun}}}}}});
    b.addNode({{"translation", {0, 3, 0}},
               {"rotation", {-kSqrtHalf, 0, 0, kSqrtHalf}},
               {"extensions", {{"KHR_lights_punctual", {{"light", spot}}}}}});
    int cube = b.addCube("cube");
    b.addNode({{"mesh", cube}});
    Scene s = loadText(b.text(), SceneFormat::Gltf).scene;
    ASSERT_EQ(s.lights.size(), 3u);
    const Light& l0 = s.lights[0];
    EXPECT_EQ(l0.type, LightType::Point);
    EXPECT_EQ(l0.name, "bulb");
    expectNear(l0.position, {1, 2, 3});
    EXPECT_NEAR(l0.intensity.r, 4.0f, 1e-5f);  // W/sr = cd / 683
    EXPECT_NEAR(l0.intensity.g, 2.0f, 1e-5f);
    EXPECT_NEAR(l0.intensity.b, 1.0f, 1e-5f);
    const Light& l1 = s.lights[1];
    EXPECT_EQ(l1.type, LightType::Directional);
    EXPECT_NEAR(l1.intensity.g, 2.0f, 1e-5f);  // W/m^2 = lux / 683
    expectNear(l1.direction, {0, -1, 0});
    const Light& l2 = s.lights[2];
    EXPECT_EQ(l2.type, LightType::Spot);
    EXPECT_NEAR(l2.intensity.b, 0.1f, 1e-6f);
    expectNear(l2.direction, {0, -1, 0});
    EXPECT_NEAR(l2.cosInnerAngle, std::cos(0.2f), 1e-6f);
    EXPECT_NEAR(l2.cosOuterAngle, std::cos(0.5f), 1e-6f);
    EXPECT_NEAR(radiantIntensityFromCandela(Rgb(1.0f), 683.0f).g, 1.0f, 1e-7f);
    EXPECT_NEAR(irradianceFromLux(Rgb(1.0f), 683.0f).g, 1.0f, 1e-7f);
}

TEST(GltfLoader, LightRangeIsWarnedOnce) {
    GltfBuilder b;
    int l = b.addLight({{"type", "point"}, {"intensity", 10.0}, {"range", 5.0}});
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}});
    b.addNode({{"extensions", {{"KHR_lights_punctual", {{"light", l}}}}}});
    b.addNode({{"mesh", b.addCube("cube")}});
    std::vector<std::string> warnings;
    loadText(b.text(), SceneFormat::Gltf, &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("range ignored"), std::string::npos) << warnings[0];
}

TEST(GltfLoader, EmissiveStrengthMakesAreaLights) {
    GltfBuilder b;
    int mat = b.addMaterial({{"name", "panel"},
                             {"emissiveFactor", {1.0, 0.5, 0.25}},
                             {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 8.0}}}}}});
    b.addNode({{"mesh", b.addMesh("panel", {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, mat)}});
    Scene s = loadText(b.text(), SceneFormat::Gltf).scene;
    EXPECT_TRUE(s.lights.empty());  // no headlight: the panel emits
    ASSERT_EQ(s.emitters.size(), 1u);
    EXPECT_NEAR(s.emitters[0].radiance.r, 8.0f, 1e-6f);
    EXPECT_NEAR(s.emitters[0].radiance.b, 2.0f, 1e-6f);
    EXPECT_NEAR(s.emitters[0].area, 0.5f, 1e-6f);
}

TEST(GltfLoader, StripsAndFansBecomeTriangles) {
    GltfBuilder b;
    std::vector<float> quad = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    int strip = b.addMesh("strip", quad, {0, 1, 2, 3});
    b.doc["meshes"][strip]["primitives"][0]["mode"] = 5;
    int fan = b.addMesh("fan", quad, {0, 1, 3, 2});
    b.doc["meshes"][fan]["primitives"][0]["mode"] = 6;
    b.addNode({{"mesh", strip}});
    b.addNode({{"mesh", fan}});
    addSomeLight(b);
    Scene s = loadText(b.text(), SceneFormat::Gltf).scene;
    for (const TriangleMesh& m : s.meshes) {
        ASSERT_EQ(m.triangleCount(), 2u) << m.name;
        for (size_t t = 0; t < 2; ++t) EXPECT_GT(m.geometricNormal(t).z, 0.0f) << m.name << " keeps its orientation";
    }
}

TEST(GltfLoader, VolumeBecomesAbsorbingMediumInsideClosedMeshesOnly) {
    GltfBuilder b;
    int mat = b.addMaterial(
        {{"name", "tinted glass"},
         {"extensions",
          {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
           {"KHR_materials_ior", {{"ior", 1.33}}},
           {"KHR_materials_volume",
            {{"attenuationColor", {0.5, 0.25, 1.0}}, {"attenuationDistance", 2.0}, {"thicknessFactor", 1.0}}}}}});
    b.addNode({{"name", "block"}, {"mesh", b.addCube("block", mat)}});
    b.addNode({{"name", "sheet"},
               {"mesh", b.addMesh("sheet", {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, mat)},
               {"translation", {3, 0, 0}}});  // beside the block, not through it
    addSomeLight(b);
    std::vector<std::string> warnings;
    Scene s = loadText(b.text(), SceneFormat::Gltf, &warnings).scene;
    ASSERT_EQ(s.media.size(), 1u);
    const Medium& m = s.media[0];
    EXPECT_NEAR(m.sigmaA.r, std::log(2.0f) / 2.0f, 1e-6f);  // -ln(c) / d
    EXPECT_NEAR(m.sigmaA.g, std::log(4.0f) / 2.0f, 1e-6f);
    EXPECT_NEAR(m.sigmaA.b, 0.0f, 1e-7f);
    EXPECT_TRUE(m.sigmaS.isBlack());
    EXPECT_EQ(s.meshes[0].interiorMedium, 0);
    EXPECT_EQ(s.materials[size_t(s.meshes[0].material)].type, MaterialType::Dielectric);
    EXPECT_NEAR(s.materials[size_t(s.meshes[0].material)].ior, 1.33f, 1e-6f);
    EXPECT_EQ(s.meshes[1].interiorMedium, kVacuum);  // open: thin-walled, warned
    bool warned = false;
    for (const std::string& w : warnings)
        warned |= w.find("'sheet'") != std::string::npos && w.find("open mesh") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(GltfLoader, HeadlightWhenTheFileHasNoLight) {
    GltfBuilder b;
    b.addNode({{"mesh", b.addCube("cube")}, {"translation", {0, 0, -3}}});
    std::vector<std::string> warnings;
    Scene s = loadText(b.text(), SceneFormat::Gltf, &warnings).scene;
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_EQ(s.lights[0].name, "headlight");
    expectNear(s.lights[0].position, s.camera.position);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("no lights"), std::string::npos);
}

// ---- Whole files on disk: .gltf with external buffer and image, .glb, the fuzzer's seeds.

/// A red diffuse cube with a base-colour texture, lit by a point light.
GltfBuilder texturedCube() {
    GltfBuilder b;
    b.doc["images"] = {{{"name", "label"}, {"uri", "label.png"}}};
    b.doc["textures"] = {{{"source", 0}}};
    int mat = b.addMaterial(
        {{"name", "red paint"},
         {"pbrMetallicRoughness",
          {{"baseColorFactor", {0.8, 0.1, 0.1, 1.0}}, {"metallicFactor", 0.0}, {"baseColorTexture", {{"index", 0}}}}}});
    b.addNode({{"name", "box"}, {"mesh", b.addCube("box mesh", mat)}, {"translation", {0, 0.5, 0}}});
    addSomeLight(b);
    return b;
}

void expectTexturedCube(const SceneFile& f, const std::vector<std::string>& warnings) {
    const Scene& s = f.scene;
    ASSERT_EQ(s.meshes.size(), 1u);
    const TriangleMesh& m = s.meshes[0];
    EXPECT_EQ(m.name, "box");
    EXPECT_EQ(m.triangleCount(), 12u);
    ASSERT_EQ(m.positions.size(), 8u);
    expectNear(m.positions[0], {-0.5f, 0.0f, -0.5f});
    expectNear(m.positions[7], {0.5f, 1.0f, 0.5f});
    EXPECT_TRUE(m.isClosed());
    const Material& mat = s.materials[size_t(m.material)];
    EXPECT_EQ(mat.name, "red paint");
    EXPECT_EQ(mat.type, MaterialType::Plastic);  // a non-metal: the coat over the diffuse base
    EXPECT_NEAR(mat.albedo.r, 0.8f, 1e-6f);
    EXPECT_NEAR(mat.albedo.g, 0.1f, 1e-6f);
    ASSERT_EQ(s.lights.size(), 1u);
    for (const std::string& w : warnings) EXPECT_EQ(w.find("ignored"), std::string::npos) << w;
    ASSERT_TRUE(mat.baseColorTexture.present()) << "the image was found and decoded";
    ASSERT_TRUE(s.textures);
    // The cube has no TEXCOORD_0: uv (0, 0) reads the 1x1 label's sRGB 128 grey.
    EXPECT_NEAR(s.textures->lookup(mat.baseColorTexture.texture, {0, 0}, 0)[0], srgbToLinear(128 / 255.0f), 2e-3f);
}

SceneFile loadFile(const std::string& path, std::vector<std::string>* warnings) {
    SceneLoadOptions o;
    o.warn = [warnings](const std::string& w) { warnings->push_back(w); };
    return loadSceneFile(path, o);
}

TEST(GltfFiles, GltfWithExternalBufferAndImageLoads) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(test::outputDir()) / "gltf-external";
    fs::create_directories(dir / "data");
    GltfBuilder b = texturedCube();
    std::ofstream(dir / "data" / "cube mesh.bin", std::ios::binary) << b.bin;
    std::ofstream(dir / "label.png", std::ios::binary) << test::pngBytes(1, 1, 3, {128, 128, 128});
    const fs::path file = dir / "cube.gltf";
    std::ofstream(file, std::ios::binary) << b.jsonWithExternalBuffer("data/cube%20mesh.bin").dump();
    std::vector<std::string> warnings;
    expectTexturedCube(loadFile(file.string(), &warnings), warnings);
}

TEST(GltfFiles, GlbLoads) {
    const std::string path = test::writeTestFile("cube.glb", texturedCube().glb());
    { std::ofstream(test::outputDir() + "/label.png", std::ios::binary) << test::pngBytes(1, 1, 3, {128, 128, 128}); }
    std::vector<std::string> warnings;
    expectTexturedCube(loadFile(path, &warnings), warnings);
}

TEST(GltfFiles, FuzzSeedsLoad) {
    for (const char* seed : {"tiny.gltf", "tiny.glb"}) {
        SCOPED_TRACE(seed);
        std::vector<std::string> warnings;
        SceneFile f = loadFile(std::string(TYNDALL_SOURCE_DIR) + "/fuzz/seeds/" + seed, &warnings);
        EXPECT_GT(f.scene.triangleCount(), 0u);
        EXPECT_FALSE(f.scene.lights.empty());
        EXPECT_FALSE(f.scene.materials.empty());
    }
}

// ---- The material mapping table.

GltfMaterialInput input(const std::string& name) {
    GltfMaterialInput in;
    in.where = "m.gltf: material '" + name + "' (index 0)";
    in.name = name;
    return in;
}

TEST(GltfMaterialMapping, TransmissionBecomesDielectricWithIorAndTint) {
    GltfMaterialInput in = input("glass");
    in.transmission = 1.0f;
    in.ior = 1.7f;
    in.roughness = 0.0f;
    in.baseColor = Rgb(0.9f, 0.8f, 0.7f);
    GltfMaterialMapping m = mapGltfMaterial(in);
    EXPECT_EQ(m.material.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(m.material.ior, 1.7f);
    EXPECT_FLOAT_EQ(m.material.albedo.b, 0.7f);
    EXPECT_TRUE(m.notes.empty());
    EXPECT_FALSE(m.interior);
    EXPECT_TRUE(m.material.thin);  // no KHR_materials_volume: thin-walled, as glTF says
}

TEST(GltfMaterialMapping, ThinWalledUnlessAVolumeHasThickness) {
    GltfMaterialInput in = input("bulb");
    in.transmission = 1.0f;
    in.roughness = 0.0f;
    in.hasVolume = true;
    in.attenuationDistance = 2.0f;
    in.attenuationColor = Rgb(0.5f);
    in.thickness = 0.0f;  // glTF: a thicknessFactor of 0 is thin-walled, the volume ignored (noted)
    GltfMaterialMapping thin = mapGltfMaterial(in);
    EXPECT_TRUE(thin.material.thin);
    EXPECT_FALSE(thin.interior);
    ASSERT_EQ(thin.notes.size(), 1u);
    EXPECT_EQ(thin.notes[0].kind, "thin-walled volume");
    in.thickness = 0.2f;
    GltfMaterialMapping solid = mapGltfMaterial(in);
    EXPECT_FALSE(solid.material.thin);
    EXPECT_TRUE(solid.interior);
    EXPECT_TRUE(solid.notes.empty());
    // Rough and thin-walled: a thin rough sheet, nothing to note.
    in.hasVolume = false;
    in.roughness = 0.4f;
    GltfMaterialMapping rough = mapGltfMaterial(in);
    EXPECT_TRUE(rough.material.thin);
    EXPECT_TRUE(rough.material.isGlossy());
    EXPECT_TRUE(rough.notes.empty());
}

TEST(GltfMaterialMapping, MetalsBecomeSmoothOrGgxConductors) {
    GltfMaterialInput in = input("chrome");
    in.metallic = 1.0f;
    in.roughness = 0.0f;
    in.baseColor = Rgb(0.95f, 0.9f, 0.8f);
    GltfMaterialMapping smooth = mapGltfMaterial(in);
    EXPECT_EQ(smooth.material.type, MaterialType::Mirror);
    EXPECT_FLOAT_EQ(smooth.material.albedo.r, 0.95f);
    EXPECT_TRUE(smooth.notes.empty());
    EXPECT_FALSE(smooth.material.isGlossy());
    for (float r : {0.3f, 0.8f}) {
        in.roughness = r;
        GltfMaterialMapping brushed = mapGltfMaterial(in);
        EXPECT_EQ(brushed.material.type, MaterialType::Mirror);
        EXPECT_TRUE(brushed.material.isGlossy());
        EXPECT_FLOAT_EQ(brushed.material.roughness, r);
        EXPECT_TRUE(brushed.notes.empty()) << brushed.notes[0].message;
    }
}

TEST(GltfMaterialMapping, RoughTransmissionIsGgxGlass) {
    GltfMaterialInput in = input("frosted");
    in.transmission = 1.0f;
    in.roughness = 0.4f;
    in.hasVolume = true;
    in.thickness = 1.0f;
    GltfMaterialMapping m = mapGltfMaterial(in);
    EXPECT_EQ(m.material.type, MaterialType::Dielectric);
    EXPECT_TRUE(m.material.isGlossy());
    EXPECT_TRUE(m.notes.empty());
}

TEST(GltfMaterialMapping, DielectricPbrIsPlasticWithBaseColourIorRoughnessAndEmission) {
    GltfMaterialInput in = input("paint");
    in.metallic = 0.0f;
    in.roughness = 0.35f;
    in.ior = 1.4f;
    in.baseColor = Rgb(0.2f, 0.4f, 0.6f);
    in.emissive = Rgb(1.0f, 0.5f, 0.0f);
    in.emissiveStrength = 3.0f;
    GltfMaterialMapping m = mapGltfMaterial(in);
    EXPECT_EQ(m.material.type, MaterialType::Plastic);
    EXPECT_FALSE(m.material.hasMetalMix());
    EXPECT_TRUE(m.material.isRough());
    EXPECT_FLOAT_EQ(m.material.roughness, 0.35f);
    EXPECT_FLOAT_EQ(m.material.ior, 1.4f);  // KHR_materials_ior: the coat's index
    EXPECT_FLOAT_EQ(m.material.albedo.g, 0.4f);
    EXPECT_FLOAT_EQ(m.material.emission.r, 3.0f);
    EXPECT_FLOAT_EQ(m.material.emission.g, 1.5f);
    EXPECT_TRUE(m.notes.empty());
}

TEST(GltfMaterialMapping, MetallicBetweenZeroAndOneOrTexturedIsThePlasticMetalMix) {
    GltfMaterialInput in = input("worn brass");
    in.metallic = 0.6f;
    in.roughness = 0.5f;
    GltfMaterialMapping mix = mapGltfMaterial(in);
    EXPECT_EQ(mix.material.type, MaterialType::Plastic);
    EXPECT_TRUE(mix.material.hasMetalMix());
    EXPECT_FLOAT_EQ(mix.material.metallic, 0.6f);
    // metallic 1 is a pure conductor, unless a metallicRoughnessTexture's B makes it vary per point.
    in.metallic = 1.0f;
    EXPECT_EQ(mapGltfMaterial(in).material.type, MaterialType::Mirror);
    in.metallicRoughnessTexture = true;
    GltfMaterialMapping textured = mapGltfMaterial(in);
    EXPECT_EQ(textured.material.type, MaterialType::Plastic);
    EXPECT_FLOAT_EQ(textured.material.metallic, 1.0f);
    // Formerly metallic >= 0.5 was a Mirror and below a Lambertian diffuse.
    in.metallicRoughnessTexture = false;
    in.metallic = 0.49f;
    EXPECT_EQ(mapGltfMaterial(in).material.type, MaterialType::Plastic);
}

TEST(GltfMaterialMapping, ApproximationsAreNotedByKind) {
    GltfMaterialInput in = input("leaf");
    in.metallic = 0.0f;
    in.alphaMode = "MASK";
    in.textures = {"baseColorTexture", "normalTexture"};
    in.hasVolume = true;
    std::vector<std::string> kinds;
    for (const GltfNote& n : mapGltfMaterial(in).notes) {
        kinds.push_back(n.kind);
        EXPECT_EQ(n.message.rfind("m.gltf: material 'leaf' (index 0): ", 0), 0u) << n.message;
    }
    EXPECT_EQ(kinds, (std::vector<std::string>{"volume without transmission", "texture baseColorTexture",
                                               "texture normalTexture"}));
}

TEST(GltfMaterialMapping, PartialTransmissionIsAMixWithTheDiffuseBase) {
    GltfMaterialInput in = input("frosted");
    in.metallic = 0.0f;
    in.roughness = 0.0f;
    in.transmission = 0.3f;
    GltfMaterialMapping m = mapGltfMaterial(in);
    EXPECT_TRUE(m.notes.empty());
    EXPECT_EQ(m.material.type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(m.material.transmission, 0.3f);
    EXPECT_TRUE(m.material.isPartlyTransmissive());
    in.transmission = 1.0f;
    EXPECT_FALSE(mapGltfMaterial(in).material.isPartlyTransmissive());
}

TEST(GltfMaterialMapping, OutOfRangeValuesAreErrorsNamingTheMaterial) {
    auto err = [](const std::function<void(GltfMaterialInput&)>& edit) {
        GltfMaterialInput in = input("bad");
        edit(in);
        return test::errorOf([&] { mapGltfMaterial(in); });
    };
    const std::string at = "m.gltf: material 'bad' (index 0): ";
    EXPECT_EQ(err([](auto& in) { in.baseColor.g = -0.1f; }).rfind(at + "baseColorFactor", 0), 0u);
    EXPECT_EQ(err([](auto& in) { in.metallic = NAN; }).rfind(at + "metallicFactor", 0), 0u);
    EXPECT_EQ(err([](auto& in) { in.emissiveStrength = -1.0f; }).rfind(at + "KHR_materials_emissive_strength", 0), 0u);
    EXPECT_EQ(err([](auto& in) { in.ior = 0.5f; }).rfind(at + "KHR_materials_ior", 0), 0u);
    EXPECT_EQ(err([](auto& in) {
                  in.hasVolume = true, in.attenuationDistance = -2.0f;
              }).rfind(at + "KHR_materials_volume", 0),
              0u);
    EXPECT_EQ(
        err([](auto& in) { in.hasVolume = true, in.attenuationColor.r = 1.5f; }).rfind(at + "KHR_materials_volume", 0),
        0u);
    EXPECT_EQ(err([](auto&) {}), "");
}

}  // namespace
}  // namespace tyndall
