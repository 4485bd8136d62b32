#include "core/bsdf.h"

namespace tyndall {

void Bsdf::buildFramed(const Material& mat, const SurfacePoint& sp, bool metal) {
    const float roughness = std::max(sp.roughness, Material::kSmoothRoughness);
    if (mat.type == MaterialType::Plastic && !metal) {
        m_kind = Kind::Coated;
        m_lobes = kLobeReflection | kLobeDiffuse | (mat.isRough() ? kLobeGlossy : kLobeSpecular);
        m_parts.local.frame = Frame(m_side.nsf);
        m_component.coat = CoatedDiffuse::make(roughness, !mat.isRough(), mat.ior, sp.baseColor);
    } else {
        // Conductors reflect on the side the path arrives from; dielectrics use the exterior side
        // (+z = the hit's ns) so eta = interior / exterior holds from both sides.
        const Ggx ggx = Ggx::fromRoughness(roughness);
        if (mat.type == MaterialType::Mirror || mat.type == MaterialType::Plastic) {
            m_kind = Kind::Conductor;
            m_lobes = kLobeReflection | kLobeGlossy;
            m_parts.local.frame = Frame(m_side.nsf);
            m_component.metal = RoughConductor{ggx, sp.baseColor};
        } else {
            m_kind = Kind::RoughDielectric;
            m_lobes = kLobeReflection | kLobeTransmission | kLobeGlossy;
            m_parts.local.frame = Frame(m_ns);
            m_component.glass = RoughDielectric{ggx, mat.ior, sp.baseColor, mat.thin};
        }
    }
    m_parts.local.wo = m_parts.local.frame.toLocal(m_wo);
}

}  // namespace tyndall
