#pragma once
// A scalar density field in world space for heterogeneous media (OpenVDB grids implement it in
// core/vdb_grid.*; tests use analytic fields). Density is dimensionless, >= 0, and multiplies the
// medium's coefficients. Implementations must be safe to call from many threads at once.
//
// Tracking (cpu/free_flight.cpp) bounds the density along a ray by majorantGrid() when the grid
// has one (piecewise-constant, tight) and by majorant(ray) otherwise (one value per segment).
#include <vector>

#include "core/affine3.h"
#include "core/majorant_grid.h"
#include "core/math.h"

namespace tyndall {

/// A grid's voxels as a dense block, for uploading as a 3D texture (gpu/). Sampling it with
/// hardware trilinear filtering at texture coordinate worldToTexture.point(p) (clamp to a zero
/// border) reproduces DensityGrid::density(p): texel (i, j, k) is voxel (i, j, k) of the block and
/// its centre sits at ((i, j, k) + 0.5) / dims.
struct DenseDensity {
    int dims[3] = {0, 0, 0};
    std::vector<float> values;  ///< x fastest: values[(k * dims[1] + j) * dims[0] + i], >= 0
    Affine3 worldToTexture;     ///< world -> [0, 1]^3 texture coordinates
};

class DensityGrid {
public:
    virtual ~DensityGrid() = default;
    /// Density at world position `p`; 0 outside bounds().
    virtual float density(const Vec3& p) const = 0;
    /// World-space box outside which the density is zero (empty for an empty grid).
    virtual Bounds3 bounds() const = 0;
    /// An upper bound on density(p) over the ray segment ray.o + t ray.d, t in [tMin, tMax]
    /// (a majorant for delta tracking). The default is the global maximum.
    virtual float majorant(const Ray& ray) const { return maxDensity(); }
    /// A piecewise-constant majorant (see core/majorant_grid.h), or null for none.
    virtual const MajorantGrid* majorantGrid() const { return nullptr; }
    /// Upper bound on density over the whole grid (0 for an empty grid).
    virtual float maxDensity() const = 0;
    /// Mean density over the active region (for the homogeneous twin of `tyndall compare`).
    virtual float meanDensity() const = 0;
    /// The voxels as a dense block for GPU upload; false when the grid has no voxel form or the
    /// block would be too large to hold.
    virtual bool toDense(DenseDensity* out) const { return false; }
};

}  // namespace tyndall
