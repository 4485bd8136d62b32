#pragma once
// Internal to the scene loaders (scene_file.cpp, scene_json.cpp, gltf_loader.cpp): the scene
// being assembled, its candidate cameras, and the steps every format ends with.
#include <string>
#include <vector>

#include "core/scene.h"
#include "loading/scene_file.h"

namespace tyndall {

struct NamedCamera {
    std::string name;
    Camera camera;
};

/// A scene before finishing: meshes/materials/media/lights filled in, cameras still to choose.
struct SceneDraft {
    Scene scene;
    std::vector<NamedCamera> cameras;
    /// A plain glTF file without lights, emissive surfaces or an environment (--environment) gets
    /// a point light at the camera (a "headlight", warned about) instead of the error a scene
    /// description would get.
    bool headlightWhenDark = false;
};

/// Indices of the meshes a reference by name selects: meshes named `name`, and the primitives
/// "name#k" of a multi-primitive glTF mesh.
std::vector<int> meshesNamed(const Scene& scene, const std::string& name);

/// A camera that frames `bounds` from the front (+z), slightly above, 40 degree vertical fov.
Camera frameBounds(const Bounds3& bounds);

/// The last steps of every load: open transmissive meshes become thin sheets (same medium on
/// both sides), the camera is chosen (options.camera), the headlight added if asked for, the
/// scene finalized and validated and its triangle count checked. `file` names the source.
SceneFile finishScene(SceneDraft draft, const std::string& file, const SceneLoadOptions& options, WarnOnce& warn);

/// Throws Error when `n` triangles would exceed options.maxTriangles.
void checkTriangleBudget(size_t n, const SceneLoadOptions& options, const std::string& where);

}  // namespace tyndall
