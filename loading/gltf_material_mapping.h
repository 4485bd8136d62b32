#pragma once
// glTF 2.0 material -> Tyndall Material (+ interior medium): the nearest material Tyndall has.
// Kept free of tinygltf so the mapping is unit-testable; gltf_loader.cpp fills the input.
//   transmission > 0 (KHR_materials_transmission)     -> Dielectric, ior (KHR_materials_ior),
//                                                       tint = baseColorFactor, roughness (GGX
//                                                       transmission above Material::kSmoothRoughness);
//                                                       thin-walled (Material::thin) without
//                                                       KHR_materials_volume or with its
//                                                       thicknessFactor 0, as glTF says (when rough:
//                                                       rough glass bounding a solid, noted);
//                                                       transmission < 1 (or a transmissionTexture,
//                                                       read by the loader) mixes in the diffuse base
//   else metallic = 1 without metallicRoughnessTexture -> Mirror (GGX conductor when rough),
//                                                       F0 = baseColorFactor
//   else                                              -> Plastic: the dielectric specular layer
//                                                       (ior, roughness) over the diffuse base
//                                                       baseColorFactor, mixed per point with the
//                                                       conductor by metallic (x texture B)
//   emissiveFactor * emissiveStrength                 -> emission (radiance, W m^-2 sr^-1)
//   KHR_materials_volume on a solid Dielectric        -> absorbing medium inside the mesh:
//        sigma_a = -ln(attenuationColor) / attenuationDistance, sigma_s = 0
// Everything else is approximated or ignored, and each such case is reported in `notes`
// (the loader warns once per kind). docs/scene-format.md has the full table.
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/material.h"
#include "core/medium.h"

namespace tyndall {

/// The glTF values the mapping reads; defaults are glTF's.
struct GltfMaterialInput {
    std::string where;  ///< "<file>: material 'name' (index i)", prefix of errors and notes
    std::string name;
    Rgb baseColor{1.0f};
    float alpha = 1.0f;
    float metallic = 1.0f;
    float roughness = 1.0f;
    Rgb emissive{0.0f};
    float emissiveStrength = 1.0f;  ///< KHR_materials_emissive_strength
    float transmission = 0.0f;      ///< KHR_materials_transmission
    float ior = 1.5f;               ///< KHR_materials_ior
    bool metallicRoughnessTexture = false;  ///< present: metallic varies per point (not a pure metal)
    bool hasVolume = false;         ///< KHR_materials_volume present
    float attenuationDistance = std::numeric_limits<float>::infinity();
    Rgb attenuationColor{1.0f};
    float thickness = 0.0f;
    std::string alphaMode = "OPAQUE";
    float alphaCutoff = 0.5f;
    std::vector<std::string> textures;  ///< names of the texture slots in use ("baseColorTexture", ...)
};

/// One approximation: `kind` groups warnings ("warn once per kind"), `message` names the material.
struct GltfNote {
    std::string kind;
    std::string message;
};

struct GltfMaterialMapping {
    Material material;
    std::optional<Medium> interior;  ///< from KHR_materials_volume
    std::vector<GltfNote> notes;
};

/// Throws Error "<where>: ..." for values outside glTF's ranges (negative, NaN, > 1 factors,
/// attenuationDistance <= 0, ior < 1).
GltfMaterialMapping mapGltfMaterial(const GltfMaterialInput& in);

}  // namespace tyndall
