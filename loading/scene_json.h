#pragma once
// The Tyndall scene description (.json, docs/scene-format.md) -> SceneDraft. Internal to loading/;
// the public entry point is loadSceneFile (scene_file.h). Each element kind is read by one
// function so the format stays easy to extend (heterogeneous media add keys in readMedium).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/density_grid.h"
#include "loading/json_reader.h"
#include "loading/scene_assembly.h"
#include "loading/vdb_grid.h"
#include "core/transform.h"

namespace tyndall {

/// Scene files give angles in degrees; this converts them to radians.
constexpr double kRadiansPerDegree = 3.14159265358979323846 / 180.0;

/// Reads a whole scene description. `render` receives the "render" block (checked).
SceneDraft readSceneJson(const std::string& text, const std::string& file, const std::string& baseDir,
                         const SceneLoadOptions& options, WarnOnce& warn, SceneFile* render);

/// One entry of "materials". Keys: name, type, albedo, ior, emission.
Material readMaterial(JsonObject& obj);
/// One entry of "media"; the caller reads the placement ("inside") first, this reads the rest and
/// finishes the object. Keys: name, sigma_s, sigma_a, g, density (readDensity), emission
/// (readEmission). `baseDir` resolves
/// relative grid files; `proceduralVoxels` as for readDensity.
Medium readMedium(JsonObject& obj, const std::string& baseDir, const SceneLoadOptions& options,
                  uint64_t* proceduralVoxels);
/// Where a medium's emission grids come from: the density's file, or the other grids a procedural
/// density built beside it (the fire's "temperature").
struct DensityChannels {
    VdbGridSource file;  ///< the density's file grid; empty `file` for procedural or no density
    std::string procedural;  ///< the procedural kind ("fire"), empty for files
    std::vector<std::pair<std::string, std::shared_ptr<const DensityGrid>>> grids;  ///< procedural, by name
};
/// A medium's "density" object (scene_density.cpp, docs/scene-format.md): an OpenVDB grid from a
/// file ("file", "grid", "scale", "transform") or a procedural one ("procedural": "smoke",
/// "rolling_fog" or "fire" with its parameters, "scale"). Errors name the JSON place.
/// `proceduralVoxels` counts the scene's procedural voxels so far: a procedural grid adds its own,
/// and one that would take the total past options.maxProceduralVoxels is an error before anything
/// is built. `channels`, when given, receives where the medium's emission grids are read from.
std::shared_ptr<const DensityGrid> readDensity(JsonObject& obj, const std::string& baseDir,
                                               const SceneLoadOptions& options, uint64_t* proceduralVoxels,
                                               DensityChannels* channels = nullptr);
/// A medium's "emission" (scene_emission.cpp, docs/scene-format.md) into `m`: an rgb Le, or for a
/// grid medium an object naming a grid of the density's file or of its procedural grids:
/// {"grid", "color", "scale"} or {"grid", "blackbody": true, "scale", "temperature_scale",
/// "temperature_offset"}. Errors name the JSON place.
void readEmission(const JsonValue& value, const DensityChannels& channels, const SceneLoadOptions& options,
                  Medium& m);
/// "transform": {"scale": s | [sx, sy, sz], "rotate": {"axis": [x, y, z], "degrees": d},
/// "translate": [x, y, z]}, applied in that order (shapes and density grids).
Affine readTransform(JsonObject& obj);
/// One entry of "lights". Keys depend on "type" (point, spot, directional).
Light readLight(JsonObject& obj, const std::string& defaultName);
/// One entry of "cameras".
NamedCamera readCamera(JsonObject& obj, const std::string& defaultName);
/// One entry of "shapes" (procedural meshes, scene_shapes.cpp), material already resolved.
/// `trianglesSoFar` is checked against options.maxTriangles before anything is built.
TriangleMesh readShape(JsonObject& obj, const std::string& defaultName, int material, size_t trianglesSoFar,
                       const SceneLoadOptions& options);

}  // namespace tyndall
