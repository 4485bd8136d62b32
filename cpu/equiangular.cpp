#include "cpu/equiangular.h"

#include <algorithm>

#include "core/equiangular.h"
#include "core/light_sampler.h"
#include "core/phase.h"
#include "core/transmittance.h"
#include "cpu/direct_light.h"

namespace tyndall {

EquiangularScattering::EquiangularScattering(const EmbreeScene& rt) : m_rt(rt) {
    const Scene& scene = rt.scene();
    double total = 0;
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& l = scene.lights[i];
        if (!handles(l)) continue;
        const double power = LightSampler::lightPower(l, scene.bounds).luminance();
        if (!(power > 0)) continue;
        m_lights.push_back(int(i));
        total += power;
        m_cdf.push_back(total);
    }
    for (double& c : m_cdf) c /= total;
}

Rgb EquiangularScattering::estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                                    const float* freeFlights, int n, Rng& rng) const {
    if (m_lights.empty() || medium == kVacuum || !(sMax > 0)) return Rgb(0.0f);
    const Scene& scene = m_rt.scene();
    const Medium& med = scene.media[medium];
    if (!estimatesIn(med) || med.sigmaS.isBlack()) return Rgb(0.0f);
    Rgb sum;
    if (m_lights.size() <= kEveryLightUpTo) {
        for (int i : m_lights) sum += fromLight(scene.lights[size_t(i)], med, medium, o, d, sMax, freeFlights, n, rng);
        return sum;
    }
    const double u = rng.uniform();
    const size_t k = std::min(size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u) - m_cdf.begin()), m_cdf.size() - 1);
    const double p = m_cdf[k] - (k > 0 ? m_cdf[k - 1] : 0.0);
    return fromLight(scene.lights[size_t(m_lights[k])], med, medium, o, d, sMax, freeFlights, n, rng) * float(1.0 / p);
}

Rgb EquiangularScattering::fromLight(const Light& light, const Medium& med, MediumId medium, const Vec3& o,
                                     const Vec3& d, float sMax, const float* freeFlights, int n, Rng& rng) const {
    float a = 0, b = sMax;
    if (light.type == LightType::Spot &&
        !clipToCone(o, d, light.position, light.direction, light.cosOuterAngle, &a, &b))
        return Rgb(0.0f);
    const EquiangularSample s = sampleEquiangular(o, d, a, b, light.position, rng.uniform());
    if (!(s.inverseSquareOverPdf > 0)) return Rgb(0.0f);
    const Vec3 x = o + d * s.t;
    const Vec3 toLight = light.position - x;
    const float dist = length(toLight);
    if (!(dist > 0)) return Rgb(0.0f);
    const Vec3 wi = toLight / dist;  // from x toward the light; the light travels along -wi
    const float falloff = light.type == LightType::Spot ? light.spotFalloff(dot(-wi, light.direction)) : 1.0f;
    if (!(falloff > 0)) return Rgb(0.0f);
    const Rgb trCam = med.homogeneous() ? med.transmittance(s.t) : Rgb(storedTransmittance(freeFlights, n, s.t));
    if (trCam.isBlack()) return Rgb(0.0f);
    const Rgb sigmaS = med.sigmaSAt(x);
    if (sigmaS.isBlack()) return Rgb(0.0f);
    DirectLightSample ls;
    ls.wi = wi;
    ls.distance = dist;
    ls.point = light.position;
    ls.delta = true;
    const Rgb trLight = shadowTransmittance(m_rt, x, ls, medium, rng);
    if (trLight.isBlack()) return Rgb(0.0f);
    const float phase = hgPhase(dot(-wi, -d), med.g);
    return sigmaS * light.intensity * trCam * trLight * (phase * falloff * s.inverseSquareOverPdf);
}

}  // namespace tyndall
