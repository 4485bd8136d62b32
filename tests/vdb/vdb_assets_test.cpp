// Real OpenVDB files from ../shared/assets/vdb (skipped with a message when absent): each file's
// grid selection, its transform checked voxel by voxel against OpenVDB's own indexToWorld, world
// bounds, the edge cases (empty grids, non-float grids, a grid not named "density"), and a render
// of the real smoke plume, and the density-and-heat file rendered as fire.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/blackbody.h"
#include "core/error.h"
#include "loading/scene_file.h"
#include "loading/vdb_grid.h"
#include "tests/test_util.h"
#include "tests/vdb/grid_scenes.h"

namespace tyndall {
namespace {

std::string assetPath(const std::string& rel) {
    return test::assetsDir() + "/vdb/" + rel;
}

#define REQUIRE_ASSET(path) \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "asset " << (path) << " absent (../shared/assets)"

VdbGridSource source(const std::string& file, const std::string& grid = "") {
    VdbGridSource s;
    s.file = file;
    s.grid = grid;
    return s;
}

std::string loadError(const VdbGridSource& src) {
    try {
        VdbDensityGrid::load(src);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

/// The grid as OpenVDB reads it, for independent reference values.
openvdb::FloatGrid::Ptr readWithOpenVdb(const std::string& path, const std::string& name) {
    openvdb::initialize();
    openvdb::io::File f(path);
    f.open(false);
    auto g = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid(name));
    f.close();
    return g;
}

/// Our density at the world position OpenVDB gives each active voxel's centre equals that voxel's
/// value (times the scale, through the scene transform `xf`), for every active voxel.
void expectVoxelCentresMatch(const VdbDensityGrid& grid, const openvdb::FloatGrid& ref, const Affine3& xf,
                             float scale) {
    uint64_t n = 0;
    for (auto it = ref.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue()) continue;
        openvdb::Vec3d w = ref.indexToWorld(it.getCoord());
        Vec3 p = xf.point(Vec3(float(w.x()), float(w.y()), float(w.z())));
        ASSERT_NEAR(grid.density(p), std::max(*it, 0.0f) * scale, 2e-4f * (1.0f + *it * scale))
            << grid.label() << " voxel " << it.getCoord();
        ++n;
    }
    EXPECT_EQ(n, ref.activeVoxelCount());
}

/// World bounds = OpenVDB's active-voxel box widened by one voxel (trilinear support), mapped.
Bounds3 expectedBounds(const openvdb::FloatGrid& ref, const Affine3& xf) {
    openvdb::CoordBBox b = ref.evalActiveVoxelBoundingBox();
    Bounds3 out;
    for (int c = 0; c < 8; ++c) {
        openvdb::Vec3d idx((c & 1) ? b.max().x() + 1 : b.min().x() - 1, (c & 2) ? b.max().y() + 1 : b.min().y() - 1,
                           (c & 4) ? b.max().z() + 1 : b.min().z() - 1);
        openvdb::Vec3d w = ref.indexToWorld(idx);
        out.extend(xf.point(Vec3(float(w.x()), float(w.y()), float(w.z()))));
    }
    return out;
}

void expectBoundsNear(const Bounds3& a, const Bounds3& b, float tol) {
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(a.lo[i], b.lo[i], tol) << "axis " << i;
        EXPECT_NEAR(a.hi[i], b.hi[i], tol) << "axis " << i;
    }
}

TEST(VdbAssets, Smoke000002LoadsWithItsTransform) {
    const std::string path = assetPath("openusd/smoke_000002.vdb");
    REQUIRE_ASSET(path);
    auto grid = VdbDensityGrid::load(source(path));
    EXPECT_EQ(grid->gridName(), "density");
    auto ref = readWithOpenVdb(path, "density");
    EXPECT_EQ(grid->activeVoxelCount(), ref->activeVoxelCount());
    float mx = 0;
    for (auto it = ref->cbeginValueOn(); it; ++it) mx = std::max(mx, *it);
    EXPECT_FLOAT_EQ(grid->maxDensity(), mx);
    EXPECT_GT(grid->meanDensity(), 0.0f);
    EXPECT_LT(grid->meanDensity(), mx);
    expectBoundsNear(grid->bounds(), expectedBounds(*ref, Affine3()), 1e-4f);
    expectVoxelCentresMatch(*grid, *ref, Affine3(), 1.0f);
}

TEST(VdbAssets, DensityAndHeatKeepsItsAnisotropicTransform) {
    const std::string path = assetPath("openusd/densityAndHeat.vdb");
    REQUIRE_ASSET(path);
    auto grid = VdbDensityGrid::load(source(path));  // "density" (no grid class), not "heat"
    EXPECT_EQ(grid->gridName(), "density");
    auto ref = readWithOpenVdb(path, "density");
    openvdb::Vec3d voxel = ref->voxelSize();
    ASSERT_NE(voxel.x(), voxel.z()) << "the asset is expected to have anisotropic voxels";
    // Index-to-world is the file's own: columns of the linear part are the voxel sizes.
    const Affine3& m = grid->indexToWorld();
    EXPECT_NEAR(m.m[0][0], voxel.x(), 1e-6);
    EXPECT_NEAR(m.m[2][2], voxel.z(), 1e-6);
    // World bounds, by hand from the file's active box [1,1,31]-[23,23,72], voxel 0.703377 x
    // 0.703377 x 0.716455, origin (-8.440519, -8.440519, -24.134912), widened by one voxel.
    Bounds3 hand{{0 * 0.703377f - 8.440519f, 0 * 0.703377f - 8.440519f, 30 * 0.716455f - 24.134912f},
                 {24 * 0.703377f - 8.440519f, 24 * 0.703377f - 8.440519f, 73 * 0.716455f - 24.134912f}};
    expectBoundsNear(grid->bounds(), expectedBounds(*ref, Affine3()), 1e-4f);
    expectBoundsNear(grid->bounds(), hand, 1e-3f);
    expectVoxelCentresMatch(*grid, *ref, Affine3(), 1.0f);

    // Composed with a scene transform (rotation about x, uniform scale, translation) and a scale.
    Affine3 xf;
    xf.m[0][0] = 0.1f;
    xf.m[1][1] = 0.0f, xf.m[1][2] = 0.1f;
    xf.m[2][1] = -0.1f, xf.m[2][2] = 0.0f;
    xf.m[0][3] = 1.0f, xf.m[1][3] = 2.0f, xf.m[2][3] = -3.0f;
    VdbGridSource src = source(path);
    src.transform = xf;
    src.scale = 2.5f;
    auto moved = VdbDensityGrid::load(src);
    expectBoundsNear(moved->bounds(), expectedBounds(*ref, xf), 1e-4f);
    expectVoxelCentresMatch(*moved, *ref, xf, 2.5f);
    EXPECT_NEAR(moved->maxDensity(), 2.5f * grid->maxDensity(), 1e-5f);
}

TEST(VdbAssets, Torus01NeedsItsGridName) {
    const std::string path = assetPath("arnold-usd/torus01.vdb");
    REQUIRE_ASSET(path);
    std::string msg = loadError(source(path, "density"));
    EXPECT_NE(msg.find("no grid named 'density'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("voxel_fog_density"), std::string::npos) << "the error lists the grids: " << msg;

    auto grid = VdbDensityGrid::load(source(path, "voxel_fog_density"));
    auto ref = readWithOpenVdb(path, "voxel_fog_density");
    EXPECT_EQ(grid->activeVoxelCount(), 2450u);
    EXPECT_FLOAT_EQ(grid->maxDensity(), 100.0f);  // large densities: the majorant must follow
    EXPECT_GE(grid->majorantGrid()->maxValue(), 100.0f);
    EXPECT_LT(grid->bounds().lo.x, 0.0f);  // negative index coordinates
    expectBoundsNear(grid->bounds(), expectedBounds(*ref, Affine3()), 1e-4f);
    expectVoxelCentresMatch(*grid, *ref, Affine3(), 1.0f);
    // Without a name the first float grid is used, which here is the same one.
    EXPECT_EQ(VdbDensityGrid::load(source(path))->gridName(), "voxel_fog_density");
}

TEST(VdbAssets, Smoke000001EmptyAndNonFloatGrids) {
    const std::string path = assetPath("openusd/smoke_000001.vdb");
    REQUIRE_ASSET(path);
    auto empty = VdbDensityGrid::load(source(path));  // "density": float, no voxels
    EXPECT_EQ(empty->gridName(), "density");
    EXPECT_TRUE(empty->bounds().empty());
    EXPECT_EQ(empty->maxDensity(), 0.0f);
    EXPECT_EQ(empty->density(Vec3(0.0f)), 0.0f);
    std::string velocity = loadError(source(path, "velocity"));
    EXPECT_NE(velocity.find("holds vec3s values"), std::string::npos) << velocity;
    std::string obstacles = loadError(source(path, "obstacles"));
    EXPECT_NE(obstacles.find("holds int32 values"), std::string::npos) << obstacles;

    // The empty medium renders as clear air: bit for bit the image of the same room with no
    // medium at all (same seed). Finite-but-wrong (a stray scattering event, a transmittance
    // below one, a photon path whose random numbers shift) would differ.
    Medium m;
    m.sigmaS = Rgb(2.0f);
    m.sigmaA = Rgb(0.2f);
    m.density = empty;
    test::GridRoom room;
    room.wallAlbedo = Rgb(0.5f);
    Scene scene = test::makeGridRoomScene(room, m, "empty smoke");
    Scene clearAir = scene;
    clearAir.media.clear();
    clearAir.globalMedium = kVacuum;
    for (TriangleMesh& mesh : clearAir.meshes) mesh.interiorMedium = mesh.exteriorMedium = kVacuum;
    clearAir.validate();
    RenderSettings s;
    s.width = s.height = 24;
    s.photonsPerPass = 200;
    Image withEmpty = test::renderPasses(scene, s, 2).mean();
    Image without = test::renderPasses(clearAir, s, 2).mean();
    for (const Rgb& c : withEmpty.pixels) ASSERT_TRUE(isFinite(c));
    double sum = 0;
    for (const Rgb& c : without.pixels) sum += c.luminance();
    ASSERT_GT(sum, 0.0) << "the room is dark: the comparison would be empty";
    EXPECT_TRUE(test::identicalImages(withEmpty, without)) << "an empty density grid is not clear air";
}

TEST(VdbAssets, Smoke000002Renders) {
    const std::string path = assetPath("openusd/smoke_000002.vdb");
    REQUIRE_ASSET(path);
    Scene scene = test::makeSmoke000002Room(path);
    Medium smoke = scene.media[0];
    test::GridRoom room = test::smoke000002Room();
    EXPECT_NEAR(smoke.density->bounds().lo.y, 0.05f, 1e-4f);
    Medium clear = smoke;
    clear.density.reset();
    clear.sigmaS = clear.sigmaA = Rgb(0.0f);
    Scene empty = test::makeGridRoomScene(room, clear, "empty room");

    RenderSettings s;
    s.width = s.height = 64;
    s.photonsPerPass = 2000;
    const int passes = 6;
    Image withSmoke = test::renderPasses(scene, s, passes).mean();
    Image without = test::renderPasses(empty, s, passes).mean();
    writeImage(test::outputDir() + "/vdb-smoke_000002-room.png", withSmoke);
    // The plume (centre of the frame) is lit and visible against the same room without it; every
    // pixel is finite.
    double plume = 0, plumeEmpty = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            ASSERT_TRUE(isFinite(withSmoke.at(x, y)));
            if (std::abs(x - 32) < 10 && std::abs(y - 32) < 16) {
                plume += withSmoke.at(x, y).luminance();
                plumeEmpty += without.at(x, y).luminance();
            }
        }
    EXPECT_GT(plume, 0.0);
    EXPECT_GT(std::abs(plume - plumeEmpty), 0.1 * plumeEmpty) << "the smoke changes nothing in the image";
}

// densityAndHeat.vdb as fire, as a user would write it: the density and the "heat" grid (0.001 to
// 0.76) through a blackbody, loaded from a scene file, emission only (sigma_s = 0, black walls):
// every camera ray then sees exactly L = integral of Tr(s) sigma_a(s) Le(s) ds. The image's mean
// is checked against that integral computed here by quadrature along the same camera's rays,
// reading the file with OpenVDB's own sampler (none of the renderer's grid, tracking or
// gathering code). Tolerance: 4 standard errors of the image mean (from the spread of the 96
// pass means; about 1.3% here: the hot core is small, so the trackers' estimate is noisy) plus
// 0.5% for the quadrature (steps of 1/14 voxel, 2 x 2 rays a pixel: halving the step or doubling
// the rays moves it by under 0.3%). A lost or doubled factor (sigma_a, the emission scale, the
// density) is far outside that.
TEST(VdbAssets, DensityAndHeatRendersAsFire) {
    const std::string path = assetPath("openusd/densityAndHeat.vdb");
    REQUIRE_ASSET(path);
    const std::string dir = test::outputDir() + "/vdb-density-and-heat";
    std::filesystem::create_directories(dir);
    const float sigmaA = 0.5f, scale = 40.0f, kelvinPerUnit = 3000.0f;
    std::ofstream(dir + "/fire.json") << R"({
      "materials": [{"name": "black", "albedo": [0, 0, 0]}],
      "shapes": [{"type": "box", "name": "room", "material": "black", "min": [-60, -60, -60], "max": [60, 60, 60], "inward": true}],
      "cameras": [{"position": [0, -45, 13], "target": [0, 0, 13], "up": [0, 0, 1], "fov": 45}],
      "media": [{"name": "fire", "sigma_s": 0, "sigma_a": 0.5,
                 "density": {"file": ")" + path + R"("},
                 "emission": {"grid": "heat", "blackbody": true, "scale": 40, "temperature_scale": 3000}}],
      "global_medium": "fire"
    })";
    SceneFile file = loadSceneFile(dir + "/fire.json");
    const Scene& scene = file.scene;
    ASSERT_TRUE(scene.media[0].emissive());
    RenderSettings s;
    s.width = s.height = 48;
    s.photonsPerPass = 200;
    const int passes = 96;
    PassRenderer renderer(scene, s);
    Accumulator acc(s.width, s.height);
    std::vector<double> passMeans[3];  // per channel, the mean of each pass image
    for (int p = 0; p < passes; ++p) {
        Image pass = renderer.renderPass(uint64_t(p));
        double m[3] = {0, 0, 0};
        for (const Rgb& c : pass.pixels) {
            ASSERT_TRUE(isFinite(c));
            for (int k = 0; k < 3; ++k) m[k] += c[k];
        }
        for (int k = 0; k < 3; ++k) passMeans[k].push_back(m[k] / double(pass.pixels.size()));
        acc.addPass(pass);
    }
    writeImage(dir + "/fire.png", acc.mean());
    double mean[3], stdErr[3];
    for (int k = 0; k < 3; ++k) {
        double sum = 0, sq = 0;
        for (double v : passMeans[k]) sum += v, sq += v * v;
        mean[k] = sum / passes;
        stdErr[k] = std::sqrt(std::max(0.0, sq / passes - mean[k] * mean[k]) / (passes - 1));
    }

    // The same integral by quadrature, from OpenVDB directly.
    auto density = readWithOpenVdb(path, "density");
    auto heat = readWithOpenVdb(path, "heat");
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> d(*density), h(*heat);
    const Bounds3 box = expectedBounds(*density, Affine3());
    const float step = 0.05f;  // world units; voxels are 0.70 x 0.70 x 0.72
    double sum[3] = {0, 0, 0};
    const int sub = 2;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x)
            for (int sy = 0; sy < sub; ++sy)
                for (int sx = 0; sx < sub; ++sx) {
                    Ray ray = scene.camera.generateRay(float(x) + (sx + 0.5f) / sub, float(y) + (sy + 0.5f) / sub,
                                                       s.width, s.height, Vec2{0.5f, 0.5f});
                    float t0 = 0, t1 = 1e30f;
                    for (int a = 0; a < 3; ++a) {
                        const float inv = 1.0f / ray.d[a];
                        float ta = (box.lo[a] - ray.o[a]) * inv, tb = (box.hi[a] - ray.o[a]) * inv;
                        t0 = std::max(t0, std::min(ta, tb));
                        t1 = std::min(t1, std::max(ta, tb));
                    }
                    double tr = 1.0;
                    for (float t = t0; t < t1; t += step) {
                        const Vec3 p = ray.o + ray.d * (t + 0.5f * step);
                        const openvdb::Vec3R w(p.x, p.y, p.z);
                        const double sa = sigmaA * std::max(0.0f, float(d.wsSample(w)));
                        if (sa <= 0) continue;
                        const double absorbed = 1.0 - std::exp(-sa * step);
                        const Rgb le = blackbodyRgb(std::max(0.0f, float(h.wsSample(w))) * kelvinPerUnit) * scale;
                        for (int c = 0; c < 3; ++c) sum[c] += tr * absorbed * le[c];
                        tr *= 1.0 - absorbed;
                    }
                }
    const double rays = double(s.width) * s.height * sub * sub;
    const Rgb expected(float(sum[0] / rays), float(sum[1] / rays), float(sum[2] / rays));
    std::printf("densityAndHeat fire: image mean %.5f %.5f %.5f (standard errors %.5f %.5f %.5f), quadrature %.5f %.5f %.5f\n",
                mean[0], mean[1], mean[2], stdErr[0], stdErr[1], stdErr[2], expected.r, expected.g, expected.b);
    ASSERT_GT(expected.r, 1e-3f) << "the fire must glow for the comparison to mean anything";
    for (int c = 0; c < 3; ++c) {
        EXPECT_LT(stdErr[c], 0.03 * expected[c]) << "too noisy for the comparison to mean anything";
        EXPECT_NEAR(mean[c], expected[c], 4.0 * stdErr[c] + 0.005 * expected[c]) << "channel " << c;
    }
}

}  // namespace
}  // namespace tyndall
