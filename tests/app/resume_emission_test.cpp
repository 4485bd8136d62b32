// A resume refuses a scene whose emission changed, as it refuses other scene changes, including a
// change the scene file does not show: the VDB's temperature grid rewritten behind an unchanged
// scene file, or the emission's own coefficients (sceneHash, app/render_checkpoint.h). A resume
// of the unchanged scene is accepted, so the refusals are not a hash that never matches.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/render_checkpoint.h"
#include "core/grid_emission.h"
#include "loading/vdb_grid.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace tyndall {
namespace {

namespace fs = std::filesystem;
using test::runTyndall;

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// fire.vdb: "density" 1 and "temperature" `kelvin` on a 6^3 block of voxels of 0.1.
void writeFire(const std::string& path, float kelvin) {
    openvdb::initialize();
    auto density = openvdb::FloatGrid::create(0.0f);
    density->setName("density");
    density->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    auto temperature = openvdb::FloatGrid::create(0.0f);
    temperature->setName("temperature");
    temperature->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
    for (int k = 0; k < 6; ++k)
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 6; ++i) {
                density->tree().setValue(openvdb::Coord(i, j, k), 1.0f);
                temperature->tree().setValue(openvdb::Coord(i, j, k), kelvin);
            }
    openvdb::io::File(path).write({density, temperature});
}

constexpr const char* kScene = R"({
  "materials": [{"name": "white"}],
  "shapes": [{"type": "box", "name": "room", "material": "white", "min": [-1, -1, -1], "max": [1.5, 1.5, 1.5], "inward": true}],
  "cameras": [{"position": [0.25, 0.25, 1.4], "target": [0.25, 0.25, 0.25]}],
  "media": [{"name": "fire", "sigma_s": 1.0, "sigma_a": 3.0,
             "density": {"file": "fire.vdb"},
             "emission": {"grid": "temperature", "blackbody": true, "scale": 2}}],
  "global_medium": "fire"
})";

TEST(ResumeEmission, ATemperatureGridRewrittenBehindTheSceneIsRefused) {
    const std::string d = test::outputDir() + "/resume-emission";
    fs::remove_all(d);
    fs::create_directories(d);
    writeFire(d + "/fire.vdb", 2500.0f);
    std::ofstream(d + "/fire.json") << kScene;
    const std::string ck = d + "/r.ckpt";
    auto r = runTyndall("render " + d + "/fire.json --size 24x16 --photons 200 --passes 2 --threads 1 --gpu off -q -o " +
                        d + "/a.exr --checkpoint " + ck);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string good = readBytes(ck);

    // Unchanged: the resume goes on.
    r = runTyndall("render --resume " + ck + " --passes 3 -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;

    // The temperature rewritten (the density and the scene file as they were): refused, untouched.
    const std::string now = readBytes(ck);
    writeFire(d + "/fire.vdb", 3000.0f);
    r = runTyndall("render --resume " + ck + " --passes 4 -q");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("different scene"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_TRUE(readBytes(ck) == now) << "a refused resume must not touch the checkpoint";
    EXPECT_FALSE(good.empty());
}

/// sceneHash itself, on scenes built in memory (no scene file): each emission parameter counts.
TEST(ResumeEmission, SceneHashSeesEveryEmissionParameter) {
    Scene base;
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.5f);
    fog.sigmaA = Rgb(0.5f);
    base.media.push_back(fog);
    base.globalMedium = 0;
    const uint64_t h0 = app::sceneHash("", base);
    EXPECT_EQ(app::sceneHash("", base), h0) << "the hash is a function of the scene";

    Scene glowing = base;
    glowing.media[0].emission = Rgb(0.0f, 0.0f, 1e-3f);
    EXPECT_NE(app::sceneHash("", glowing), h0) << "homogeneous emission";
    Scene forward = base;
    forward.media[0].g = 0.3f;
    EXPECT_NE(app::sceneHash("", forward), h0) << "the phase function";

    // A grid medium with a temperature field: its scale, its temperature mapping and the field's
    // presence each change the hash.
    const int dims[3] = {4, 4, 4};
    std::vector<float> ones(64, 1.0f), hot(64, 2000.0f);
    auto grid = VdbDensityGrid::fromDense(dims, ones, Affine3::scaleTranslate(Vec3(0.25f), Vec3(0.0f)), "block");
    auto temperature = VdbDensityGrid::fromDense(dims, hot, Affine3::scaleTranslate(Vec3(0.25f), Vec3(0.0f)), "T");
    Scene smoke = base;
    smoke.media[0].density = grid;
    const uint64_t hs = app::sceneHash("", smoke);
    auto withField = [&](float scale, float temperatureScale) {
        Scene s = smoke;
        GridEmission::Blackbody bb;
        bb.scale = scale;
        bb.temperatureScale = temperatureScale;
        s.media[0].emissionField = std::make_shared<GridEmission>(temperature, bb);
        return app::sceneHash("", s);
    };
    const uint64_t hf = withField(1.0f, 1.0f);
    EXPECT_NE(hf, hs) << "the emission field";
    EXPECT_EQ(withField(1.0f, 1.0f), hf);
    EXPECT_NE(withField(2.0f, 1.0f), hf) << "the emission scale";
    EXPECT_NE(withField(1.0f, 1.5f), hf) << "the temperature scale";
}

}  // namespace
}  // namespace tyndall
