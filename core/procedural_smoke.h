#pragma once
// A procedural smoke plume made with OpenVDB at start-up (no file needed): the density grid of the
// built-in heterogeneous scene (core/default_smoke_scene.h) and of `tyndall compare` without a
// scene. A rising, widening column with fractal value noise carved into it; deterministic for a
// given seed, so every process that builds it gets the same voxels.
#include <cstdint>
#include <memory>

#include "core/math.h"
#include "core/vdb_grid.h"

namespace tyndall {

struct ProceduralSmoke {
    Vec3 base{0.45f, 0.0f, -1.3f};  ///< world position of the plume's foot (on the floor)
    float height = 2.7f;            ///< world units from the foot to where the plume has faded
    float baseRadius = 0.3f;        ///< column radius at the foot
    float topRadius = 0.85f;        ///< column radius at the top
    float voxelSize = 0.03f;        ///< world units (cubic voxels)
    float noiseFrequency = 2.2f;    ///< base noise frequency, 1 / world unit
    uint32_t seed = 7;
};

/// Builds the plume as an OpenVDB fog volume (values in [0, 1]) wrapped as a density grid.
std::shared_ptr<const VdbDensityGrid> makeProceduralSmoke(const ProceduralSmoke& params = {});

}  // namespace tyndall
