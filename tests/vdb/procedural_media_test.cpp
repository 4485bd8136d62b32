// Procedural grids: deterministic for a seed, values in [0, 1], inside the box they were asked to
// fill, and not trivially empty or full; the fire hot in its flames and cooling with height.
#include "loading/procedural_media.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tyndall {
namespace {

constexpr size_t kMaxVoxels = size_t(1) << 26;

void expectSane(const VdbDensityGrid& g, const Bounds3& box, const char* what) {
    SCOPED_TRACE(what);
    ASSERT_FALSE(g.bounds().empty());
    EXPECT_GT(g.maxDensity(), 0.5f);
    EXPECT_LE(g.maxDensity(), 1.0f);
    EXPECT_GT(g.meanDensity(), 0.05f);
    EXPECT_LT(g.meanDensity(), g.maxDensity());
    // One voxel of trilinear support may reach past the box.
    const float slack = 0.11f;
    for (int a = 0; a < 3; ++a) {
        EXPECT_GE(g.bounds().lo[a], box.lo[a] - slack);
        EXPECT_LE(g.bounds().hi[a], box.hi[a] + slack);
    }
}

TEST(ProceduralMedia, SmokeIsDeterministicAndSane) {
    ProceduralSmoke p;
    p.voxelSize = 0.06f;  // coarser than the default, to keep the test quick
    auto a = makeProceduralSmoke(p), b = makeProceduralSmoke(p);
    DensityVolume da, db;
    ASSERT_TRUE(a->denseVolume(&da, kMaxVoxels));
    ASSERT_TRUE(b->denseVolume(&db, kMaxVoxels));
    EXPECT_EQ(da.voxels, db.voxels);
    Bounds3 box{p.base - Vec3(1.2f, 0.0f, 1.2f), p.base + Vec3(1.2f, p.height, 1.2f)};
    expectSane(*a, box, "smoke");
    p.seed += 1;
    DensityVolume dc;
    makeProceduralSmoke(p)->denseVolume(&dc, kMaxVoxels);
    EXPECT_NE(da.voxels, dc.voxels);
}

TEST(ProceduralMedia, RollingFogIsDeterministicAndHugsTheGround) {
    RollingFog f;
    f.lo = Vec3(-3.0f, 0.0f, -3.0f);
    f.hi = Vec3(3.0f, 3.0f, 3.0f);
    auto a = makeRollingFog(f), b = makeRollingFog(f);
    DensityVolume da, db;
    ASSERT_TRUE(a->denseVolume(&da, kMaxVoxels));
    ASSERT_TRUE(b->denseVolume(&db, kMaxVoxels));
    EXPECT_EQ(da.voxels, db.voxels);
    expectSane(*a, Bounds3{f.lo, f.hi}, "fog");
    // Thicker near the ground than at the mean layer height, nothing well above the layer.
    double low = 0, high = 0;
    for (float x = -2.5f; x <= 2.5f; x += 0.25f)
        for (float z = -2.5f; z <= 2.5f; z += 0.25f) {
            low += a->density(Vec3(x, 0.2f, z));
            high += a->density(Vec3(x, f.layerHeight, z));
            EXPECT_EQ(a->density(Vec3(x, 2.0f * f.layerHeight + 0.2f, z)), 0.0f);
        }
    EXPECT_GT(low, 2.0 * high);
}

}  // namespace
}  // namespace tyndall

namespace tyndall {
namespace {

// The procedural fire: deterministic, temperature in (0, temperature], hottest in the flames at
// the foot and cooling with height (above the flames nothing is hot enough to glow much), the
// density present wherever the gas is hot (the source is sigma_a * density * Le), and both grids
// inside the box the parameters describe.
TEST(ProceduralMedia, FireIsHotAtTheFootAndCoolsWithHeight) {
    ProceduralFire f;
    f.voxelSize = 0.05f;  // coarser than the default, to keep the test quick
    f.base = Vec3(0.5f, 0.1f, -0.2f);
    const FireGrids a = makeProceduralFire(f), b = makeProceduralFire(f);
    DensityVolume ta, tb;
    ASSERT_TRUE(a.temperature->denseVolume(&ta, kMaxVoxels));
    ASSERT_TRUE(b.temperature->denseVolume(&tb, kMaxVoxels));
    EXPECT_EQ(ta.voxels, tb.voxels);
    EXPECT_LE(a.temperature->maxDensity(), f.temperature);
    EXPECT_GT(a.temperature->maxDensity(), 0.8f * f.temperature);
    EXPECT_GT(a.density->maxDensity(), 0.5f);
    EXPECT_LE(a.density->maxDensity(), 1.0f);
    const float reach = f.radius * 2.0f;
    Bounds3 box{f.base - Vec3(reach, 0.0f, reach), f.base + Vec3(reach, f.height, reach)};
    for (const auto& g : {a.density, a.temperature})
        for (int ax = 0; ax < 3; ++ax) {
            EXPECT_GE(g->bounds().lo[ax], box.lo[ax] - 0.06f);
            EXPECT_LE(g->bounds().hi[ax], box.hi[ax] + 0.06f);
        }
    // Hottest point and mean temperature per height band, on a lattice over the box.
    constexpr int kBands = 8;
    float hot[kBands] = {};
    float hottestY = 0, hottest = 0;
    int hotWithoutDensity = 0, hotPoints = 0;
    for (float y = 0.0f; y < f.height; y += 0.02f)
        for (float x = -reach; x <= reach; x += 0.02f)
            for (float z = -reach; z <= reach; z += 0.02f) {
                const Vec3 p = f.base + Vec3(x, y, z);
                const float t = a.temperature->density(p);
                ASSERT_TRUE(std::isfinite(t));
                ASSERT_GE(t, 0.0f);
                const int band = std::min(kBands - 1, int(y / f.height * kBands));
                hot[band] = std::max(hot[band], t);
                if (t > hottest) hottest = t, hottestY = y;
                if (t > 0.5f * f.temperature) {
                    ++hotPoints;
                    if (!(a.density->density(p) > 0)) ++hotWithoutDensity;
                }
            }
    EXPECT_LT(hottestY, 0.5f * f.flameHeight) << "the hottest gas is low in the flames";
    EXPECT_GT(hotPoints, 100);
    EXPECT_EQ(hotWithoutDensity, 0) << "hot gas without density would not emit";
    // The hottest temperature of each height band falls band by band.
    for (int band = 0; band + 1 < kBands; ++band) {
        EXPECT_GT(hot[band], hot[band + 1]) << "band " << band;
    }
    // Above the flames, nothing reaches half the core's temperature.
    float aboveFlames = 0;
    for (float y = 1.2f * f.flameHeight; y < f.height; y += 0.02f)
        for (float x = -reach; x <= reach; x += 0.02f)
            for (float z = -reach; z <= reach; z += 0.02f)
                aboveFlames = std::max(aboveFlames, a.temperature->density(f.base + Vec3(x, y, z)));
    EXPECT_LT(aboveFlames, 0.5f * f.temperature);
    // The smoke above the flames is there: density in the upper half.
    float smoke = 0;
    for (float y = 0.5f * f.height; y < 0.8f * f.height; y += 0.05f)
        for (float x = -reach; x <= reach; x += 0.02f)
            for (float z = -reach; z <= reach; z += 0.02f) smoke = std::max(smoke, a.density->density(f.base + Vec3(x, y, z)));
    EXPECT_GT(smoke, 0.3f);
    // Another seed, other voxels; the voxel count the loader checks covers both grids.
    f.seed += 1;
    DensityVolume tc;
    makeProceduralFire(f).temperature->denseVolume(&tc, kMaxVoxels);
    EXPECT_NE(ta.voxels, tc.voxels);
    int64_t nx = int64_t(std::ceil(2.0 * (f.radius * 1.75 + 2.0 * f.voxelSize) / f.voxelSize)) + 1;
    int64_t ny = int64_t(std::ceil(f.height / f.voxelSize)) + 1;
    EXPECT_EQ(voxelCount(f), uint64_t(2 * nx * nx * ny));
}

}  // namespace
}  // namespace tyndall
