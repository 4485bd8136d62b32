#pragma once
// Surface materials Tyndall renders. Specular ones (mirror, dielectric) continue camera and photon
// paths deterministically or by a Fresnel choice; diffuse ones store surface photons and end
// camera paths with a photon density estimate; Interface is an invisible boundary that only
// switches the medium (index-matched, e.g. the hull of a fog volume).
#include <string>

#include "core/math.h"
#include "core/texture.h"

namespace tyndall {

enum class MaterialType { Diffuse, Mirror, Dielectric, Interface };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Rgb albedo{0.8f};    ///< diffuse reflectance; mirror reflectance; dielectric transmission tint
    float ior = 1.5f;    ///< dielectric: index inside the mesh relative to outside
    float alpha = 1.0f;      ///< glTF baseColorFactor alpha (coverage)
    float metallic = 0.0f;   ///< glTF metallicFactor, [0, 1]
    float roughness = 1.0f;  ///< glTF roughnessFactor (perceptual; GGX alpha = roughness^2), [0, 1]
    Rgb emission{0.0f};  ///< emitted radiance (W m^-2 sr^-1) from the front face; makes an area light

    // Textures (glTF's slots; core/material_eval.h reads them). Each multiplies its factor above.
    TextureRef baseColorTexture;          ///< sRGB RGB x albedo, alpha x baseColor alpha
    TextureRef emissiveTexture;           ///< sRGB RGB x emission
    TextureRef metallicRoughnessTexture;  ///< linear: G x roughness, B x metallic (glTF's packing)

    bool isTextured() const {
        return baseColorTexture.present() || emissiveTexture.present() || metallicRoughnessTexture.present();
    }

    bool isSpecular() const { return type == MaterialType::Mirror || type == MaterialType::Dielectric; }
    /// Surfaces a path can cross, switching medium.
    bool isTransmissive() const { return type == MaterialType::Dielectric || type == MaterialType::Interface; }
    bool isEmissive() const { return !emission.isBlack(); }
};

}  // namespace tyndall
