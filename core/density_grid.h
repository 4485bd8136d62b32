#pragma once
// A scalar density field in world space for heterogeneous media (OpenVDB grids implement it in
// core/vdb_grid.*; tests use analytic fields). Density is dimensionless, >= 0, and multiplies the
// medium's coefficients. Implementations must be safe to call from many threads at once.
//
// Tracking (cpu/free_flight.cpp) bounds the density along a ray by majorantGrid() when the grid
// has one (piecewise-constant, tight) and by majorant(ray) otherwise (one value per segment).
#include <cstddef>
#include <cstdint>

#include "core/density_volume.h"
#include "core/majorant_grid.h"
#include "core/math.h"

namespace tyndall {

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
    /// The integral of density(p) over all space, in world units^3 (the homogeneous twin's mass).
    /// Default: integrateDensity over bounds(); OpenVDB grids sum their voxels exactly.
    virtual double integratedDensity() const;
    /// The grid in dense voxel form for the GL splatter (core/density_volume.h states the rule
    /// `out->sample(p)` must match density(p) by), when it has one of at most `maxVoxels` voxels;
    /// false otherwise, and the primary-segment splat of this medium stays on the CPU.
    virtual bool denseVolume(DensityVolume* out, size_t maxVoxels) const { return false; }
    /// `h` (an FNV-1a state, core/checkpoint.h) mixed with the whole field, for the resume check
    /// (a checkpoint's scene hash): any change to any value changes it, with near certainty.
    /// OpenVDB grids hash every stored value (leaf buffers, tiles), the scale and the transform;
    /// the default, for analytic fields, hashes bounds() and density() at the centres of a 32^3
    /// lattice over them.
    virtual uint64_t contentHash(uint64_t h) const;
};

/// The integral of `grid`'s density over the world box `box` (clipped to grid.bounds()), in world
/// units^3, by the midpoint rule on a lattice of `cellsPerAxis`^3 cells (deterministic; a
/// piecewise-trilinear field sampled at about two points per voxel is within ~1e-3 relative).
double integrateDensity(const DensityGrid& grid, const Bounds3& box, int cellsPerAxis = 128);

}  // namespace tyndall
