#pragma once
// Photon emission: picks a light (point, spot, directional or one emissive triangle) with
// probability proportional to its power and samples an emitted ray. Used by the photon tracer.
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/scene.h"

namespace tyndall {

/// One emitted photon path start. `power` is (emitted power sample)/(pdf of choosing it): the
/// expected value of `power` over many samples is the scene's total emitted power (W).
struct EmittedPhoton {
    Ray ray;
    Rgb power;
    /// Index into Scene::lights for point/spot/directional; -1 for an area light.
    int light = -1;
    /// Area lights: the emitting mesh (the path starts in its exterior medium); else -1.
    int emitterMesh = -1;
};

class LightSampler {
public:
    explicit LightSampler(const Scene& scene);

    EmittedPhoton sample(Rng& rng) const;
    /// Total emitted power summed over all lights (W, luminance-weighted selection uses it).
    Rgb totalPower() const { return m_totalPower; }
    /// Emitted power of source `i` (lights first, then Scene::emitters).
    Rgb sourcePower(size_t i) const { return m_power[i]; }
    size_t sourceCount() const { return m_power.size(); }

    /// Power of one light as emitted into the scene (spot cone integrated, directional over the
    /// disk that covers the scene's bounding sphere).
    static Rgb lightPower(const Light& light, const Bounds3& sceneBounds);

private:
    const Scene& m_scene;
    std::vector<Rgb> m_power;
    std::vector<double> m_cdf;  // over luminance of m_power
    Rgb m_totalPower;
    Vec3 m_sceneCenter;
    float m_sceneRadius = 1.0f;
};

}  // namespace tyndall
