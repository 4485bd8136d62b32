// VdbDensityGrid: trilinear sampling under rotated, anisotropic transforms; bounds; the majorant
// grid really bounds the density along rays; the dense export reproduces density(); thread
// safety of the per-thread accessors; empty grids; and the loader's errors on files written here.
#include "loading/vdb_grid.h"

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

// A rotation about (1, 2, 3) by 0.7 rad, anisotropic voxels 0.05 x 0.11 x 0.08, translated.
Affine3 skewedIndexToWorld() {
    Vec3 axis = normalize(Vec3(1, 2, 3));
    float c = std::cos(0.7f), s = std::sin(0.7f), t = 1 - c;
    float r[3][3] = {{t * axis.x * axis.x + c, t * axis.x * axis.y - s * axis.z, t * axis.x * axis.z + s * axis.y},
                     {t * axis.x * axis.y + s * axis.z, t * axis.y * axis.y + c, t * axis.y * axis.z - s * axis.x},
                     {t * axis.x * axis.z - s * axis.y, t * axis.y * axis.z + s * axis.x, t * axis.z * axis.z + c}};
    const float voxel[3] = {0.05f, 0.11f, 0.08f};
    Affine3 a;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) a.m[i][j] = r[i][j] * voxel[j];
        a.m[i][3] = float(i + 1) * 0.3f - 0.2f;
    }
    return a;
}

struct Block {
    int dims[3] = {7, 5, 9};
    std::vector<float> values;
    float at(int i, int j, int k) const {
        if (i < 0 || j < 0 || k < 0 || i >= dims[0] || j >= dims[1] || k >= dims[2]) return 0.0f;
        return std::max(values[(size_t(k) * dims[1] + j) * dims[0] + i], 0.0f);
    }
    /// Independent trilinear interpolation at index-space point x (voxel centres at integers).
    double trilinear(const Vec3& x) const {
        int i = int(std::floor(x.x)), j = int(std::floor(x.y)), k = int(std::floor(x.z));
        double fx = x.x - i, fy = x.y - j, fz = x.z - k, sum = 0;
        for (int c = 0; c < 8; ++c) {
            int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
            double w = (di ? fx : 1 - fx) * (dj ? fy : 1 - fy) * (dk ? fz : 1 - fz);
            sum += w * at(i + di, j + dj, k + dk);
        }
        return sum;
    }
};

Block randomBlock(uint64_t seed) {
    Block b;
    Rng rng = Rng::forKey(seed, 0, 0, StreamPurpose::Test);
    b.values.resize(size_t(b.dims[0]) * b.dims[1] * b.dims[2]);
    for (float& v : b.values) {
        float u = rng.uniform();
        v = u < 0.3f ? 0.0f : (u < 0.35f ? -0.5f : 3.0f * rng.uniform());  // zeros, a few negatives
    }
    return b;
}

TEST(VdbGrid, DensityIsTrilinearInIndexSpaceUnderAnAnisotropicRotatedTransform) {
    Block b = randomBlock(1);
    Affine3 xf = skewedIndexToWorld();
    auto grid = VdbDensityGrid::fromDense(b.dims, b.values, xf, "test block");
    Rng rng = Rng::forKey(2, 0, 0, StreamPurpose::Test);
    for (int n = 0; n < 20000; ++n) {
        Vec3 x(-1.5f + rng.uniform() * (b.dims[0] + 2), -1.5f + rng.uniform() * (b.dims[1] + 2),
               -1.5f + rng.uniform() * (b.dims[2] + 2));
        Vec3 p = xf.point(x);
        double expected = b.trilinear(grid->worldToIndex().point(p));
        ASSERT_NEAR(grid->density(p), expected, 1e-5 * (1 + expected))
            << "index point " << x.x << " " << x.y << " " << x.z;
        // Away from float round-off, the index point we generated is the one the grid uses.
        ASSERT_NEAR(b.trilinear(x), expected, 1e-3 * (1 + expected));
    }
}

TEST(VdbGrid, BoundsHoldTheSupportAndNothingOutside) {
    Block b = randomBlock(3);
    Affine3 xf = skewedIndexToWorld();
    auto grid = VdbDensityGrid::fromDense(b.dims, b.values, xf, "test block");
    Bounds3 box = grid->bounds();
    ASSERT_FALSE(box.empty());
    Rng rng = Rng::forKey(4, 0, 0, StreamPurpose::Test);
    Vec3 lo = box.lo - box.diagonal() * 0.5f, size = box.diagonal() * 2.0f;
    int inside = 0;
    for (int n = 0; n < 50000; ++n) {
        Vec3 p = lo + mul(size, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        float d = grid->density(p);
        if (d > 0) {
            ASSERT_TRUE(box.contains(p));
            ++inside;
        }
        if (!box.contains(p)) {
            ASSERT_EQ(d, 0.0f);
        }
        // The bounds are the support, not just any box: the index-space support is the voxel box
        // widened by one voxel, so points outside it must read zero from the independent formula.
        Vec3 x = grid->worldToIndex().point(p);
        if (b.trilinear(x) > 1e-6) {
            ASSERT_TRUE(box.contains(p));
        }
    }
    EXPECT_GT(inside, 100);
}

TEST(VdbGrid, MeanMaxAndActiveVoxels) {
    Block b = randomBlock(5);
    auto grid = VdbDensityGrid::fromDense(b.dims, b.values, Affine3(), "test block");
    double sum = 0;
    uint64_t active = 0;
    float maxV = 0;
    for (float v : b.values)
        if (v > 0) {
            sum += v;
            ++active;
            maxV = std::max(maxV, v);
        }
    EXPECT_EQ(grid->activeVoxelCount(), active);
    EXPECT_NEAR(grid->meanDensity(), sum / double(active), 1e-5);
    EXPECT_FLOAT_EQ(grid->maxDensity(), maxV);
}

// The majorant walk: ordered, contiguous segments, and density <= majorant everywhere on them,
// for rays from all directions, including rays starting inside and ending inside the grid.
TEST(VdbGrid, MajorantGridBoundsTheDensityAlongEveryRay) {
    Block b = randomBlock(6);
    for (int block : {1, 2, 8}) {
        Affine3 xf = skewedIndexToWorld();
        auto grid = VdbDensityGrid::fromDense(b.dims, b.values, xf, "test block", block);
        const MajorantGrid* mg = grid->majorantGrid();
        ASSERT_NE(mg, nullptr);
        Bounds3 box = grid->bounds();
        Rng rng = Rng::forKey(7, block, 0, StreamPurpose::Test);
        int checked = 0;
        for (int n = 0; n < 3000; ++n) {
            Vec3 o = box.lo - box.diagonal() * 0.25f +
                     mul(box.diagonal() * 1.5f, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
            Vec3 d = normalize(Vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
            if (n % 5 == 0) d = Vec3(0, 0, n % 2 ? 1.0f : -1.0f);  // axis-aligned in world space
            Ray ray{o, d};
            float tMax = length(box.diagonal()) * 2.0f * rng.uniform();
            MajorantGrid::Walk walk = mg->walk(ray, 0.0f, tMax);
            float t0, t1, maj, last = 0.0f;
            bool first = true;
            std::vector<std::array<float, 3>> segments;
            while (walk.next(&t0, &t1, &maj)) {
                if (!first) {
                    ASSERT_FLOAT_EQ(t0, last) << "segments must be contiguous";
                }
                first = false;
                ASSERT_LE(t0, t1);
                ASSERT_GE(t0, 0.0f);
                ASSERT_LE(t1, tMax);
                last = t1;
                segments.push_back({t0, t1, maj});
                for (int s = 0; s <= 8; ++s) {
                    float t = t0 + (t1 - t0) * float(s) / 8.0f;
                    ASSERT_LE(grid->density(ray.at(t)), maj) << "block " << block << " ray " << n << " t " << t;
                    ++checked;
                }
            }
            // Every point of the ray with density > 0 lies in a segment.
            for (int s = 0; s < 64; ++s) {
                float t = tMax * rng.uniform();
                if (grid->density(ray.at(t)) <= 0) continue;
                bool covered = false;
                for (auto& seg : segments) covered |= t >= seg[0] - 1e-5f && t <= seg[1] + 1e-5f;
                ASSERT_TRUE(covered) << "density " << grid->density(ray.at(t)) << " outside every majorant segment";
            }
            ASSERT_LE(grid->majorant(Ray{o, d, 0.0f, tMax}), grid->maxDensity() * 1.0001f);
        }
        EXPECT_GT(checked, 3000);
    }
}

// The GL splatter's form (core/density_volume.h): DensityVolume::sample, the rule its shader
// twin follows, reproduces density() everywhere, inside and around the grid.
TEST(VdbGrid, DenseVolumeReproducesDensity) {
    Block b = randomBlock(8);
    Affine3 xf = skewedIndexToWorld();
    auto grid = VdbDensityGrid::fromDense(b.dims, b.values, xf, "test block");
    DensityVolume dense;
    ASSERT_TRUE(grid->denseVolume(&dense, size_t(1) << 20));
    EXPECT_EQ(dense.voxels.size(), dense.voxelCount());
    EXPECT_EQ(dense.nx, b.dims[0] + 2);  // every face of the random block has a positive voxel
    DensityVolume small;
    EXPECT_FALSE(grid->denseVolume(&small, dense.voxelCount() - 1)) << "must respect maxVoxels";
    Rng rng = Rng::forKey(9, 0, 0, StreamPurpose::Test);
    Bounds3 box = grid->bounds();
    Vec3 lo = box.lo - box.diagonal() * 0.2f, size = box.diagonal() * 1.4f;
    for (int n = 0; n < 20000; ++n) {
        Vec3 p = lo + mul(size, Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
        float d = grid->density(p);
        ASSERT_NEAR(dense.sample(p), d, 1e-4f * (1 + d)) << n;
    }
    // An empty grid exports an empty volume that samples to 0.
    int dims[3] = {2, 2, 2};
    auto empty = VdbDensityGrid::fromDense(dims, std::vector<float>(8, 0.0f), Affine3(), "empty");
    DensityVolume none;
    ASSERT_TRUE(empty->denseVolume(&none, 10));
    EXPECT_EQ(none.voxelCount(), 0u);
    EXPECT_EQ(none.sample(Vec3(0.5f)), 0.0f);
}

// Five grids read in interleaved order from many threads: more grids than the per-thread accessor
// cache holds, so accessors are rebuilt constantly; every value must equal a serial read.
TEST(VdbGrid, ConcurrentReadsFromManyGridsMatchSerialReads) {
    std::vector<std::shared_ptr<const VdbDensityGrid>> grids;
    for (int g = 0; g < 5; ++g) {
        Block b = randomBlock(20 + g);
        grids.push_back(VdbDensityGrid::fromDense(b.dims, b.values, Affine3(), "grid " + std::to_string(g)));
    }
    const int kPoints = 200000;
    std::vector<Vec3> points(kPoints);
    Rng rng = Rng::forKey(10, 0, 0, StreamPurpose::Test);
    for (Vec3& p : points) p = Vec3(-1 + 9 * rng.uniform(), -1 + 7 * rng.uniform(), -1 + 11 * rng.uniform());
    std::vector<float> serial(kPoints), parallel(kPoints);
    for (int i = 0; i < kPoints; ++i) serial[i] = grids[i % 5]->density(points[i]);
    tbb::parallel_for(0, kPoints, [&](int i) { parallel[i] = grids[i % 5]->density(points[i]); });
    for (int i = 0; i < kPoints; ++i) ASSERT_EQ(serial[i], parallel[i]) << i;
    // A grid destroyed and another created (possibly at the same address) never sees stale state.
    Block b = randomBlock(30);
    grids[2].reset();
    auto fresh = VdbDensityGrid::fromDense(b.dims, b.values, Affine3(), "fresh");
    tbb::parallel_for(0, 10000, [&](int i) { ASSERT_NEAR(fresh->density(points[i]), b.trilinear(points[i]), 1e-5); });
}

TEST(VdbGrid, AnEmptyGridIsAnEmptyMedium) {
    int dims[3] = {4, 4, 4};
    std::vector<float> zeros(64, 0.0f);
    auto grid = VdbDensityGrid::fromDense(dims, zeros, Affine3(), "empty");
    EXPECT_TRUE(grid->bounds().empty());
    EXPECT_EQ(grid->maxDensity(), 0.0f);
    EXPECT_EQ(grid->meanDensity(), 0.0f);
    EXPECT_EQ(grid->density(Vec3(1, 1, 1)), 0.0f);
    MajorantGrid::Walk w = grid->majorantGrid()->walk(Ray{Vec3(-1.0f), normalize(Vec3(1.0f))}, 0.0f, 10.0f);
    float t0, t1, m;
    EXPECT_FALSE(w.next(&t0, &t1, &m));
}

// Two voxels 40000 apart: the majorant grid coarsens instead of allocating 5000^3 cells, still
// bounds both voxels, and the dense export declines (40001^3 voxels).
TEST(VdbGrid, SparseGridsOverHugeRangesStayBounded) {
    openvdb::initialize();
    auto g = openvdb::FloatGrid::create(0.0f);
    g->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    g->tree().setValue(openvdb::Coord(40000, 40000, 40000), 2.0f);
    std::string path = test::outputDir() + "/sparse-far-apart.vdb";
    openvdb::io::File(path).write({g});
    VdbGridSource src;
    src.file = path;
    auto grid = VdbDensityGrid::load(src);
    EXPECT_GT(grid->majorantBlock(), VdbDensityGrid::kMajorantBlock);
    EXPECT_LE(int64_t(grid->majorantGrid()->cellCount()), VdbDensityGrid::kMaxMajorantCells);
    EXPECT_GE(grid->majorant(Ray{Vec3(-1.0f), normalize(Vec3(1.0f)), 0.0f, 10.0f}), 1.0f);
    EXPECT_GE(grid->majorant(Ray{Vec3(39999.0f), normalize(Vec3(1.0f)), 0.0f, 10.0f}), 2.0f);
    EXPECT_NEAR(grid->density(Vec3(40000.0f)), 2.0f, 1e-5f);
    DensityVolume dense;
    EXPECT_FALSE(grid->denseVolume(&dense, size_t(1) << 28));
}

// ---- The loader's errors, on files written by this test ----

std::string outPath(const std::string& name) {
    return test::outputDir() + "/" + name;
}

VdbGridSource source(const std::string& file, const std::string& grid = "") {
    VdbGridSource s;
    s.file = file;
    s.grid = grid;
    return s;
}

void writeGrids(const std::string& path, openvdb::GridPtrVec grids) {
    openvdb::initialize();
    openvdb::io::File(path).write(grids);
}

std::string loadError(const VdbGridSource& src) {
    try {
        VdbDensityGrid::load(src);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(VdbGridLoad, MissingFileNamesTheFile) {
    std::string msg = loadError(source(outPath("no-such-file.vdb")));
    EXPECT_NE(msg.find("no-such-file.vdb"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
}

TEST(VdbGridLoad, NotAVdbFileGivesAClearError) {
    std::string path = outPath("not-a-vdb.vdb");
    std::ofstream(path) << "this is not an OpenVDB file\n";
    std::string msg = loadError(source(path));
    EXPECT_NE(msg.find("not-a-vdb.vdb"), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot be read"), std::string::npos) << msg;
}

TEST(VdbGridLoad, GridSelectionAndTypeErrors) {
    openvdb::initialize();
    auto heat = openvdb::FloatGrid::create(0.0f);
    heat->setName("heat");
    heat->tree().setValue(openvdb::Coord(1, 2, 3), 0.5f);
    auto vel = openvdb::Vec3SGrid::create();
    vel->setName("velocity");
    vel->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 0, 0));
    std::string path = outPath("heat-and-velocity.vdb");
    writeGrids(path, {vel, heat});

    // No "density": the first float grid.
    auto g = VdbDensityGrid::load(source(path));
    EXPECT_EQ(g->gridName(), "heat");
    EXPECT_EQ(g->activeVoxelCount(), 1u);
    EXPECT_NEAR(g->density(Vec3(1, 2, 3)), 0.5f, 1e-6f);

    std::string missing = loadError(source(path, "density"));
    EXPECT_NE(missing.find("no grid named 'density'"), std::string::npos) << missing;
    EXPECT_NE(missing.find("'heat' (float)"), std::string::npos) << missing;
    EXPECT_NE(missing.find("'velocity' (vec3s)"), std::string::npos) << missing;

    std::string wrongType = loadError(source(path, "velocity"));
    EXPECT_NE(wrongType.find("grid 'velocity' holds vec3s values"), std::string::npos) << wrongType;

    // Only non-float grids: no density at all.
    std::string path2 = outPath("velocity-only.vdb");
    writeGrids(path2, {vel});
    std::string none = loadError(source(path2));
    EXPECT_NE(none.find("no float grid"), std::string::npos) << none;
}

TEST(VdbGridLoad, LevelSetIsRejected) {
    openvdb::initialize();
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, openvdb::Vec3f(0), 0.1f);
    sphere->setName("surface");
    std::string path = outPath("level-set-sphere.vdb");
    writeGrids(path, {sphere});
    std::string msg = loadError(source(path));
    EXPECT_NE(msg.find("level set"), std::string::npos) << msg;
    EXPECT_NE(msg.find("surface"), std::string::npos) << msg;
}

TEST(VdbGridLoad, PositiveBackgroundAndBadScaleAreRejected) {
    openvdb::initialize();
    auto g = openvdb::FloatGrid::create(0.25f);
    g->setName("density");
    g->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    std::string path = outPath("positive-background.vdb");
    writeGrids(path, {g});
    EXPECT_NE(loadError(source(path)).find("background"), std::string::npos);

    auto ok = openvdb::FloatGrid::create(0.0f);
    ok->setName("density");
    ok->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
    std::string okPath = outPath("one-voxel.vdb");
    writeGrids(okPath, {ok});
    VdbGridSource src = source(okPath);
    src.scale = -1.0f;
    EXPECT_NE(loadError(src).find("scale"), std::string::npos);
    src.scale = 3.0f;
    src.transform = Affine3::scaleTranslate(Vec3(2.0f), Vec3(10, 0, 0));
    auto grid = VdbDensityGrid::load(src);
    EXPECT_NEAR(grid->density(Vec3(10, 0, 0)), 3.0f, 1e-6f);  // voxel (0,0,0) moved by the scene transform
    EXPECT_NEAR(grid->density(Vec3(11, 0, 0)), 1.5f, 1e-6f);  // half a (scaled) voxel away
    EXPECT_NEAR(grid->bounds().lo.x, 8.0f, 1e-5f);
    EXPECT_NEAR(grid->bounds().hi.x, 12.0f, 1e-5f);
}

}  // namespace
}  // namespace tyndall
