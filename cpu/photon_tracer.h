#pragma once
// Photon tracing (PPB step 1): emits the pass's photon paths from the lights (the environment's
// from a disc outside the scene's bounding sphere, core/light_sampler.h) and from emissive media
// (cpu/medium_emitters.h), and follows them
// through specular and diffuse surfaces and through media, storing a photon beam for every
// medium segment (long beams: each reaches the next surface, with analytic or stored-distance
// transmittance) and a surface photon at every diffuse hit (with --direct-light on, none for a path
// that has not scattered since its light: shadow rays carry that light; every stored photon carries
// the kPhotonDirect / kPhotonDeltaPath flags); with --photon-planes on, a photon plane for every
// beam in a homogeneous medium, and no beam for the segments the planes stand for (core/photon_plane.h).
// Radii follow the per-path schedule.
//
// Deterministic: path k of pass i draws from Rng::forKey(seed, i, k, PhotonPath) and the output
// is in path order, whatever the thread count.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/light_sampler.h"
#include "core/photon_beam.h"
#include "core/radius_schedule.h"
#include "core/settings.h"
#include "cpu/embree_scene.h"
#include "cpu/medium_emitters.h"

namespace tyndall {

/// Settings resolved against a scene: absolute radii and the schedule.
struct RadiusSetup {
    float beamRadius = 0;     ///< radius of photon path 0
    float surfaceRadius = 0;  ///< surface-photon radius of photon path 0
    RadiusSchedule schedule{0.5, 1000};
    /// Photon cone (cpu/beam_cone.h): path distance from the light where a beam reaches its full
    /// radius, beamRadius / photonAngle; 0 = no cone.
    double coneReach = 0;
    /// RenderSettings::scatteredBeamMfp over the beam radius at the plan's end (1 / scene units):
    /// a beam that starts at a scattering where the largest channel of sigma_t is s gets
    /// scatteredScale(s) times the schedule's radius; 0 = off.
    double scatteredPerMfp = 0;

    /// The factor on the schedule's radius for a beam that starts at a scattering where the
    /// extinction's largest channel is `sigmaT`: max(1, C mfp / end radius), at most
    /// RenderSettings::kMaxScatteredBeamScale; 1 when off.
    float scatteredScale(float sigmaT) const {
        if (!(scatteredPerMfp > 0)) return 1.0f;
        const double s = sigmaT > 0 ? scatteredPerMfp / double(sigmaT) : RenderSettings::kMaxScatteredBeamScale;
        return float(std::clamp(s, 1.0, RenderSettings::kMaxScatteredBeamScale));
    }

    /// RenderSettings::mediumPointMfp over the beam radius at the plan's end (1 / scene units); 0 = off.
    double pointPerMfp = 0;

    /// Photon points (RenderSettings::mediumPointMfp): the factor on the schedule's radius for the
    /// points in a homogeneous medium whose extinction's largest channel is `sigmaT`,
    /// max(1, C mfp / end radius); 0 where the medium keeps its beams: points off, or its mean free
    /// path long against the radius (C mfp over kMaxMediumPointScale end radii).
    float pointScale(float sigmaT) const {
        if (!(pointPerMfp > 0) || !(sigmaT > 0)) return 0.0f;
        const double s = pointPerMfp / double(sigmaT);
        return s > RenderSettings::kMaxMediumPointScale ? 0.0f : float(std::max(1.0, s));
    }

    /// RenderSettings::indirectPhotonSpread over the surface radius at the plan's end (1 / scene
    /// units); 0 = off.
    double indirectPerLength = 0;

    /// The factor on the schedule's surface radius for a photon whose light scattered diffusely
    /// (a diffuse surface, a medium) a path length `length` before it: C length / the plan's end
    /// surface radius, clamped to [1, RenderSettings::kMaxIndirectPhotonScale] and rounded down to a
    /// quarter octave (a few radii a pass: the surface kernel's edge coverage is cached per radius);
    /// 1 when off or for length < 0 (no such scattering: a direct or caustic photon).
    float indirectScale(double length) const {
        if (!(indirectPerLength > 0) || !(length > 0)) return 1.0f;
        const double s = std::min(indirectPerLength * length, RenderSettings::kMaxIndirectPhotonScale);
        if (!(s > 1)) return 1.0f;
        return float(std::exp2(std::floor(4.0 * std::log2(s) + 1e-9) / 4.0));
    }

    static RadiusSetup resolve(const RenderSettings& settings, const Scene& scene);
    float beamRadiusOf(uint64_t path) const { return float(beamRadius * schedule.beamFactor(path)); }
    float surfaceRadiusOf(uint64_t path) const { return float(surfaceRadius * schedule.surfaceFactor(path)); }
    /// Both radii of photon path `path` from one evaluation of the schedule.
    void radiiOf(uint64_t path, float* beam, float* surface) const {
        double f = schedule.beamFactor(path);
        *beam = float(beamRadius * f);
        *surface = float(surfaceRadius * std::sqrt(f));
    }
};

class PhotonTracer {
public:
    PhotonTracer(const EmbreeScene& rt, const RenderSettings& settings, const RadiusSetup& radii);

    /// Traces `settings.photonsPerPass` paths for pass `pass` (global path indices start at
    /// pass * photonsPerPass).
    PhotonMap trace(uint64_t pass) const;

    /// Traces `count` paths starting at global path index `firstPath` with streams keyed by
    /// (seed, pass, k); the power divisor is `count`.
    PhotonMap trace(uint64_t pass, uint64_t firstPath, uint32_t count) const;

    /// Paths [begin, end) of pass `pass`: exactly those paths of trace(pass), same streams, radii
    /// and power (divided by the pass's photonsPerPass), in path order. The union of a pass's
    /// batches is the pass: every estimate is a sum over beams and photons, so summing the
    /// batches' estimates gives the pass's (bounded-memory passes, PassRenderer).
    PhotonMap traceBatch(uint64_t pass, uint32_t begin, uint32_t end) const;

    /// trace(pass), also appending every ray it casts (origin, direction, t range), in path order:
    /// what build/bench/tyndall_stages replays through Embree alone as the photon tracer's raw ray rate.
    PhotonMap traceRecordingRays(uint64_t pass, std::vector<Ray>* rays) const;

private:
    /// Paths pathInPass = begin + k, k < count, global index firstPath + k, power / divisor.
    PhotonMap trace(uint64_t pass, uint64_t firstPath, uint32_t begin, uint32_t count, uint32_t divisor,
                    std::vector<Ray>* rays) const;
    void tracePath(uint64_t pass, uint64_t pathInPass, uint64_t globalPath, uint32_t count, PhotonMap& out,
                   std::vector<Ray>* rays) const;

    const EmbreeScene& m_rt;
    const Scene& m_scene;
    RenderSettings m_settings;
    RadiusSetup m_radii;
    LightSampler m_lights;
    /// Photons from emissive media (cpu/medium_emitters.h), chosen with probability m_mediaShare
    /// (the luminance share of their estimated power; no draw when there are none).
    MediumEmitters m_media;
    float m_mediaShare = 0;
    std::vector<MediumId> m_lightMedium;  // per Scene::lights entry
    std::vector<double> m_emitterStart;   // per mesh: path distance an area light's photons start at
    bool m_anyHeterogeneous = false;
    /// --direct-light on: photons that reach a diffuse surface straight from a light (kPhotonDirect)
    /// are not stored there; shadow rays carry that light (cpu/direct_light.h).
    bool m_directLight = false;
    /// RenderSettings::maxPathLength - 1: the most segments a photon path may have; -1 = uncapped.
    int m_maxSegments = -1;
    /// RenderSettings::photonPlanes: the cap on a plane's length along its second direction.
    float m_planeLengthCap = 0;
};

}  // namespace tyndall
