#pragma once
// Lights. Lights may sit inside glass or behind mirrors: photon emission never assumes a direct
// connection to anything. Area lights are emissive triangles (Material::emission) and are not
// listed here; Scene::finalize() collects them.
#include <string>

#include "core/math.h"

namespace tyndall {

enum class LightType { Point, Spot, Directional };

struct Light {
    std::string name;
    LightType type = LightType::Point;
    Vec3 position{0, 0, 0};    ///< point, spot
    Vec3 direction{0, -1, 0};  ///< spot axis / directional travel direction (unit)
    /// Point, spot: radiant intensity in W/sr (on the spot axis). Directional: irradiance in
    /// W/m^2 on a plane perpendicular to `direction`.
    Rgb intensity{1.0f};
    float cosInnerAngle = 1.0f;  ///< spot: full intensity inside this cone
    float cosOuterAngle = 0.7f;  ///< spot: zero outside; smoothstep between inner and outer

    /// Spot falloff for a direction with cosine `cosTheta` to the axis, in [0, 1].
    float spotFalloff(float cosTheta) const {
        if (cosTheta >= cosInnerAngle) return 1.0f;
        if (cosTheta <= cosOuterAngle) return 0.0f;
        float x = (cosTheta - cosOuterAngle) / std::max(cosInnerAngle - cosOuterAngle, 1e-6f);
        return x * x * (3.0f - 2.0f * x);
    }
};

}  // namespace tyndall
