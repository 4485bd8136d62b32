#pragma once
// The built-in default scene (`tyndall render` with no scene): a closed room filled with thin fog,
// a glass sphere, a small bright spot light whose beam the sphere focuses into a volumetric
// caustic, and a mirror on the back wall so secondary camera paths matter. Needs no files.
#include "core/scene.h"
#include <nlohmann/json_fwd.hpp>

namespace tyndall {

Scene makeDefaultScene();

/// The default scene's "render" block (RenderSettings JSON keys; scenes/caustic-box.json has the
/// same): surface photons gathered over 0.3 units (about 4% of the room's diagonal instead of the
/// usual 2%), so that the dimly lit walls of the first picture a user sees are smooth rather than
/// speckled after the default 64 passes.
nlohmann::json defaultSceneRender();

}  // namespace tyndall
