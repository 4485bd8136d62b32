#include "loading/gltf_material_mapping.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace tyndall {

namespace {
void checkUnit(const std::string& where, const char* what, float v) {
    if (!(v >= 0.0f && v <= 1.0f)) {
        std::ostringstream s;
        s << where << ": " << what << " must lie in [0, 1], got " << v;
        throw Error(s.str());
    }
}
void checkUnit(const std::string& where, const char* what, const Rgb& c) {
    for (int i = 0; i < 3; ++i) checkUnit(where, what, c[i]);
}
}  // namespace

GltfMaterialMapping mapGltfMaterial(const GltfMaterialInput& in) {
    const std::string& at = in.where;
    checkUnit(at, "baseColorFactor", in.baseColor);
    checkUnit(at, "baseColorFactor alpha", in.alpha);
    checkUnit(at, "metallicFactor", in.metallic);
    checkUnit(at, "roughnessFactor", in.roughness);
    checkUnit(at, "emissiveFactor", in.emissive);
    checkUnit(at, "KHR_materials_transmission transmissionFactor", in.transmission);
    if (!(in.emissiveStrength >= 0.0f) || !std::isfinite(in.emissiveStrength))
        throw Error(at + ": KHR_materials_emissive_strength emissiveStrength must be a finite number >= 0");
    if (!(in.ior >= 1.0f) || !std::isfinite(in.ior))
        throw Error(at + ": KHR_materials_ior ior must be a finite number >= 1");
    if (in.hasVolume) {
        if (!(in.attenuationDistance > 0.0f))
            throw Error(at + ": KHR_materials_volume attenuationDistance must be > 0");
        checkUnit(at, "KHR_materials_volume attenuationColor", in.attenuationColor);
        if (!(in.thickness >= 0.0f) || !std::isfinite(in.thickness))
            throw Error(at + ": KHR_materials_volume thicknessFactor must be a finite number >= 0");
    }

    GltfMaterialMapping out;
    Material& m = out.material;
    m.name = in.name;
    auto note = [&](const std::string& kind, const std::string& what) {
        out.notes.push_back({kind, at + ": " + what});
    };

    if (in.transmission > 0.0f) {
        // glTF's mix: the dielectric lobe with weight transmission (x transmissionTexture R), the
        // diffuse base with the rest (Material::isPartlyTransmissive).
        m.type = MaterialType::Dielectric;
        m.albedo = in.baseColor;
        m.ior = in.ior;
        m.transmission = in.transmission;
        // glTF: without KHR_materials_volume, or with a thicknessFactor of 0, the material is
        // thin-walled (no refraction, no volume).
        m.thin = !in.hasVolume || in.thickness == 0.0f;
    } else if (in.metallic >= 1.0f && !in.metallicRoughnessTexture) {
        m.type = MaterialType::Mirror;  // a GGX conductor when roughness > Material::kSmoothRoughness
        m.albedo = in.baseColor;
    } else {
        // glTF's non-metal: a dielectric coat at the material's ior over the diffuse base; with
        // metallic > 0 (factor x texture B) mixed per point with the conductor (F0 = baseColor).
        m.type = MaterialType::Plastic;
        m.albedo = in.baseColor;
        m.ior = in.ior;
    }
    m.emission = in.emissive * in.emissiveStrength;
    m.alpha = in.alpha;
    m.metallic = in.metallic;
    m.roughness = in.roughness;

    if (in.hasVolume) {
        if (m.type != MaterialType::Dielectric) {
            note("volume without transmission", "KHR_materials_volume ignored: the material is not transmissive");
        } else if (m.thin) {
            if (std::isfinite(in.attenuationDistance))
                note("thin-walled volume", "KHR_materials_volume ignored: thicknessFactor 0 makes the material thin-walled");
        } else if (std::isfinite(in.attenuationDistance)) {
            Medium med;
            med.name = in.name + " volume";
            med.sigmaS = Rgb(0.0f);
            med.g = 0.0f;
            for (int c = 0; c < 3; ++c)  // a colour of 0 would absorb infinitely: clamp
                med.sigmaA[c] = -std::log(std::max(in.attenuationColor[c], 1e-6f)) / in.attenuationDistance;
            out.interior = med;
        }
    }
    m.alphaMode = in.alphaMode == "MASK" ? AlphaMode::Mask : in.alphaMode == "BLEND" ? AlphaMode::Blend : AlphaMode::Opaque;
    m.alphaCutoff = in.alphaCutoff;
    if (in.alphaMode != "OPAQUE" && in.alphaMode != "MASK" && in.alphaMode != "BLEND")
        throw Error(at + ": alphaMode must be OPAQUE, MASK or BLEND, got '" + in.alphaMode + "'");
    for (const std::string& t : in.textures) note("texture " + t, t + " ignored: the factor alone is used");
    return out;
}

}  // namespace tyndall
