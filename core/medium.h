#pragma once
// Participating media. Coefficients are per scene unit (1/m when the scene is in metres).
//
// Homogeneous (density == nullptr): sigma_s, sigma_a are RGB constants, transmittance is the
// analytic exp(-sigma_t t) per channel.
// Heterogeneous (density != nullptr): sigma_x(p) = density(p) * sigma_x. The extinction must be
// grey (sigma_s + sigma_a equal in all channels; colour comes from the albedo) so that one set of
// free-flight distances serves all channels; Scene::validate() enforces this.
#include <memory>
#include <string>

#include "core/density_grid.h"
#include "core/math.h"

namespace tyndall {

struct Medium {
    std::string name;
    Rgb sigmaS{0.1f};  ///< scattering coefficient (at density 1 for grid media)
    Rgb sigmaA{0.0f};  ///< absorption coefficient (at density 1 for grid media)
    float g = 0.0f;    ///< Henyey-Greenstein asymmetry in (-1, 1)
    std::shared_ptr<const DensityGrid> density;  ///< null for homogeneous media

    bool homogeneous() const { return density == nullptr; }
    Rgb sigmaT() const { return sigmaS + sigmaA; }
    Rgb albedo() const {
        Rgb t = sigmaT();
        return {t.r > 0 ? sigmaS.r / t.r : 0, t.g > 0 ? sigmaS.g / t.g : 0, t.b > 0 ? sigmaS.b / t.b : 0};
    }
    /// Scattering coefficient at `p` (the constant for homogeneous media).
    Rgb sigmaSAt(const Vec3& p) const { return density ? sigmaS * density->density(p) : sigmaS; }
    /// Analytic transmittance over distance `t` (homogeneous only).
    Rgb transmittance(float t) const {
        Rgb st = sigmaT();
        return exp(Rgb(-st.r * t, -st.g * t, -st.b * t));
    }
};

/// Index of a medium in Scene::media; kVacuum for none.
using MediumId = int;
constexpr MediumId kVacuum = -1;

}  // namespace tyndall
