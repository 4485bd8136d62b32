#include "cpu/camera_tracer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/beam_estimator.h"
#include "core/transmittance.h"
#include "cpu/free_flight.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

Rgb gatherBeams(const Scene& scene, const PhotonMap& photons, const std::vector<BeamHitRecord>& hits,
                MediumId medium, const Vec3& o, const Vec3& d, const float* segmentFreeFlights, int n) {
    const Medium& med = scene.media[medium];
    Rgb sum;
    if (med.homogeneous()) {
        Rgb st = med.sigmaT();
        for (const BeamHitRecord& h : hits) {
            const PhotonBeam& beam = photons.beams[h.beam];
            if (beam.medium != medium) continue;
            float s = h.hit.s, t = h.hit.t;
            Rgb tr = exp(Rgb(-st.r * (s + t), -st.g * (s + t), -st.b * (s + t)));
            sum += beamRadiance(h.hit, beam, med.sigmaS, med.g, tr, Rgb(1.0f));
        }
        return sum;
    }
    const int nb = photons.freeFlightsPerBeam;
    for (const BeamHitRecord& h : hits) {
        const PhotonBeam& beam = photons.beams[h.beam];
        if (beam.medium != medium) continue;
        float trCam = storedTransmittance(segmentFreeFlights, n, h.hit.s);
        float trBeam = storedTransmittance(&photons.freeFlights[size_t(h.beam) * nb], nb, h.hit.t);
        if (trCam == 0 || trBeam == 0) continue;
        Rgb sigmaS = med.sigmaSAt(o + d * h.hit.s);
        sum += beamRadiance(h.hit, beam, sigmaS, med.g, Rgb(trCam), Rgb(trBeam));
    }
    return sum;
}

CameraTracer::CameraTracer(const EmbreeScene& rt, const RenderSettings& settings)
    : m_rt(rt), m_scene(rt.scene()), m_settings(settings), m_cameraMedium(rt.mediumAt(rt.scene().camera.position)) {
    for (const Medium& m : m_scene.media) m_anyHeterogeneous |= !m.homogeneous();
}

namespace {
struct ThreadScratch {
    std::vector<BeamHitRecord> hits;
    std::vector<float> freeFlights;
    CameraPassStats stats;
};
}  // namespace

CameraPassResult CameraTracer::trace(uint64_t pass, const PhotonMap& photons, const BeamBvh& beams,
                                     const SurfacePhotonGrid& surfacePhotons) const {
    const int w = m_settings.width, h = m_settings.height;
    const int nff = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
    CameraPassResult result;
    result.radiance = Image(w, h);
    result.primary.width = w;
    result.primary.height = h;
    result.primary.rays.resize(size_t(w) * h);
    result.primary.freeFlightsPerRay = nff;
    result.primary.freeFlights.assign(size_t(w) * h * nff, kInfinity);
    tbb::enumerable_thread_specific<ThreadScratch> scratch;

    tbb::parallel_for(0, h, [&](int y) {
        ThreadScratch& tls = scratch.local();
        tls.freeFlights.resize(std::max(nff, 1));
        for (int x = 0; x < w; ++x) {
            const uint64_t pixel = uint64_t(y) * w + x;
            Rng jitter = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::PixelJitter);
            Rng rng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::CameraPath);
            float jx = jitter.uniform(), jy = jitter.uniform();
            Vec2 lens{jitter.uniform(), jitter.uniform()};
            Ray ray = m_scene.camera.generateRay(float(x) + jx, float(y) + jy, w, h, lens);
            MediumId medium = m_cameraMedium;
            Rgb throughput(1.0f), L;

            for (int depth = 0; depth <= m_settings.maxCameraBounces; ++depth) {
                SurfaceHit hit;
                bool surface = m_rt.intersect(ray, &hit);
                tls.stats.rays++;
                float tHit = surface ? hit.t : kInfinity;
                Ray seg;
                if (medium != kVacuum && m_rt.mediumSegment(ray.o, ray.d, tHit, &seg)) {
                    const Medium& med = m_scene.media[medium];
                    float* ff = depth == 0 && nff > 0 ? &result.primary.freeFlights[pixel * nff] : tls.freeFlights.data();
                    if (!med.homogeneous()) sampleCollisionDistances(med, seg, seg.tMax, depth == 0 ? jitter : rng, nff, ff);
                    if (depth == 0) {
                        result.primary.rays[pixel] = PrimaryRay{seg.o, seg.tMax, seg.d, medium};
                    } else {
                        beams.query(seg.o, seg.d, seg.tMax, tls.hits);
                        tls.stats.beamQueries++;
                        tls.stats.beamHits += tls.hits.size();
                        L += throughput * gatherBeams(m_scene, photons, tls.hits, medium, seg.o, seg.d, ff, nff);
                    }
                    throughput *= med.homogeneous() ? med.transmittance(seg.tMax)
                                                    : Rgb(storedTransmittance(ff, nff, seg.tMax));
                } else if (depth == 0) {
                    result.primary.rays[pixel] = PrimaryRay{ray.o, 0.0f, ray.d, kVacuum};
                }
                if (!surface || throughput.isBlack()) break;

                const TriangleMesh& mesh = m_scene.meshes[hit.mesh];
                const Material& mat = m_scene.materials[mesh.material];
                HitSide side = hitSide(hit, ray.d);
                if (mat.isEmissive() && side.entering) L += throughput * mat.emission;
                if (mat.type == MaterialType::Diffuse) {
                    L += throughput * mat.albedo * kInvPi * surfacePhotons.density(hit.p, side.nf);
                    break;
                }
                SpecularEvent ev;
                if (!sampleSpecular(mat, mesh, hit, ray.d, medium, rng.uniform(), TransportMode::Radiance, &ev)) break;
                throughput *= ev.weight;
                medium = ev.medium;
                ray = Ray{m_rt.offsetOrigin(hit.p, hit.ng, ev.d), ev.d};
            }
            result.radiance.at(x, y) = L;
        }
    });
    for (const ThreadScratch& s : scratch) {
        result.stats.rays += s.stats.rays;
        result.stats.beamQueries += s.stats.beamQueries;
        result.stats.beamHits += s.stats.beamHits;
    }
    return result;
}

}  // namespace tyndall
