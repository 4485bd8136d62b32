#pragma once
// Scene edits and view files: what the interactive viewer changes in a scene (the camera, each
// light's position, direction and power, each medium's coefficients, the environment's scale and
// rotation) as JSON, and the scene file
// the viewer saves: a base scene plus those edits plus the resolved render settings
// (docs/scene-format.md, "View files"), so that `tyndall render SAVED.json` renders exactly what
// the viewer showed.
//
// The edits are a complete snapshot of the editable fields, and the viewer renders
// applySceneEdits(scene, edits) itself: the scene it renders and the scene a view file loads are
// made by the same code from the same numbers, bit for bit (numbers are written as the shortest
// decimal that reads back to the same float).
#include <nlohmann/json.hpp>
#include <string>

#include "core/scene.h"

namespace tyndall {

/// The editable fields of `scene` as JSON:
///   {"camera": {"position", "forward", "up" (vec3), "y_fov" (radians), "lens_radius", "focus_distance"},
///    "lights": [{"name", "position", "direction", "intensity"} per light, in scene order],
///    "media":  [{"name", "sigma_s", "sigma_a" (rgb), "g", "emission_scale" (multiplies the
///               medium's emission; optional when applied, default 1)} per medium, in scene order],
///    "environment": {"scale", "rotate" (degrees)} (only when the scene has one)}
nlohmann::json sceneEdits(const Scene& scene);

/// The edits for the homogeneous twin of `edited` (the right half of the viewer's compare view;
/// loading/homogeneous_twin.h, which keeps the media in order): `edited`'s camera, lights and
/// environment, and `twin`'s own media (their names and coefficients), each with the emission
/// scale of the same medium of `edited`, so that one emission slider drives both halves (the
/// twin's Le is the grid's density-weighted mean before the scale). Throws Error when the media
/// counts differ.
nlohmann::json twinSceneEdits(const Scene& edited, const Scene& twin);

/// Sets the fields named in `edits` (any of the four keys; lights and media must list every
/// light/medium of the scene, by the same names in the same order). The camera is rebuilt with
/// Camera::lookAt(position, position + forward, up, y_fov); light directions are normalized.
/// Throws Error naming `where` and the JSON place on unknown keys, wrong types, counts or names.
/// Checks what it sets (finite values, g in range, a non-zero and, for grid media, grey
/// extinction) but not the rest of the scene (Scene::validate checks every mesh: too slow for
/// every mouse motion); call PassRenderer::sceneChanged after.
void applySceneEdits(Scene& scene, const nlohmann::json& edits, const std::string& where);

/// The "base" of a view file for the built-in scenes.
inline constexpr const char* kBuiltinDefaultScene = "builtin:default";
inline constexpr const char* kBuiltinSmokeScene = "builtin:smoke";

/// A view file's JSON: {"name", "base" (a scene path as given, or a builtin: name), "base_camera"
/// (the --camera the base was loaded with, "" = its first), "edits", "render"}. `base` should be
/// absolute or relative to the directory the view file is written to.
nlohmann::json viewFileJson(const std::string& name, const std::string& base, const std::string& baseCamera,
                            const nlohmann::json& edits, const nlohmann::json& render);

/// True when a parsed scene-description document is a view file (it has a "base" key).
bool isViewFile(const nlohmann::json& doc);

}  // namespace tyndall
