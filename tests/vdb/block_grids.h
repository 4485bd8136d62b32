#pragma once
// OpenVDB grids written by the tests that need a .vdb file on disk (header-only: the test links
// OpenVDB itself).
#include <openvdb/openvdb.h>

namespace tyndall::test {

/// A float grid named `name` on cubic voxels of `voxelSize` world units (index to world a plain
/// scale), background `background`, with active voxels of `value` on the index cube
/// [lo, hi]^3, inclusive (voxel by voxel: no tiles).
inline openvdb::FloatGrid::Ptr blockGrid(const char* name, double voxelSize, int lo, int hi, float value,
                                         float background = 0.0f) {
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(background);
    grid->setName(name);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
    for (int k = lo; k <= hi; ++k)
        for (int j = lo; j <= hi; ++j)
            for (int i = lo; i <= hi; ++i) grid->tree().setValue(openvdb::Coord(i, j, k), value);
    return grid;
}

}  // namespace tyndall::test
