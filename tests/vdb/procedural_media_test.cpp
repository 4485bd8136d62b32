// Procedural grids: deterministic for a seed, values in [0, 1], inside the box they were asked to
// fill, and not trivially empty or full.
#include "loading/procedural_media.h"

#include <gtest/gtest.h>

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
