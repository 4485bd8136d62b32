#include "cpu/free_flight.h"

#include <cmath>

namespace tyndall {

namespace {
float expSample(float sigma, float u) { return sigma > 0 ? -std::log(1.0f - u) / sigma : kInfinity; }  // u < 1
}  // namespace

FreeFlight sampleFreeFlight(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    FreeFlight ff;
    if (medium.homogeneous()) {
        Rgb st = medium.sigmaT();
        int channel = std::min(int(rng.uniform() * 3.0f), 2);
        float t = expSample(st[channel], rng.uniform());
        if (t < tEnd) {
            Rgb tr = medium.transmittance(t);
            float pdf = (st.r * tr.r + st.g * tr.g + st.b * tr.b) / 3.0f;
            ff.scattered = true;
            ff.t = t;
            ff.weight = medium.sigmaS * tr / pdf;
        } else {
            Rgb tr = medium.transmittance(tEnd);
            float pass = tr.average();
            ff.t = tEnd;
            ff.weight = pass > 0 ? tr / pass : Rgb(0.0f);
        }
        return ff;
    }
    // Delta tracking: tentative collisions at the majorant rate, real with probability density/majorant.
    float sigmaT = medium.sigmaT().r;
    float majorantDensity = medium.density->majorant(Ray{ray.o, ray.d, 0.0f, tEnd});
    float mu = majorantDensity * sigmaT;
    float t = 0;
    while (true) {
        t += expSample(mu, rng.uniform());
        if (!(t < tEnd)) break;
        float density = medium.density->density(ray.at(t));
        if (rng.uniform() * majorantDensity < density) {
            ff.scattered = true;
            ff.t = t;
            ff.weight = medium.albedo();
            return ff;
        }
    }
    ff.t = tEnd;
    return ff;
}

float sampleCollisionDistance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (medium.homogeneous()) {
        float t = expSample(medium.sigmaT().r, rng.uniform());
        return t < tEnd ? t : kInfinity;
    }
    float sigmaT = medium.sigmaT().r;
    float majorantDensity = medium.density->majorant(Ray{ray.o, ray.d, 0.0f, tEnd});
    float mu = majorantDensity * sigmaT;
    float t = 0;
    while (true) {
        t += expSample(mu, rng.uniform());
        if (!(t < tEnd)) return kInfinity;
        if (rng.uniform() * majorantDensity < medium.density->density(ray.at(t))) return t;
    }
}

Rgb estimateTransmittance(const Medium& medium, const Ray& ray, float tEnd, Rng& rng) {
    if (medium.homogeneous()) return medium.transmittance(tEnd);
    // Ratio tracking (Novak et al. 2014): product of (1 - density/majorant) at tentative collisions.
    float sigmaT = medium.sigmaT().r;
    float majorantDensity = medium.density->majorant(Ray{ray.o, ray.d, 0.0f, tEnd});
    float mu = majorantDensity * sigmaT;
    float tr = 1.0f, t = 0;
    while (tr > 0) {
        t += expSample(mu, rng.uniform());
        if (!(t < tEnd)) break;
        tr *= 1.0f - medium.density->density(ray.at(t)) / majorantDensity;
    }
    return Rgb(std::max(tr, 0.0f));
}

}  // namespace tyndall
