#pragma once
// The environment light from a scene description's "environment" object or from the command

//
// "environment": {"file": "sky.exr", "scale": 1, "rotate": 0, "visible": true}
//             or {"radiance": [r, g, b] (or one number), "scale": 1, "visible": true}
//   file      a latitude-longitude image (EXR, Radiance .hdr, or any format OpenImageIO reads;
//             8-bit formats are taken as sRGB), relative to the scene file; mapping in
//             core/environment_light.h. Not 2:1: a warning (the image is stretched over the sphere).
//   radiance  a constant colour instead of an image (W m^-2 sr^-1), each channel finite and >= 0
//   scale     multiplies the radiance, finite and >= 0 (default 1)
//   rotate    degrees about +Y (default 0)
//   visible   false: camera rays that leave the scene straight see black; the light, its
//             reflections and refractions stay (default true)
#include <string>

#include "core/environment_light.h"
#include "loading/json_reader.h"
#include "loading/scene_file.h"

namespace tyndall {

/// Reads the "environment" object; `baseDir` resolves a relative "file". Errors name the JSON place.
EnvironmentLight readEnvironment(JsonObject& obj, const std::string& baseDir, const SceneLoadOptions& options,
                                 WarnOnce& warn);
/// A lat-long image file as an environment light; `where` prefixes errors ("--environment",
/// "<scene>: /environment/file"), and a non-2:1 image is warned about. `budget` (the load's,
/// SceneLoadOptions::budget) weighs the image's declared size before it is read.
EnvironmentLight loadEnvironmentImage(const std::string& path, const std::string& where, WarnOnce& warn,
                                      LoadBudget* budget);

}  // namespace tyndall
