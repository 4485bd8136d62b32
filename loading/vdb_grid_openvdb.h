#pragma once
// Private to tyndall_core's .cpp files (includes OpenVDB, which tyndall_core links PRIVATE): turns
// an in-memory OpenVDB float grid into a VdbDensityGrid. Used by the file loader, fromDense() and
// the procedural smoke.
#include <openvdb/openvdb.h>

#include <memory>
#include <string>

#include "loading/vdb_grid.h"

namespace tyndall {

class LoadBudget;

/// openvdb::initialize(), once per process; safe to call from any thread, any number of times.
void initializeOpenVdb();

/// Wraps `grid` (float fog volume; the caller has rejected level sets and non-float types).
/// `sceneTransform` is applied after the grid's own index-to-world transform; `scale` multiplies
/// the values. `label` prefixes error messages ("vdb file 'x': grid 'density'"). Throws Error for
/// a frustum or singular transform, a positive background or a bad scale. May copy the grid to
/// clamp negative values. `budget` (may be null) is asked for the majorant grid and the dense copy
/// kept for lookups before they are built. `background` is what VdbDensityGrid::background()
/// reports (the caller has already taken it out of the values).
std::shared_ptr<const VdbDensityGrid> makeVdbDensityGrid(openvdb::FloatGrid::ConstPtr grid,
                                                         const Affine3& sceneTransform, float scale,
                                                         const std::string& label, int majorantBlock,
                                                         LoadBudget* budget = nullptr, float background = 0.0f);

}  // namespace tyndall
