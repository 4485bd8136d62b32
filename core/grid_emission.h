#pragma once
// Le(p) of a grid medium from a scalar grid (an emission or temperature channel of a simulation,
// read from the same OpenVDB file as the density or built procedurally). The scalar field
// is v(p) = ambient + values(p): values any DensityGrid (trilinear, >= 0: OpenVDB grids clamp
// negative voxels to 0, and read 0 outside their voxels), ambient >= 0 the field's value away
// from its voxels (a grid file's positive background, e.g. an ambient temperature; 0 for most).
// It need not share the density's resolution or transform, since both are sampled at world
// points. Away from its voxels Le is the ambient value's, but the source term sigma_a(p) Le(p)
// is zero wherever the density is, so the field never emits outside the medium's density however
// far its own domain reaches.
//   colour:    Le(p) = scale * color * v(p)
//   blackbody: Le(p) = scale * blackbodyRgb(T),  T = (v(p) - temperatureOffset) * temperatureScale
//              kelvin (pbrt-v4's order); T <= 0 emits nothing (core/blackbody.h for the colour
//              and its normalisation).
// The medium's source term is sigma_a(p) Le(p) (core/medium.h).
#include <memory>

#include "core/blackbody.h"
#include "core/density_grid.h"
#include "core/medium.h"

namespace tyndall {

class GridEmission : public EmissionField {
public:
    struct Blackbody {
        float scale = 1.0f;
        float temperatureScale = 1.0f;
        float temperatureOffset = 0.0f;
    };
    /// Colour mode. `color` and `scale` finite and >= 0 (the loader checks).
    GridEmission(std::shared_ptr<const DensityGrid> values, Rgb color, float scale, float ambient = 0.0f)
        : m_values(std::move(values)), m_color(color * scale), m_ambient(ambient) {}
    /// Blackbody mode.
    GridEmission(std::shared_ptr<const DensityGrid> values, const Blackbody& b, float ambient = 0.0f)
        : m_values(std::move(values)), m_blackbody(true), m_bb(b), m_ambient(ambient) {}

    Rgb radiance(const Vec3& p) const override {
        const float v = m_ambient + m_values->density(p);
        if (!m_blackbody) return m_color * v;
        return blackbodyRgb((v - m_bb.temperatureOffset) * m_bb.temperatureScale) * m_bb.scale;
    }
    /// The values grid's content hash and every parameter above (core/field_hash.cpp).
    uint64_t contentHash(uint64_t h, const Bounds3& where) const override;
    const DensityGrid& values() const { return *m_values; }
    bool blackbody() const { return m_blackbody; }
    float ambient() const { return m_ambient; }

private:
    std::shared_ptr<const DensityGrid> m_values;
    Rgb m_color;
    bool m_blackbody = false;
    Blackbody m_bb;
    float m_ambient = 0;
};

}  // namespace tyndall
