#include "core/scene_file.h"

#include "core/error.h"

namespace tyndall {

Scene loadSceneFile(const std::string& path) {
    // Scene files arrive with the glTF / scene-format issue; until then only the default scene.
    throw Error("scene '" + path + "': loading scene files is not implemented yet; run without SCENE for the default scene");
}

}  // namespace tyndall
