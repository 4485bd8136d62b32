#include "cpu/photon_tracer.h"

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/phase.h"
#include "core/sampling.h"
#include "cpu/free_flight.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

RadiusSetup RadiusSetup::resolve(const RenderSettings& settings, const Scene& scene) {
    RadiusSetup r;
    float diagonal = scene.bounds.empty() ? 1.0f : length(scene.bounds.diagonal());
    r.beamRadius = settings.radius > 0 ? settings.radius : 0.005f * diagonal;
    r.surfaceRadius = settings.surfaceRadius > 0 ? settings.surfaceRadius : 0.02f * diagonal;
    r.schedule = RadiusSchedule(settings.alpha, settings.radiusOffset);
    return r;
}

PhotonTracer::PhotonTracer(const EmbreeScene& rt, const RenderSettings& settings, const RadiusSetup& radii)
    : m_rt(rt), m_scene(rt.scene()), m_settings(settings), m_radii(radii), m_lights(rt.scene()) {
    for (const Light& l : m_scene.lights)
        m_lightMedium.push_back(l.type == LightType::Directional ? m_scene.globalMedium : m_rt.mediumAt(l.position));
    for (const Medium& m : m_scene.media) m_anyHeterogeneous |= !m.homogeneous();
}

PhotonMap PhotonTracer::trace(uint64_t pass) const {
    uint32_t m = m_settings.photonsPerPass;
    return trace(pass, pass * uint64_t(m), m);
}

PhotonMap PhotonTracer::trace(uint64_t pass, uint64_t firstPath, uint32_t count) const {
    constexpr uint32_t kBlock = 64;
    uint32_t blocks = (count + kBlock - 1) / kBlock;
    std::vector<PhotonMap> parts(blocks);
    tbb::parallel_for(uint32_t(0), blocks, [&](uint32_t b) {
        PhotonMap& part = parts[b];
        part.beams.reserve(kBlock * 8);
        part.surfacePhotons.reserve(kBlock * 4);
        part.freeFlightsPerBeam = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
        uint32_t end = std::min(count, (b + 1) * kBlock);
        for (uint32_t k = b * kBlock; k < end; ++k) tracePath(pass, k, firstPath + k, count, part);
    });
    PhotonMap out;
    out.pass = pass;
    out.firstPath = firstPath;
    out.pathCount = count;
    out.freeFlightsPerBeam = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
    size_t nb = 0, ns = 0;
    for (const PhotonMap& p : parts) {
        nb += p.beams.size();
        ns += p.surfacePhotons.size();
        out.raysTraced += p.raysTraced;
    }
    out.beams.reserve(nb);
    out.surfacePhotons.reserve(ns);
    out.freeFlights.reserve(nb * size_t(out.freeFlightsPerBeam));
    for (const PhotonMap& p : parts) {
        out.beams.insert(out.beams.end(), p.beams.begin(), p.beams.end());
        out.surfacePhotons.insert(out.surfacePhotons.end(), p.surfacePhotons.begin(), p.surfacePhotons.end());
        out.freeFlights.insert(out.freeFlights.end(), p.freeFlights.begin(), p.freeFlights.end());
    }
    return out;
}

void PhotonTracer::tracePath(uint64_t pass, uint64_t pathInPass, uint64_t globalPath, uint32_t count,
                             PhotonMap& out) const {
    Rng rng = Rng::forKey(m_settings.seed, pass, pathInPass, StreamPurpose::PhotonPath);
    EmittedPhoton e = m_lights.sample(rng);
    Rgb power = e.power / float(count);
    const float startMax = power.maxComponent();
    if (!(startMax > 0)) return;
    float beamRadius, surfaceRadius;
    m_radii.radiiOf(globalPath, &beamRadius, &surfaceRadius);

    MediumId medium = e.light >= 0 ? m_lightMedium[e.light] : m_scene.meshes[e.emitterMesh].exteriorMedium;
    Ray ray = e.ray;
    // Area-light photons start on their triangle: nudge them off it along the emitted direction.
    if (e.emitterMesh >= 0) ray.o = m_rt.offsetOrigin(ray.o, ray.d, ray.d);

    for (int bounce = 0; bounce < m_settings.maxPhotonBounces; ++bounce) {
        SurfaceHit hit;
        bool surface = m_rt.intersect(ray, &hit);
        out.raysTraced++;
        float tHit = surface ? hit.t : kInfinity;

        if (medium != kVacuum) {
            const Medium& med = m_scene.media[medium];
            Ray seg;
            if (m_rt.mediumSegment(ray.o, ray.d, tHit, &seg)) {
                PhotonBeam beam;
                beam.origin = seg.o;
                beam.dir = seg.d;
                beam.tMax = seg.tMax;
                beam.radius = beamRadius;
                beam.power = power;
                beam.medium = medium;
                out.beams.push_back(beam);
                if (const int n = out.freeFlightsPerBeam; n > 0) {
                    // Homogeneous beams in a scene with grid media keep analytic transmittance.
                    size_t at = out.freeFlights.size();
                    out.freeFlights.resize(at + size_t(n), kInfinity);
                    if (!med.homogeneous()) sampleCollisionDistances(med, seg, seg.tMax, rng, n, &out.freeFlights[at]);
                }
                FreeFlight ff = sampleFreeFlight(med, seg, seg.tMax, rng);
                power *= ff.weight;
                if (ff.scattered) {
                    // Russian roulette keeps path power near its start value.
                    float q = std::min(1.0f, power.maxComponent() / startMax);
                    if (!(rng.uniform() < q)) return;
                    power *= 1.0f / q;
                    Vec3 x = seg.at(ff.t);
                    ray = Ray{x, sampleHg(ray.d, med.g, rng.uniform(), rng.uniform())};
                    continue;
                }
            }
        }
        if (!surface) return;

        const TriangleMesh& mesh = m_scene.meshes[hit.mesh];
        const Material& mat = m_scene.materials[mesh.material];
        if (mat.type == MaterialType::Diffuse) {
            HitSide side = hitSide(hit, ray.d);
            SurfacePhoton sp;
            sp.position = hit.p;
            sp.radius = surfaceRadius;
            sp.wi = -ray.d;
            sp.normal = side.nf;
            sp.power = power;
            out.surfacePhotons.push_back(sp);
            power *= mat.albedo;
            float q = std::min(1.0f, power.maxComponent() / startMax);
            if (!(rng.uniform() < q)) return;
            power *= 1.0f / q;
            Vec3 d = Frame(side.nf).toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
            ray = Ray{m_rt.offsetOrigin(hit.p, side.nf, d), d};
            continue;
        }
        SpecularEvent ev;
        if (!sampleSpecular(mat, mesh, hit, ray.d, medium, rng.uniform(), TransportMode::Importance, &ev)) return;
        power *= ev.weight;
        if (power.isBlack()) return;
        medium = ev.medium;
        ray = Ray{m_rt.offsetOrigin(hit.p, hit.ng, ev.d), ev.d};
    }
}

}  // namespace tyndall
