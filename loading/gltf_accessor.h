#pragma once
// Bounds-checked reading of glTF accessors (tinygltf parses the JSON but does not check that an
// accessor fits its buffer view and buffer, nor index ranges): every offset, stride, count and
// index is checked before any byte is read, and any mismatch throws Error naming `where` and the
// accessor. Handles all component types (normalised integers included, so KHR_mesh_quantization
// works), byte strides, accessors without a buffer view (zeros) and sparse accessors.
// Internal to loading/: includes tiny_gltf.h.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tyndall {

class LoadBudget;

/// Throws Error "WHERE: KIND index INDEX out of range (the file has COUNT[ PLURAL])" unless
/// 0 <= index < count: the one message for every glTF index (a node's mesh, an accessor, ...).
void checkGltfIndex(const std::string& where, const char* kind, int64_t index, size_t count,
                    const char* plural = "");

/// Accessor `index` as `components` floats per element (count * components values).
/// `components`: 1, 2, 3 or 4 (SCALAR, VEC2, VEC3, VEC4); other accessor types throw. More than
/// `maxElements` elements is an error; `budget` (may be null) is asked for the declared count x
/// element size after the accessor is found to fit its buffer view, before anything is allocated.
std::vector<float> readGltfFloats(const tinygltf::Model& model, int index, int components, const std::string& where,
                                  size_t maxElements, LoadBudget* budget);
/// Accessor `index` as vertex indices (SCALAR of unsigned byte, short or int).
std::vector<uint32_t> readGltfIndices(const tinygltf::Model& model, int index, const std::string& where,
                                      size_t maxElements, LoadBudget* budget);

}  // namespace tyndall
