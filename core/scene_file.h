#pragma once
// Loading scene files (.json scene description, .gltf, .glb) into a Scene.
#include <string>

#include "core/scene.h"

namespace tyndall {

/// Throws Error naming the file and the place in it.
Scene loadSceneFile(const std::string& path);

}  // namespace tyndall
