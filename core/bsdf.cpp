#include "core/bsdf.h"

namespace tyndall {

Bsdf::Framed Bsdf::buildFramed(const Material& mat, float roughness, Rgb baseColor, bool metal, HitSide side, Vec3 ns,
                               Vec3 wo) {
    Framed f;
    roughness = std::max(roughness, Material::kSmoothRoughness);
    if (mat.type == MaterialType::Plastic && !metal) {
        f.kind = Kind::Coated;
        f.lobes = kLobeReflection | kLobeDiffuse | (mat.isRough() ? kLobeGlossy : kLobeSpecular);
        f.parts.local.frame = Frame(side.nsf);
        f.component.coat = CoatedDiffuse::make(roughness, !mat.isRough(), mat.ior, baseColor);
    } else {
        // Conductors reflect on the side the path arrives from; dielectrics use the exterior side
        // (+z = the hit's ns) so eta = interior / exterior holds from both sides.
        const Ggx ggx = Ggx::fromRoughness(roughness);
        if (mat.type == MaterialType::Mirror || mat.type == MaterialType::Plastic) {
            f.kind = Kind::Conductor;
            f.lobes = kLobeReflection | kLobeGlossy;
            f.parts.local.frame = Frame(side.nsf);
            f.component.metal = RoughConductor{ggx, baseColor};
        } else {
            f.kind = Kind::RoughDielectric;
            f.lobes = kLobeReflection | kLobeTransmission | kLobeGlossy;
            f.parts.local.frame = Frame(ns);
            f.component.glass = RoughDielectric{ggx, mat.ior, baseColor, mat.thin};
        }
    }
    f.parts.local.wo = f.parts.local.frame.toLocal(wo);
    return f;
}

}  // namespace tyndall
