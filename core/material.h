#pragma once
// Surface materials Tyndall renders. Specular ones (mirror, dielectric) continue camera and photon
// paths deterministically or by a Fresnel choice when smooth, by sampling a GGX lobe when rough
// (isGlossy(): docs/algorithm.md, "Glossy vertices"); diffuse ones store surface photons and end
// camera paths with a photon density estimate; Interface is an invisible boundary that only
// switches the medium (index-matched, e.g. the hull of a fog volume). Plastic is the dielectric
// specular layer over diffuse (core/coated_diffuse.h; glTF's non-metals), optionally mixed with a
// conductor (glTF metallic in (0, 1)): docs/algorithm.md "Coated (plastic) vertices".
#include <string>

#include "core/math.h"
#include "core/texture.h"

namespace tyndall {

enum class MaterialType { Diffuse, Mirror, Dielectric, Interface, Plastic };

/// glTF alphaMode: Mask cuts out where alpha < alphaCutoff; Blend lets a ray through with
/// probability 1 - alpha (stochastic transparency). Both act in Embree's intersection filter
/// (cpu/embree_scene.cpp), so camera rays, photons and shadow rays all see the same cut-outs.
enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    /// diffuse reflectance; mirror reflectance; dielectric transmission tint; plastic: the base's
    /// diffuse reflectance and the metal part's F0
    Rgb albedo{0.8f};
    float ior = 1.5f;    ///< dielectric: index inside the mesh relative to outside; plastic: the coat's index
    float alpha = 1.0f;      ///< glTF baseColorFactor alpha (coverage), x baseColorTexture alpha
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  ///< Mask only
    /// glTF metallicFactor, [0, 1]. Plastic: at each path vertex the conductor lobe (F0 = albedo)
    /// is taken with probability metallic (x metallicRoughnessTexture B), the coated one otherwise.
    /// Other types: informational (the type decides).
    float metallic = 0.0f;
    /// Mirror, Dielectric, Plastic: glTF roughnessFactor (perceptual; GGX alpha = roughness^2), [0, 1].
    /// Up to kSmoothRoughness the surface (a plastic's coat and metal) is an exact delta lobe;
    /// above it a GGX lobe (isRough).
    float roughness = 0.0f;
    Rgb emission{0.0f};  ///< emitted radiance (W m^-2 sr^-1) from the front face; makes an area light
    /// Dielectric only: KHR_materials_transmission's factor, (0, 1]. Where the transmission at a
    /// point (this x transmissionTexture R) is t < 1, the surface is a mix: the dielectric lobe with
    /// probability t, else the diffuse base (albedo); chosen per path vertex (docs/algorithm.md).
    float transmission = 1.0f;
    /// Dielectric only: a thin-walled sheet (a soap film, a bulb's wall, a window pane; glTF's
    /// transmission without a volume) instead of the boundary of a solid. Smooth: light reflects with
    /// the slab's reflectance R' = R + T^2 R / (1 - R^2) (Fresnel R = 1 - T at the incident angle,
    /// the internal bounces summed: fresnelThinSlab) and goes straight through with 1 - R' times the
    /// tint, without refraction. Rough (a frosted pane): the same split per GGX microfacet, the
    /// transmitted light spread as the reflected is (RoughDielectric::thin, core/microfacet.h).
    /// Crossing still switches between the mesh's exterior and interior media (a closed thin mesh
    /// can hold smoke).
    bool thin = false;
    /// glTF normalTexture scale: multiplies the tangent-space normal's x and y.
    float normalScale = 1.0f;

    // Textures (glTF's slots; core/material_eval.h reads them). Each multiplies its factor above.
    TextureRef baseColorTexture;          ///< sRGB RGB x albedo, alpha x baseColor alpha
    TextureRef emissiveTexture;           ///< sRGB RGB x emission
    TextureRef metallicRoughnessTexture;  ///< linear: G x roughness, B x metallic (glTF's packing)
    /// Linear, tangent space (glTF): n = normalize((2 rgb - 1) x (normalScale, normalScale, 1)) in
    /// the frame (T, B, N) of the mesh's tangents (TriangleMesh::tangents) and shading normal.
    TextureRef normalTexture;
    TextureRef transmissionTexture;       ///< linear: R x transmission

    bool isTextured() const {
        return baseColorTexture.present() || emissiveTexture.present() || metallicRoughnessTexture.present() ||
               transmissionTexture.present();
    }
    /// The shading normal comes from a normal map (every stage then shades with it, diffuse included).
    bool isNormalMapped() const { return normalTexture.present(); }
    /// A dielectric that is partly the diffuse base somewhere: each vertex chooses its lobe.
    bool isPartlyTransmissive() const {
        return type == MaterialType::Dielectric && (transmission < 1.0f || transmissionTexture.present());
    }

    static constexpr float kSmoothRoughness = 0.05f;

    /// Mirror or dielectric, smooth (delta) or rough (glossy).
    bool isSpecular() const { return type == MaterialType::Mirror || type == MaterialType::Dielectric; }
    /// A rough mirror (GGX conductor) or rough dielectric (GGX transmission): sampled, not delta.
    bool isGlossy() const { return isSpecular() && isRough(); }
    /// GGX lobes rather than delta ones (mirror, dielectric, plastic).
    bool isRough() const { return roughness > kSmoothRoughness; }
    /// A plastic that is partly metal somewhere: each vertex chooses coat or conductor.
    bool hasMetalMix() const { return type == MaterialType::Plastic && metallic > 0.0f; }
    /// Shades with the mesh's interpolated normals (diffuse uses the geometric normal unless normal-mapped).
    bool usesVertexNormals() const { return isSpecular() || type == MaterialType::Plastic; }
    /// Surfaces a path can cross, switching medium.
    bool isTransmissive() const { return type == MaterialType::Dielectric || type == MaterialType::Interface; }
    bool isEmissive() const { return !emission.isBlack(); }
};

}  // namespace tyndall
