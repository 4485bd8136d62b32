#pragma once
// Single scattering from point and spot lights along a camera segment inside a homogeneous
// medium, by equiangular sampling (core/equiangular.h; docs/algorithm.md "Single scattering by
// equiangular sampling"). For the segment o + s d, s in [0, sMax], and each such light (position
// p, intensity I, spot falloff F), one point x = o + s d is drawn and
//   L = sigma_s p_HG(w_l . -d) I F / |x - p|^2 Tr_light(p -> x) Tr_cam(0 -> s) / pdf(s)
// with w_l the light's travel direction (p -> x), Tr_light a shadow ray's transmittance
// (cpu/direct_light.h: analytic, or ratio tracking through grid media on the way, through
// Interfaces, blocked by every other surface) and Tr_cam the segment's own, analytic. For a spot
// the segment is first clipped to the spot's outer cone. Unbiased for the light that reaches the
// segment from these lights with no scattering vertex on the way: the light the photon tracer's
// unscattered first beams in homogeneous media carry, which it then leaves out
// (RenderSettings::equiangular), so nothing counts twice. Directional lights, area lights, the
// environment and every light's beams in density-grid media are kept.
//
// Up to kEveryLightUpTo such lights each get a sample; beyond, one light is chosen per segment in
// proportion to its power. Randomness only from the caller's stream.
#include <vector>

#include "core/rng.h"
#include "cpu/embree_scene.h"

namespace tyndall {

class EquiangularScattering {
public:
    /// Keeps a reference to `rt` (it must outlive this); reads the scene's lights now.
    explicit EquiangularScattering(const EmbreeScene& rt);

    /// True for the lights this estimator stands for (point and spot): their unscattered beams
    /// must not be stored when it is used.
    static bool handles(const Light& light) { return light.type == LightType::Point || light.type == LightType::Spot; }
    /// The media it estimates in: homogeneous ones. In a density grid the step estimate of the
    /// camera's transmittance and the density's own variation (sampled by nothing here) made it
    /// noisier than the beams at equal time (docs/performance.md), so grid media keep their beams.
    static bool estimatesIn(const Medium& medium) { return medium.homogeneous(); }
    /// False when the scene has no such light of non-zero intensity (nothing to estimate).
    bool any() const { return !m_lights.empty(); }

    /// The single-scattered radiance arriving at `o` along -d from the segment o + s d, s in
    /// [0, sMax], inside `medium`, before the camera path's throughput. `freeFlights` (n distances
    /// from `o`) would be the segment's stored transmittance samples in a grid medium (0 there:
    /// estimatesIn). Draws from `rng`: one uniform per light sampled (two with more than
    /// kEveryLightUpTo lights), then the shadow ray's.
    Rgb estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax, const float* freeFlights, int n,
                 Rng& rng) const;

    static constexpr size_t kEveryLightUpTo = 8;

private:
    Rgb fromLight(const Light& light, const Medium& med, MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                  const float* freeFlights, int n, Rng& rng) const;

    const EmbreeScene& m_rt;
    std::vector<int> m_lights;     ///< indices into Scene::lights
    std::vector<double> m_cdf;     ///< over the luminance of their powers, normalised
};

}  // namespace tyndall
