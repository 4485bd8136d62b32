#pragma once
// A density grid in dense voxel form: the interface through which a heterogeneous medium reaches
// the GL splatter. gpu/ uploads the voxels and samples them in GLSL (gpu/shaders/media.glsl) with
// exactly the rule of sample() below, so a DensityGrid whose density() follows the same rule is
// rendered identically by the CPU and GL splatters.
//
// The rule: q = worldToIndex * (p, 1) is p in index space; lattice point (i, j, k), with
// 0 <= i < nx, 0 <= j < ny, 0 <= k < nz, holds voxels[(k * ny + j) * nx + i]; the density at p is
// the trilinear interpolation of the 8 lattice points around q, lattice points outside the array
// counting as 0. That is OpenVDB's BoxSampler (trilinear between values at integer index
// coordinates) with background 0 when the array covers the grid's active voxels plus a margin of
// one, so an OpenVDB grid exports its active bounding box padded by one voxel, its index
// transform (affine part) and its density scale folded into the values.
//
// Grids opt in through DensityGrid::denseVolume(); grids without a dense form (or too large for
// the GPU) keep the primary-segment splat on the CPU (`--gpu auto` warns, `--gpu on` fails).
#include <cstddef>
#include <vector>

#include "core/math.h"

namespace tyndall {

struct DensityVolume {
    /// Row-major 3x4 affine map from world space to index space.
    float worldToIndex[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
    int nx = 0, ny = 0, nz = 0;
    std::vector<float> voxels;  ///< nx * ny * nz, x fastest; >= 0

    size_t voxelCount() const { return size_t(nx) * size_t(ny) * size_t(nz); }
    /// Value at lattice point (i, j, k); 0 outside the array.
    float lattice(int i, int j, int k) const {
        if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0.0f;
        return voxels[(size_t(k) * ny + j) * nx + i];
    }
    Vec3 toIndex(const Vec3& p) const {
        const float(&m)[3][4] = worldToIndex;
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    /// The density at world position p by the rule above.
    float sample(const Vec3& p) const {
        Vec3 q = toIndex(p);
        float fx = std::floor(q.x), fy = std::floor(q.y), fz = std::floor(q.z);
        // Far outside, the int conversion would overflow: everything there is 0 anyway.
        if (!(fx > -2.0f && fy > -2.0f && fz > -2.0f && fx < float(nx) && fy < float(ny) && fz < float(nz)))
            return 0.0f;
        int i = int(fx), j = int(fy), k = int(fz);
        float tx = q.x - fx, ty = q.y - fy, tz = q.z - fz;
        auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
        float c00 = lerp(lattice(i, j, k), lattice(i + 1, j, k), tx);
        float c10 = lerp(lattice(i, j + 1, k), lattice(i + 1, j + 1, k), tx);
        float c01 = lerp(lattice(i, j, k + 1), lattice(i + 1, j, k + 1), tx);
        float c11 = lerp(lattice(i, j + 1, k + 1), lattice(i + 1, j + 1, k + 1), tx);
        return lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz);
    }
};

}  // namespace tyndall
