#pragma once
// glTF 2.0 -> SceneDraft through tinygltf (Debian's compiled libtinygltf; tiny_gltf.h stays in
// the .cpp). What is read and how it maps is documented in docs/scene-format.md ("glTF mapping"):
// the default scene's node hierarchy with transforms, triangle primitives, cameras (perspective),
// KHR_lights_punctual, and materials through mapGltfMaterial (gltf_material_mapping.h).
#include <string>

#include "loading/scene_assembly.h"

namespace tyndall {

/// `bytes`: the .gltf JSON text or .glb contents (`binary`); `file` names it in messages;
/// external buffers and images resolve against `baseDir`. Throws Error naming the file and the
/// node/mesh/material/accessor at fault.
SceneDraft importGltf(const std::string& bytes, bool binary, const std::string& file, const std::string& baseDir,
                      const SceneLoadOptions& options, WarnOnce& warn);

}  // namespace tyndall
