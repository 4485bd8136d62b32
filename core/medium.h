#pragma once
// Participating media. Coefficients are per scene unit (1/m when the scene is in metres).
//
// Homogeneous (density == nullptr): sigma_s, sigma_a are RGB constants, transmittance is the
// analytic exp(-sigma_t t) per channel.
// Heterogeneous (density != nullptr): sigma_x(p) = density(p) * sigma_x. The extinction must be
// grey (sigma_s + sigma_a equal in all channels; colour comes from the albedo) so that one set of
// free-flight distances serves all channels; Scene::validate() enforces this.
//
// Emission (fire, glowing gas; pbrt-v4's convention): the radiative transfer source term is
// sigma_a(p) Le(p), so a medium emits only where it absorbs. Le is `emission` (a constant) or,
// when `emissionField` is set, emissionField->radiance(p) (an emission or temperature grid), times
// `emissionScale` (1 as loaded; the viewer's emission slider sets it).
// Along a ray through a homogeneous medium the emitted radiance reaching the ray's origin from
// [0, d] is sigma_a Le (1 - exp(-sigma_t d)) / sigma_t; the tracers estimate the same integral in
// grid media at the tracking's tentative collisions (cpu/free_flight.h).
#include <memory>
#include <string>

#include "core/density_grid.h"
#include "core/math.h"

namespace tyndall {

/// Le(p) of an emissive grid medium (W m^-2 sr^-1), >= 0 and finite everywhere; safe to call
/// from many threads at once. Implemented by loading/vdb_emission.h (emission and temperature
/// grids) and by tests.
class EmissionField {
public:
    virtual ~EmissionField() = default;
    virtual Rgb radiance(const Vec3& p) const = 0;
    /// `h` mixed with the whole field, for the resume check (DensityGrid::contentHash). The
    /// default hashes radiance() at the centres of a 32^3 lattice over `where` (the medium's
    /// density bounds); GridEmission hashes its grid and parameters.
    virtual uint64_t contentHash(uint64_t h, const Bounds3& where) const;
};

struct Medium {
    std::string name;
    Rgb sigmaS{0.1f};  ///< scattering coefficient (at density 1 for grid media)
    Rgb sigmaA{0.0f};  ///< absorption coefficient (at density 1 for grid media)
    float g = 0.0f;    ///< Henyey-Greenstein asymmetry in (-1, 1)
    std::shared_ptr<const DensityGrid> density;  ///< null for homogeneous media
    Rgb emission{0.0f};  ///< Le where emissionField is null (W m^-2 sr^-1)
    std::shared_ptr<const EmissionField> emissionField;  ///< Le(p) of a grid medium; null = `emission`
    float emissionScale = 1.0f;  ///< multiplies Le, finite and >= 0

    bool homogeneous() const { return density == nullptr; }
    Rgb sigmaT() const { return sigmaS + sigmaA; }
    Rgb albedo() const {
        Rgb t = sigmaT();
        return {t.r > 0 ? sigmaS.r / t.r : 0, t.g > 0 ? sigmaS.g / t.g : 0, t.b > 0 ? sigmaS.b / t.b : 0};
    }
    /// Scattering coefficient at `p` (the constant for homogeneous media).
    Rgb sigmaSAt(const Vec3& p) const { return density ? sigmaS * density->density(p) : sigmaS; }
    /// True when the medium emits: it absorbs and has an emission.
    bool emissive() const {
        return !sigmaA.isBlack() && emissionScale > 0 && (emissionField || !emission.isBlack());
    }
    /// The constant Le (homogeneous media, or grid media without a field), scale applied.
    Rgb constantEmission() const { return emission * emissionScale; }
    /// Le at `p` (before sigma_a), scale applied.
    Rgb emissionAt(const Vec3& p) const {
        return (emissionField ? emissionField->radiance(p) : emission) * emissionScale;
    }
    /// The source term sigma_a(p) Le(p) (W m^-3 sr^-1).
    Rgb sourceAt(const Vec3& p) const {
        if (!density) return sigmaA * constantEmission();
        const float d = density->density(p);
        return d > 0 ? sigmaA * d * emissionAt(p) : Rgb(0.0f);
    }
    /// Analytic transmittance over distance `t` (homogeneous only).
    Rgb transmittance(float t) const {
        Rgb st = sigmaT();
        if (st.r == st.g && st.r == st.b) return Rgb(std::exp(-st.r * t));  // grey: one exp, the same values
        return exp(Rgb(-st.r * t, -st.g * t, -st.b * t));
    }
};

/// Index of a medium in Scene::media; kVacuum for none.
using MediumId = int;
constexpr MediumId kVacuum = -1;

}  // namespace tyndall
