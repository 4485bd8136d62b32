// DensityVolume's sampling rule: trilinear between lattice values, 0 beyond the lattice, exact on
// affine fields (so a constant grid stays constant and a ramp stays a ramp), and the lattice
// values themselves at lattice points, under a general affine index transform.
#include "core/density_volume.h"

#include <gtest/gtest.h>

#include "core/rng.h"

using namespace tyndall;

namespace {
DensityVolume affineVolume(int nx, int ny, int nz) {
    DensityVolume v;
    v.nx = nx;
    v.ny = ny;
    v.nz = nz;
    // index = A p + b: a shear and a scale, no axis alignment.
    const float m[3][4] = {{2.0f, 0.5f, 0.0f, 1.0f}, {0.0f, 3.0f, -0.4f, 2.0f}, {0.3f, 0.0f, 1.5f, 0.5f}};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) v.worldToIndex[r][c] = m[r][c];
    v.voxels.resize(v.voxelCount());
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
                v.voxels[(size_t(k) * ny + j) * nx + i] = 1.0f + 0.5f * i - 0.25f * j + 0.125f * k;
    return v;
}
}  // namespace

TEST(DensityVolume, TrilinearIsExactOnAffineFieldsInsideTheLattice) {
    DensityVolume v = affineVolume(6, 5, 7);
    Rng rng(1, 2);
    int inside = 0;
    for (int n = 0; n < 20000; ++n) {
        Vec3 p{4 * rng.uniform() - 1, 4 * rng.uniform() - 1, 6 * rng.uniform() - 1};
        Vec3 q = v.toIndex(p);
        if (q.x < 0 || q.y < 0 || q.z < 0 || q.x > 5 || q.y > 4 || q.z > 6) continue;
        ++inside;
        float expected = 1.0f + 0.5f * q.x - 0.25f * q.y + 0.125f * q.z;
        ASSERT_NEAR(v.sample(p), expected, 2e-5f) << "index " << q.x << " " << q.y << " " << q.z;
    }
    EXPECT_GT(inside, 500);
}

TEST(DensityVolume, LatticePointsAndZeroOutside) {
    DensityVolume v;
    v.nx = 3;
    v.ny = 2;
    v.nz = 2;
    v.voxels = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
    EXPECT_FLOAT_EQ(v.sample({2, 1, 1}), 12.0f);
    EXPECT_FLOAT_EQ(v.sample({1, 0, 1}), 8.0f);
    EXPECT_FLOAT_EQ(v.sample({0.5f, 0, 0}), 1.5f);
    // Half a voxel beyond the last lattice point blends with the zero outside.
    EXPECT_FLOAT_EQ(v.sample({2.5f, 0, 0}), 1.5f);
    EXPECT_FLOAT_EQ(v.sample({-0.5f, 0, 0}), 0.5f);
    EXPECT_EQ(v.sample({3.0f, 0, 0}), 0.0f);
    EXPECT_EQ(v.sample({-1.0f, 0, 0}), 0.0f);
    EXPECT_EQ(v.sample({1e30f, 0, 0}), 0.0f);
    EXPECT_EQ(v.sample({0, -1e30f, 0}), 0.0f);
}
