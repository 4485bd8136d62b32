// The scene format's "emission" key (docs/scene-format.md, loading/scene_emission.cpp): constant
// Le, an emission grid with colour and scale, a temperature grid through a blackbody, each read
// from the density's file through its transform (another resolution and voxel size than the
// density's), and bad input: one-line errors naming the JSON place, or the stated behaviour
// (negative voxels read as 0), never NaN.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/blackbody.h"
#include "core/error.h"
#include "loading/scene_file.h"
#include "tests/test_util.h"
#include "tests/vdb/block_grids.h"

namespace tyndall {
namespace {

using json = nlohmann::json;

std::string dir() {
    std::string d = test::outputDir() + "/scene-emission";
    std::filesystem::create_directories(d);
    return d;
}

/// fire.vdb: "density" 1 on voxels of 0.1 over index 0..9 (world [0, 0.9]^3); "temperature" on
/// voxels of 0.2 (another resolution) holding 2000 except one voxel of -50; "flames" 0.5 on voxels
/// of 0.1; "velocity" a vec3 grid; "heat_level_set" a level set.
void writeFireFile() {
    auto density = test::blockGrid("density", 0.1, 0, 9, 1.0f);
    auto temperature = test::blockGrid("temperature", 0.2, -1, 6, 2000.0f);
    temperature->tree().setValue(openvdb::Coord(0, 0, 0), -50.0f);
    auto flames = test::blockGrid("flames", 0.1, 0, 9, 0.5f);
    auto velocity = openvdb::Vec3SGrid::create();
    velocity->setName("velocity");
    velocity->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 0, 0));
    auto ls = openvdb::FloatGrid::create(0.1f);
    ls->setName("heat_level_set");
    ls->setGridClass(openvdb::GRID_LEVEL_SET);
    openvdb::io::File(dir() + "/fire.vdb").write({density, temperature, flames, velocity, ls});
}

json sceneWith(const json& emission, const json& medium = {{"sigma_s", 1.0}, {"sigma_a", 0.5}},
               bool withDensity = true) {
    json j = json::parse(R"({
      "materials": [{"name": "white"}],
      "shapes": [{"type": "box", "name": "room", "material": "white", "min": [-3, -3, -3], "max": [3, 3, 3], "inward": true}],
      "cameras": [{"position": [0, 0, 2.5], "target": [0, 0, 0]}],
      "global_medium": "fire"
    })");
    json m = medium;
    m["name"] = "fire";
    if (withDensity) m["density"] = {{"file", "fire.vdb"}, {"transform", {{"translate", {1, 0, 0}}}}};
    if (!emission.is_null()) m["emission"] = emission;
    j["media"] = json::array({m});
    return j;
}

SceneFile load(const std::string& name, const json& j) {
    const std::string path = dir() + "/" + name;
    std::ofstream(path) << j.dump();
    return loadSceneFile(path);
}

std::string errorOf(const std::string& name, const json& j) {
    try {
        load(name, j);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SceneEmission, ConstantGridAndBlackbodyEmission) {
    writeFireFile();
    // Constant Le on a homogeneous medium, no light needed.
    json hom = sceneWith({1, 0.5, 0.25}, {{"sigma_s", 0.2}, {"sigma_a", 0.5}}, false);
    SceneFile h = load("constant.json", hom);
    const Medium& hm = h.scene.media[0];
    EXPECT_TRUE(hm.emissive());
    EXPECT_EQ(hm.emission.g, 0.5f);
    EXPECT_EQ(hm.sourceAt(Vec3(0.0f)).r, 0.5f);

    // An emission grid: Le = scale x color x flames, through the density's transform (+1 in x).
    SceneFile g = load("flames.json", sceneWith({{"grid", "flames"}, {"color", {1, 0.5, 0.25}}, {"scale", 4}}));
    const Medium& gm = g.scene.media[0];
    ASSERT_TRUE(gm.emissionField);
    const Vec3 inside(1.45f, 0.45f, 0.45f), outside(0.45f, 0.45f, 0.45f);
    EXPECT_NEAR(gm.emissionAt(inside).r, 4 * 0.5f, 1e-5f);
    EXPECT_NEAR(gm.emissionAt(inside).b, 4 * 0.5f * 0.25f, 1e-5f);
    EXPECT_NEAR(gm.sourceAt(inside).g, 0.5f * 1.0f * 1.0f, 1e-5f);  // sigma_a x density x Le
    EXPECT_TRUE(gm.sourceAt(outside).isBlack());

    // Temperature through a blackbody, on voxels twice the density's: (T - t0) x k kelvin.
    SceneFile b = load("blackbody.json", sceneWith({{"grid", "temperature"},
                                                   {"blackbody", true},
                                                   {"scale", 3},
                                                   {"temperature_scale", 1.5},
                                                   {"temperature_offset", 100}}));
    const Medium& bm = b.scene.media[0];
    const Rgb le = bm.emissionAt(Vec3(1.5f, 0.5f, 0.5f));
    const Rgb expected = blackbodyRgb((2000 - 100) * 1.5f) * 3.0f;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(le[c], expected[c], 1e-4f * expected.maxComponent());
    // The negative voxel reads as 0 (its neighbourhood blends towards it), never negative or NaN.
    const Vec3 corner = Vec3(1.0f, 0.0f, 0.0f);
    const Rgb atCorner = bm.emissionAt(corner);
    EXPECT_TRUE(isFinite(atCorner));
    EXPECT_GE(atCorner.r, 0.0f);
    EXPECT_NEAR(atCorner.r, (blackbodyRgb((0 - 100) * 1.5f) * 3.0f).r, 1e-6f);  // T = -150 K: nothing
}

/// ambient.vdb: "density" 1 on index 0..4 of voxels of 0.1 (world [0, 0.4]^3); "temperature" of
/// background 1500 (an ambient temperature) with 3000 on index 0..1 and 1000 (below the
/// background) at index 3, on the same voxels.
void writeAmbientFile() {
    auto density = test::blockGrid("density", 0.1, 0, 4, 1.0f);
    auto temperature = test::blockGrid("temperature", 0.1, 0, 1, 3000.0f, 1500.0f);
    temperature->tree().setValue(openvdb::Coord(3, 3, 3), 1000.0f);
    openvdb::io::File(dir() + "/ambient.vdb").write({density, temperature});
}

// A temperature grid whose background is positive (an ambient temperature) loads; the ambient
// temperature is the field's value away from its voxels, but the medium emits only where its
// density is: nothing anywhere else in the temperature grid's (unbounded) domain.
TEST(SceneEmission, APositiveBackgroundIsAnAmbientValueAndEmitsOnlyInTheDensity) {
    writeAmbientFile();
    json j = sceneWith({{"grid", "temperature"}, {"blackbody", true}, {"scale", 2}});
    j["media"][0]["density"] = {{"file", "ambient.vdb"}};
    SceneFile f = load("ambient.json", j);
    const Medium& m = f.scene.media[0];
    const Rgb hot = blackbodyRgb(3000.0f) * 2.0f, ambient = blackbodyRgb(1500.0f) * 2.0f;
    ASSERT_GT(ambient.maxComponent(), 0.0f) << "the ambient temperature must glow for the test to mean anything";
    auto expectNear = [](const Rgb& a, const Rgb& b, const char* what) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-4f * b.maxComponent() + 1e-9f) << what << " channel " << c;
    };
    // In the density: the hot voxels, the ambient elsewhere, and a voxel below the ambient reads as it.
    expectNear(m.sourceAt(Vec3(0.05f, 0.05f, 0.05f)), hot * 0.5f, "hot voxels");  // sigma_a 0.5 x density 1
    expectNear(m.sourceAt(Vec3(0.25f, 0.25f, 0.05f)), ambient * 0.5f, "ambient in the density");
    expectNear(m.sourceAt(Vec3(0.3f, 0.3f, 0.3f)), ambient * 0.5f, "a voxel below the ambient");
    // Out of the density, near and far, the source is zero though Le is the ambient's.
    for (const Vec3& p : {Vec3(0.7f, 0.2f, 0.2f), Vec3(-2.0f, 1.0f, 2.5f), Vec3(2.9f, -2.9f, 0.0f)}) {
        expectNear(m.emissionAt(p), ambient, "Le away from the voxels");
        EXPECT_TRUE(m.sourceAt(p).isBlack()) << "emits outside the density at " << p.x << " " << p.y << " " << p.z;
    }
}

TEST(SceneEmission, BadInputIsAOneLineErrorNamingThePlace) {
    writeFireFile();
    struct Case {
        const char* name;
        json scene;
        std::vector<std::string> expect;
    };
    const Case cases[] = {
        {"missing-grid", sceneWith({{"grid", "heat"}, {"blackbody", true}}),
         {"/media/0/emission/grid", "no grid named 'heat'", "'temperature' (float)", "'velocity' (vec3s)"}},
        {"vector-grid", sceneWith({{"grid", "velocity"}}), {"/media/0/emission/grid", "holds vec3s values"}},
        {"level-set", sceneWith({{"grid", "heat_level_set"}, {"blackbody", true}}), {"level set"}},
        {"no-absorption", sceneWith({{"grid", "flames"}}, {{"sigma_s", 1.0}, {"sigma_a", 0.0}}),
         {"/media/0/emission", "sigma_a = 0"}},
        {"no-density-file", sceneWith({{"grid", "flames"}}, {{"sigma_s", 1.0}, {"sigma_a", 0.5}}, false),
         {"/media/0/emission", "density"}},
        {"color-with-blackbody", sceneWith({{"grid", "temperature"}, {"blackbody", true}, {"color", {1, 0, 0}}}),
         {"/media/0/emission/color", "without \"blackbody\""}},
        {"temperature-without-blackbody", sceneWith({{"grid", "flames"}, {"temperature_scale", 2}}),
         {"/media/0/emission/temperature_scale", "applies to \"blackbody\": true"}},
        {"negative-emission", sceneWith({1, -1, 0}), {"/media/0/emission"}},
        {"negative-scale", sceneWith({{"grid", "flames"}, {"scale", -2}}), {"/media/0/emission/scale"}},
        {"nan-offset", sceneWith({{"grid", "temperature"}, {"blackbody", true}, {"temperature_offset", "hot"}}),
         {"/media/0/emission/temperature_offset"}},
        {"misspelt-key", sceneWith({{"grid", "flames"}, {"colour", {1, 1, 1}}}), {"/media/0/emission", "colour"}},
        {"grid-not-a-string", sceneWith({{"grid", 3}}), {"/media/0/emission/grid"}},
    };
    for (const Case& c : cases) {
        const std::string e = errorOf(std::string(c.name) + ".json", c.scene);
        ASSERT_FALSE(e.empty()) << c.name << ": no error";
        EXPECT_EQ(e.find('\n'), std::string::npos) << c.name << ": " << e;
        for (const std::string& part : c.expect) EXPECT_NE(e.find(part), std::string::npos) << c.name << ": " << e;
    }
}

}  // namespace
}  // namespace tyndall
