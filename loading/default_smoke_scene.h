#pragma once
// The built-in heterogeneous scene: the default caustic box (loading/default_scene.h) with its fog
// replaced by the procedural OpenVDB smoke plume (loading/procedural_media.h), which the glass
// sphere's focused spot beam cuts through. Used by `tyndall compare` without a scene and by the
// benchmark's heterogeneous case. Needs no files.
#include "core/scene.h"

namespace tyndall {

Scene makeDefaultSmokeScene();

}  // namespace tyndall
