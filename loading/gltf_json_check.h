#pragma once
// Type check of a glTF file's JSON before tinygltf reads it. tinygltf 2.7.0 silently skips a
// property of the wrong type ("mesh": "0" drops the geometry, "translation": "x" becomes the
// identity, a light's "intensity": "bright" becomes 1, "mesh": 1.0 is not an integer to it and
// 4294967296 wraps to 0), so every glTF property Tyndall reads (docs/scene-format.md, "glTF
// mapping") is checked here first:
//   scene, scenes[].nodes; nodes[]: mesh, camera, skin, children, matrix (16 numbers),
//     translation (3), rotation (4), scale (3), extensions.KHR_lights_punctual.light;
//   meshes[].primitives[]: attributes (object of indices), indices, material, mode, targets;
//   accessors[]: bufferView, byteOffset, componentType, normalized, count, type, sparse.{count,
//     indices.{bufferView, byteOffset, componentType}, values.{bufferView, byteOffset}};
//   bufferViews[]: buffer, byteOffset, byteLength, byteStride; buffers[]: uri, byteLength;
//   images[]: uri, bufferView, mimeType;
//   materials[]: pbrMetallicRoughness.{baseColorFactor (4), metallicFactor, roughnessFactor},
//     emissiveFactor (3), alphaMode, the texture slots' index, and the values of
//     KHR_materials_emissive_strength, _transmission, _ior and _volume (attenuationColor: 3);
//   cameras[]: type, perspective.{yfov, znear, zfar, aspectRatio}, orthographic.{xmag, ymag,
//     znear, zfar}; extensions.KHR_lights_punctual.lights[]: type, color (3), intensity, range,
//     spot.{innerConeAngle, outerConeAngle}; extensionsUsed, extensionsRequired; every `name`.
// Indices must be integers in [0, 2^31 - 1], byte sizes and counts non-negative integers; ranges
// of values (colours in [0, 1], intensity >= 0, indices against what they index) are the
// importer's job (gltf_loader.cpp). Unknown keys, `extras` and other extensions are allowed, as
// glTF allows them. Throws Error with one line:
//     <file>: <glTF path>: expected <what>, got <what was there>
// e.g. "car.gltf: nodes[3].translation: expected an array of 3 numbers, got the string \"x\"".
// Text that is not JSON (or a .glb without a readable JSON chunk) is left for tinygltf to report.
// Internal to loading/; called by importGltf. Pure functions of their arguments (thread-safe).
#include <nlohmann/json.hpp>
#include <string>

namespace tyndall {

/// The JSON of a glTF file: `bytes` is the .gltf text, or the .glb contents (`binary`: its JSON
/// chunk). A discarded value (is_discarded()) when it is not readable JSON.
nlohmann::json gltfJsonOf(const std::string& bytes, bool binary);
/// Checks `root` (from gltfJsonOf, not discarded) as above; `file` names the file in messages.
void checkGltfJson(const nlohmann::json& root, const std::string& file);

}  // namespace tyndall
