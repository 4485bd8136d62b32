#pragma once
// OpenVDB density grids for heterogeneous media (DensityGrid implementation). OpenVDB itself is a
// private dependency of tyndall_core: nothing here includes its headers.
//
// What a grid means:
// - Values are a float fog volume (OpenVDB's convention: 0 = empty). Level sets, non-float grids
//   and frustum transforms are rejected with an Error; negative voxel values are clamped to 0; a
//   background value must be <= 0 (treated as 0), except for emission and temperature channels
//   (VdbGridSource::ambientBackground).
// - density(p) = scale * trilinear interpolation of the voxel values, voxel (i, j, k) centred at
//   index-space point (i, j, k) (OpenVDB's BoxSampler), at index point worldToIndex(p). The
//   world <- index map is the file's index-to-world transform (anisotropic voxels, rotations)
//   followed by the scene's transform. Inactive voxels read as their stored value (0 in fog
//   volumes). The same values feed the majorant grid and the dense export (denseVolume: the
//   positive voxels plus a one-voxel zero border, scale folded in), so tracking, gathering and the
//   GL splatter all see one field.
// - An empty grid (no positive voxel) is a valid, empty medium: density 0 everywhere.
// - Lookups: when the dense lattice (the positive voxels' bounding box plus the border) has at
//   most kMaxDenseVoxels voxels, density() samples a dense copy (DensityVolume::sample, the GL
//   splatter's rule; 4 bytes per voxel), 1.5-2x faster than OpenVDB's accessor; larger sparse
//   grids are read through OpenVDB. Both give the same trilinear field up to float rounding.
// - Majorants: a coarse grid of cells of `kMajorantBlock`^3 voxels (coarser for huge sparse
//   grids), each holding the maximum of every voxel its trilinear stencil can touch (plus one
//   voxel of margin for rounding).
//
// Threading: all queries are safe from any number of threads. OpenVDB accessors are not, so each
// thread keeps its own accessor (a small thread_local cache keyed by a per-grid id that is never
// reused, so a destroyed grid's cached accessor is never touched again).
#include <cstdint>
#include <memory>
#include <functional>
#include <string>
#include <vector>

#include "core/affine3.h"
#include "core/density_grid.h"

namespace tyndall {

class LoadBudget;

/// Where a grid comes from (the scene format's medium key "density": {"file", "grid", "scale",
/// "transform"}).
struct VdbGridSource {
    std::string file;    ///< path to a .vdb file
    /// Grid name; empty = "density" if present, else the first float grid. Files may hold several
    /// grids of one name: "name[k]" picks the k-th of them (from 0, in file order, as vdb_print
    /// lists them); a plain "name" takes the first and says so.
    std::string grid;
    float scale = 1.0f;  ///< density multiplier, >= 0
    Affine3 transform;   ///< scene transform applied after the file's index-to-world map
    /// Emission and temperature channels: a positive background is the field's value away from
    /// the voxels (an ambient temperature), not an error. It is taken out of the values (each
    /// becomes max(v - background, 0), so the grid is again 0 outside its voxels and voxels below
    /// the background read as it) and kept as background(); the caller adds it back.
    bool ambientBackground = false;
};

class VdbDensityGrid : public DensityGrid {
public:
    /// Edge of a majorant cell, in voxels (doubled until the majorant grid has at most
    /// kMaxMajorantCells cells, for sparse grids spanning huge index ranges).
    static constexpr int kMajorantBlock = 8;
    static constexpr int64_t kMaxMajorantCells = int64_t(1) << 21;
    /// Largest dense copy kept for lookups (64 MiB).
    static constexpr size_t kMaxDenseVoxels = size_t(1) << 24;

    /// Loads a grid through the strict reader (loading/vdb_file.h); throws Error "vdb file
    /// '<file>': ..." for a missing, unreadable, truncated or damaged file, a missing grid name
    /// (listing the grids present), a level set, a non-float grid, a frustum or singular transform,
    /// a positive background, a bad scale, or a grid that does not fit `budget` (may be null: no
    /// limit). `notice` receives one line when the choice was ambiguous (several grids of the
    /// chosen name): which one was taken and how to pick another; empty = "tyndall: <line>" on
    /// stderr. OpenVDB's own console warnings are never triggered.
    static std::shared_ptr<const VdbDensityGrid> load(const VdbGridSource& source,
                                                      const std::function<void(const std::string&)>& notice = {},
                                                      LoadBudget* budget = nullptr);

    /// Builds an OpenVDB grid from dense values (tests, procedural media): voxel (i, j, k) of a
    /// dims[0] x dims[1] x dims[2] block (x fastest) sits at index (i, j, k); values <= 0 stay
    /// inactive. `indexToWorld` as for files. `label` names it in messages.
    static std::shared_ptr<const VdbDensityGrid> fromDense(const int dims[3], const std::vector<float>& values,
                                                           const Affine3& indexToWorld, const std::string& label,
                                                           int majorantBlock = kMajorantBlock);

    ~VdbDensityGrid() override;

    float density(const Vec3& p) const override;
    Bounds3 bounds() const override;
    float majorant(const Ray& ray) const override;
    const MajorantGrid* majorantGrid() const override;
    float maxDensity() const override;
    float meanDensity() const override;
    /// Exact for the trilinear field: the sum of the positive voxel values x voxel volume x scale.
    double integratedDensity() const override;
    bool denseVolume(DensityVolume* out, size_t maxVoxels) const override;
    /// Every stored value (each leaf's origin, value mask and 512 values; each tile above the
    /// leaves with its extent and state), the scale, the background and the world <- index map.
    uint64_t contentHash(uint64_t h) const override;

    /// "file 'x' grid 'density'" or the label given to fromDense.
    const std::string& label() const;
    const std::string& gridName() const;
    /// The positive background taken out of the values (VdbGridSource::ambientBackground); 0 when
    /// there was none.
    float background() const;
    uint64_t activeVoxelCount() const;
    /// Edge of the majorant cells actually used, in voxels.
    int majorantBlock() const;
    const Affine3& indexToWorld() const;
    const Affine3& worldToIndex() const;

    struct Impl;  // OpenVDB state, loading/vdb_grid_openvdb.h
    explicit VdbDensityGrid(std::unique_ptr<Impl> impl);

private:
    std::unique_ptr<Impl> m_impl;
};

}  // namespace tyndall
