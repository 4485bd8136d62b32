// The scene format's "density" key (docs/scene-format.md): file grids with grid name, scale and
// transform, procedural grids, and one-line errors naming the JSON place (and the file and grid).
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/blackbody.h"
#include "loading/default_smoke_scene.h"
#include "loading/procedural_media.h"
#include "core/error.h"
#include "loading/scene_file.h"
#include "loading/vdb_grid.h"
#include "tests/scene/scene_test_util.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

using json = nlohmann::json;

std::string dir() {
    std::string d = test::outputDir() + "/scene-density";
    std::filesystem::create_directories(d);
    return d;
}

std::string write(const std::string& name, const std::string& text) {
    std::string path = dir() + "/" + name;
    std::ofstream(path) << text;
    return path;
}

/// A one-voxel grid named "smoke" (value 2 at index (0,0,0)) in the scene folder.
void writeOneVoxelGrid() {
    openvdb::initialize();
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName("smoke");
    g->tree().setValue(openvdb::Coord(0, 0, 0), 2.0f);
    openvdb::io::File(dir() + "/one-voxel.vdb").write({g});
}

json sceneWith(const json& density, const json& medium = {{"sigma_s", 1.0}, {"sigma_a", 0.2}}) {
    json j = json::parse(R"({
      "materials": [{"name": "white"}],
      "shapes": [{"type": "box", "name": "room", "material": "white", "min": [-3, -3, -3], "max": [3, 3, 3], "inward": true}],
      "lights": [{"type": "point", "position": [0, 2, 0], "intensity": 1}],
      "cameras": [{"position": [0, 0, 2.5], "target": [0, 0, 0]}],
      "global_medium": "smoke"
    })");
    json m = medium;
    m["name"] = "smoke";
    m["density"] = density;
    j["media"] = json::array({m});
    return j;
}

std::string errorOf(const std::string& name, const json& j) {
    try {
        loadSceneFile(write(name, j.dump()));
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(SceneDensity, FileGridWithNameScaleAndTransform) {
    writeOneVoxelGrid();
    json t = {{"scale", 0.5}, {"translate", {1, 0, 0}}};
    SceneFile f = loadSceneFile(
        write("file-grid.json",
              sceneWith({{"file", "one-voxel.vdb"}, {"grid", "smoke"}, {"scale", 3}, {"transform", t}}).dump()));
    const Medium& m = f.scene.media[f.scene.globalMedium];
    ASSERT_FALSE(m.homogeneous());
    // Voxel (0,0,0) lands at x = 1 (scaled by 0.5, moved by 1); value 2 x scale 3.
    EXPECT_NEAR(m.density->density(Vec3(1, 0, 0)), 6.0f, 1e-5f);
    EXPECT_NEAR(m.density->density(Vec3(1.25f, 0, 0)), 3.0f, 1e-5f);  // half a (scaled) voxel away
    EXPECT_EQ(m.density->density(Vec3(0, 0, 0)), 0.0f);
}

TEST(SceneDensity, ProceduralSmokeFileMatchesTheBuiltInSmokeScene) {
    SceneFile f = loadSceneFile(std::string(TYNDALL_SOURCE_DIR) + "/scenes/caustic-box-smoke.json");
    Scene builtIn = makeDefaultSmokeScene();
    const Medium& a = f.scene.media[f.scene.globalMedium];
    const Medium& b = builtIn.media[builtIn.globalMedium];
    EXPECT_EQ(a.sigmaS.r, b.sigmaS.r);
    EXPECT_EQ(a.sigmaA.b, b.sigmaA.b);
    EXPECT_EQ(a.g, b.g);
    ASSERT_FALSE(a.homogeneous());
    EXPECT_EQ(a.density->meanDensity(), b.density->meanDensity());
    EXPECT_EQ(a.density->maxDensity(), b.density->maxDensity());
    for (Vec3 p : {Vec3(0.45f, 1.0f, -1.3f), Vec3(0.2f, 2.0f, -1.0f), Vec3(0.7f, 0.5f, -1.5f)})
        EXPECT_EQ(a.density->density(p), b.density->density(p));
    test::expectSameScene(f.scene, builtIn, 1e-6f);  // everything else: materials, meshes, lights, camera
}

TEST(SceneDensity, ProceduralRollingFogWithScale) {
    json d = {{"procedural", "rolling_fog"}, {"min", {-3, -3, -3}}, {"max", {3, 0, 3}}, {"scale", 2}, {"seed", 5}};
    SceneFile f = loadSceneFile(write("fog.json", sceneWith(d).dump()));
    const DensityGrid& g = *f.scene.media[0].density;
    EXPECT_GT(g.maxDensity(), 1.0f);  // scaled past 1
    EXPECT_LE(g.maxDensity(), 2.0f);
    EXPECT_GT(g.density(Vec3(0, -2.9f, 0)) + g.density(Vec3(1, -2.9f, 1)) + g.density(Vec3(-1, -2.9f, 2)), 0.0f);
}

// "procedural": "fire": its density and, for the emission, its "temperature" grid (kelvin) through
// a blackbody; the medium emits in the flames and not away from them.
TEST(SceneDensity, ProceduralFireEmitsFromItsTemperatureGrid) {
    json d = {{"procedural", "fire"}, {"base", {0, -3, 0}}, {"voxel_size", 0.05}, {"temperature", 2000}};
    json m = {{"sigma_s", 1.0}, {"sigma_a", 0.5}, {"emission", {{"grid", "temperature"}, {"blackbody", true}, {"scale", 3}}}};
    SceneFile f = loadSceneFile(write("fire.json", sceneWith(d, m).dump()));
    const Medium& fire = f.scene.media[0];
    ASSERT_TRUE(fire.emissive());
    ASSERT_TRUE(fire.emissionField);
    // The same grids as built directly.
    ProceduralFire p;
    p.base = Vec3(0, -3, 0);
    p.voxelSize = 0.05f;
    p.temperature = 2000;
    const FireGrids g = makeProceduralFire(p);
    int glowing = 0;
    for (float y = -2.95f; y < -1.0f; y += 0.05f)
        for (float x = -0.4f; x <= 0.4f; x += 0.05f) {
            const Vec3 at(x, y, 0.02f);
            ASSERT_EQ(fire.density->density(at), g.density->density(at));
            const Rgb expected = blackbodyRgb(g.temperature->density(at)) * 3.0f * 0.5f * g.density->density(at);
            const Rgb got = fire.sourceAt(at);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], expected[c], 1e-4f * expected.maxComponent() + 1e-12f);
            glowing += got.r > 0;
        }
    EXPECT_GT(glowing, 20);
    EXPECT_TRUE(fire.sourceAt(Vec3(0, 2.5f, 0)).isBlack()) << "far above the fire";
    EXPECT_TRUE(fire.sourceAt(Vec3(2, -2.9f, 2)).isBlack()) << "beside the fire";
}

TEST(SceneDensity, ErrorsNameThePlace) {
    writeOneVoxelGrid();
    struct Case {
        const char* name;
        json scene;
        const char* place;
        const char* what;
    };
    const Case cases[] = {
        {"missing-file", sceneWith({{"file", "nope.vdb"}}), "/media/0/density/file", "no such file"},
        {"missing-grid", sceneWith({{"file", "one-voxel.vdb"}, {"grid", "density"}}), "/media/0/density/file",
         "no grid named 'density' (grids in the file: 'smoke' (float))"},
        {"neither", sceneWith(json::object()), "/media/0/density", "exactly one of 'file'"},
        {"both", sceneWith({{"file", "one-voxel.vdb"}, {"procedural", "smoke"}}), "/media/0/density", "exactly one"},
        {"unknown-kind", sceneWith({{"procedural", "clouds"}}), "/media/0/density/procedural", "\"rolling_fog\""},
        {"transform-on-procedural", sceneWith({{"procedural", "smoke"}, {"transform", {{"scale", 2}}}}),
         "/media/0/density", "apply to file grids"},
        {"typo", sceneWith({{"procedural", "smoke"}, {"hieght", 2}}), "/media/0/density", "hieght"},
        {"negative-scale", sceneWith({{"procedural", "smoke"}, {"scale", -1}}), "/media/0/density/scale",
         "in [0, 1e+06]"},
        {"too-many-voxels", sceneWith({{"procedural", "rolling_fog"}, {"voxel_size", 0.001}}), "/media/0/density",
         "raise voxel_size"},
        // Hostile extents: the voxel count saturates instead of overflowing (into a small number).
        {"huge-fog-box",
         sceneWith({{"procedural", "rolling_fog"}, {"min", {-1e30, 0, -1e30}}, {"max", {1e30, 1, 1e30}}}),
         "/media/0/density", "raise voxel_size"},
        {"infinite-fog-box",
         sceneWith({{"procedural", "rolling_fog"}, {"min", {-3e38, 0, -3e38}}, {"max", {3e38, 1, 3e38}}}),
         "/media/0/density", "raise voxel_size"},
        {"huge-smoke", sceneWith({{"procedural", "smoke"}, {"height", 1e4}, {"top_radius", 1e4}, {"voxel_size", 1e-4}}),
         "/media/0/density", "raise voxel_size"},
        {"colour-extinction", sceneWith({{"procedural", "smoke"}}, {{"sigma_s", {1, 0.5, 0.2}}}), "/media/0",
         "grey extinction"},
        {"fire-flames-above-height", sceneWith({{"procedural", "fire"}, {"flame_height", 3}, {"height", 2}}),
         "/media/0/density/flame_height", "must not exceed 'height'"},
        {"fire-no-such-grid",
         sceneWith({{"procedural", "fire"}, {"voxel_size", 0.1}},
                   {{"sigma_s", 1.0}, {"sigma_a", 0.2}, {"emission", {{"grid", "heat"}, {"blackbody", true}}}}),
         "/media/0/emission/grid", "procedural fire has no grid named 'heat' (its grids: 'density', 'temperature')"},
        {"emission-grid-on-smoke",
         sceneWith({{"procedural", "smoke"}, {"voxel_size", 0.1}},
                   {{"sigma_s", 1.0}, {"sigma_a", 0.2}, {"emission", {{"grid", "temperature"}, {"blackbody", true}}}}),
         "/media/0/emission", "\"procedural\": \"fire\""},
        {"huge-fire", sceneWith({{"procedural", "fire"}, {"voxel_size", 1e-3}}), "/media/0/density", "raise voxel_size"},
    };
    for (const Case& c : cases) {
        std::string err = errorOf(std::string(c.name) + ".json", c.scene);
        SCOPED_TRACE(std::string(c.name) + ": " + err);
        ASSERT_FALSE(err.empty()) << "no error";
        EXPECT_NE(err.find(std::string(c.name) + ".json"), std::string::npos) << "names the scene file";
        EXPECT_NE(err.find(c.place), std::string::npos) << "names the place";
        EXPECT_NE(err.find(c.what), std::string::npos) << "says what";
        EXPECT_EQ(err.find('\n'), std::string::npos) << "one line";
    }
}

TEST(SceneDensity, ProceduralVoxelBudgetIsForTheWholeScene) {
    // Two fogs of 11^3 = 1331 voxels each: one fits a budget of 2000, the second does not.
    json fog = {{"procedural", "rolling_fog"}, {"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"voxel_size", 0.1}};
    json j = sceneWith(fog);
    SceneLoadOptions o;
    o.maxProceduralVoxels = 2000;
    EXPECT_NO_THROW(loadSceneFile(write("budget-one.json", j.dump()), o));
    json second = j["media"][0];
    second["name"] = "more smoke";
    j["media"].push_back(second);
    try {
        loadSceneFile(write("budget-two.json", j.dump()), o);
        FAIL() << "the second grid was built past the budget";
    } catch (const Error& e) {
        std::string err = e.what();
        EXPECT_NE(err.find("/media/1/density"), std::string::npos) << err;
        EXPECT_NE(err.find("1331 voxels (after 1331 in this scene's other grids): at most 2000"), std::string::npos)
            << err;
    }
}

TEST(SceneDensity, ExternalFilesCanBeDisabled) {
    writeOneVoxelGrid();
    SceneLoadOptions o;
    o.allowExternalFiles = false;
    try {
        loadSceneFile(write("no-external.json", sceneWith({{"file", "one-voxel.vdb"}}).dump()), o);
        FAIL() << "an external grid file was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("disabled"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace tyndall
