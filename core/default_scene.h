#pragma once
// The built-in default scene (`tyndall render` with no scene): a closed room filled with thin fog,
// a glass sphere, a small bright spot light whose beam the sphere focuses into a volumetric
// caustic, and a mirror on the back wall so secondary camera paths matter. Needs no files.
#include "core/scene.h"

namespace tyndall {

Scene makeDefaultScene();

}  // namespace tyndall
