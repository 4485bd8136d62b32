// A resume refuses a scene whose emission changed, as it refuses other scene changes, including a
// change the scene file does not show: one voxel of the VDB's temperature grid rewritten behind an
// unchanged scene file, a density grid with two voxels changed and its mass and maximum kept, or
// the emission's own coefficients (sceneHash, app/render_checkpoint.h). A resume of the unchanged
// scene is accepted, so the refusals are not a hash that never matches.
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
#include "tests/vdb/block_grids.h"
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

/// Edge of the fire's block of voxels. 47 voxels and their one-voxel border span 48: a 16^3
/// lattice of sample points over the grid's bounds sits at index 0.5 + 3i, so no sample reads
/// voxel (2, 2, 2) (each stencil reaches one voxel): a change there is invisible to sampling.
constexpr int kFireVoxels = 47;

/// fire.vdb: "density" 1 and "temperature" 2500 K on a kFireVoxels^3 block of voxels 0.6 wide,
/// voxel (2, 2, 2) at `corner` kelvin.
void writeFire(const std::string& path, float corner) {
    const double voxel = 0.6 / kFireVoxels;
    auto temperature = test::blockGrid("temperature", voxel, 0, kFireVoxels - 1, 2500.0f);
    temperature->tree().setValue(openvdb::Coord(2, 2, 2), corner);
    openvdb::io::File(path).write({test::blockGrid("density", voxel, 0, kFireVoxels - 1, 1.0f), temperature});
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

TEST(ResumeEmission, OneTemperatureVoxelRewrittenBehindTheSceneIsRefused) {
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

    // One temperature voxel of 110,592 rewritten (the density and the scene file as they were):
    // refused, the checkpoint untouched.
    const std::string now = readBytes(ck);
    writeFire(d + "/fire.vdb", 3500.0f);
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

/// One voxel, or two with the grid's mass and maximum kept, where no sampling lattice looks.
TEST(ResumeEmission, SceneHashSeesOneVoxel) {
    const int n = kFireVoxels, dims[3] = {n, n, n};
    std::vector<float> values(size_t(n) * n * n, 1.0f);
    values[size_t(40 + n * (40 + n * 40))] = 2.0f;  // the maximum, away from the voxels changed
    auto hashOf = [&](const std::vector<float>& v) {
        Scene s;
        Medium smoke;
        smoke.name = "smoke";
        smoke.density = VdbDensityGrid::fromDense(dims, v, Affine3::scaleTranslate(Vec3(0.6f / n), Vec3(0.0f)), "b");
        s.media.push_back(smoke);
        s.globalMedium = 0;
        return app::sceneHash("", s);
    };
    const uint64_t h = hashOf(values);
    EXPECT_EQ(hashOf(values), h);
    std::vector<float> moved = values;
    moved[size_t(2 + n * (2 + n * 2))] = 1.5f;  // voxel (2, 2, 2)
    moved[size_t(2 + n * (5 + n * 2))] = 0.5f;  // voxel (2, 5, 2)
    EXPECT_NE(hashOf(moved), h) << "two voxels changed, mass and maximum kept";
    std::vector<float> one = values;
    one[size_t(2 + n * (2 + n * 2))] = 1.0f + 1e-6f;
    EXPECT_NE(hashOf(one), h) << "one voxel, by one part in a million";
}

}  // namespace
}  // namespace tyndall
