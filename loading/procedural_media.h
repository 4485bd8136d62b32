#pragma once
// Procedural density grids made with OpenVDB at start-up (no file needed), deterministic for a
// given seed so every process that builds one gets the same voxels:
// - smoke: a rising, widening column with fractal value noise carved into it; the density grid
//   of the built-in heterogeneous scene (loading/default_smoke_scene.h) and of `tyndall compare`
//   without a scene;
// - rolling fog: a ground-hugging layer whose thickness and density roll in long horizontal
//   banks (the street lamp's heterogeneous variant);
// - fire: a flame and its smoke as two grids, density and temperature (kelvin), for a medium
//   that emits through a blackbody (core/grid_emission.h).
// Densities are fog volumes with values in [0, densityScale] (1 by default).
#include <cstdint>
#include <memory>

#include "core/math.h"
#include "loading/vdb_grid.h"

namespace tyndall {

struct ProceduralSmoke {
    Vec3 base{0.45f, 0.0f, -1.3f};  ///< world position of the plume's foot (on the floor)
    float height = 2.7f;            ///< world units from the foot to where the plume has faded
    float baseRadius = 0.3f;        ///< column radius at the foot
    float topRadius = 0.85f;        ///< column radius at the top
    float voxelSize = 0.03f;        ///< world units (cubic voxels)
    float noiseFrequency = 2.2f;    ///< base noise frequency, 1 / world unit
    float densityScale = 1.0f;      ///< multiplies every value (so values lie in [0, densityScale])
    uint32_t seed = 7;
};

/// Builds the plume as an OpenVDB fog volume (values in [0, 1]) wrapped as a density grid.
std::shared_ptr<const VdbDensityGrid> makeProceduralSmoke(const ProceduralSmoke& params = {});

struct RollingFog {
    Vec3 lo{-10.0f, 0.0f, -10.0f};  ///< world box the fog fills (its floor is the ground)
    Vec3 hi{10.0f, 3.0f, 10.0f};
    float layerHeight = 1.2f;   ///< world units: mean thickness of the layer
    float bankSize = 4.0f;      ///< world units: horizontal size of the rolling banks
    float voxelSize = 0.1f;     ///< world units (cubic voxels)
    float densityScale = 1.0f;  ///< multiplies every value (so values lie in [0, densityScale])
    uint32_t seed = 11;
};

/// A fire on the ground: flame tongues over a disc of `radius` at `base`, carved by fractal noise
/// advected upward, hottest in the core at the foot (`temperature` kelvin) and cooling with
/// height until, at `flameHeight`, the gas no longer glows in the visible; above it a widening
/// column of smoke, cool, rising to `height`. Density: thin soot in the flames (about 0.4),
/// smoke up to 1 above them (times densityScale). Temperature: a fog volume in kelvin, 0 outside
/// the flames and the warm smoke (nothing below 1% of `temperature` is kept).
struct ProceduralFire {
    Vec3 base{0.0f, 0.0f, 0.0f};  ///< world position of the fire's foot (on the floor)
    float radius = 0.3f;           ///< world units: the flames' base radius
    float flameHeight = 0.8f;      ///< world units from the foot to the tips of the flames
    float height = 2.0f;           ///< world units from the foot to where the smoke has faded
    float temperature = 2100.0f;   ///< kelvin in the core at the foot
    float voxelSize = 0.025f;      ///< world units (cubic voxels)
    float noiseFrequency = 3.0f;   ///< base noise frequency, 1 / world unit
    float densityScale = 1.0f;     ///< multiplies the density (not the temperature)
    uint32_t seed = 3;
};

struct FireGrids {
    std::shared_ptr<const VdbDensityGrid> density;
    std::shared_ptr<const VdbDensityGrid> temperature;  ///< kelvin
};

/// Voxels a procedural grid with these parameters would hold (checked by scene loading before
/// building one); UINT64_MAX when that does not fit 64 bits. The fire's count is both its grids'.
uint64_t voxelCount(const ProceduralSmoke& params);
uint64_t voxelCount(const RollingFog& params);
uint64_t voxelCount(const ProceduralFire& params);

/// Builds the fog layer as an OpenVDB fog volume (values in [0, 1]) wrapped as a density grid.
std::shared_ptr<const VdbDensityGrid> makeRollingFog(const RollingFog& params = {});

/// Builds the fire's two grids (OpenVDB fog volumes on one lattice).
FireGrids makeProceduralFire(const ProceduralFire& params = {});

}  // namespace tyndall
