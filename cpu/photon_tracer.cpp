#include "cpu/photon_tracer.h"

#include <algorithm>

#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include "core/error.h"
#include "core/phase.h"
#include "core/sampling.h"
#include "cpu/beam_cone.h"
#include "cpu/equiangular.h"
#include "cpu/free_flight.h"
#include "cpu/radius_defaults.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

RadiusSetup RadiusSetup::resolve(const RenderSettings& settings, const Scene& scene) {
    RadiusSetup r;
    float diagonal = scene.bounds.empty() ? 1.0f : length(scene.bounds.diagonal());
    // Settings that were not resolved (cpu/radius_defaults.h) get the scene-relative defaults.
    r.beamRadius = settings.radius > 0 ? settings.radius : float(RadiusDefaults::kSceneRelativeBeam) * diagonal;
    r.surfaceRadius =
        settings.surfaceRadius > 0 ? settings.surfaceRadius : float(RadiusDefaults::kSceneRelativeSurface) * diagonal;
    uint64_t offset = settings.radiusOffset == RenderSettings::kAutoRadiusOffset ? RadiusDefaults::kSceneRelativeOffset
                                                                                 : settings.radiusOffset;
    r.schedule = RadiusSchedule(settings.alpha, offset);
    // An automatic angle left unresolved is off (the scene-relative defaults had no cone).
    if (settings.photonAngle > 0) r.coneReach = double(r.beamRadius) / double(settings.photonAngle);
    if (settings.scatteredBeamMfp > 0) {
        // The plan's end radius (where the automatic radii sit at kBeamEndFootprints footprints).
        const double end = double(r.beamRadius) * r.schedule.beamFactor(plannedPhotonPaths(settings));
        if (end > 0) r.scatteredPerMfp = settings.scatteredBeamMfp / end;
    }
    if (settings.mediumPointMfp > 0) {
        const double end = double(r.beamRadius) * r.schedule.beamFactor(plannedPhotonPaths(settings));
        if (end > 0) r.pointPerMfp = settings.mediumPointMfp / end;
    }
    if (settings.indirectPhotonSpread > 0) {
        const double end = double(r.surfaceRadius) * r.schedule.surfaceFactor(plannedPhotonPaths(settings));
        if (end > 0) r.indirectPerLength = settings.indirectPhotonSpread / end;
    }
    return r;
}

PhotonTracer::PhotonTracer(const EmbreeScene& rt, const RenderSettings& settings, const RadiusSetup& radii)
    : m_rt(rt), m_scene(rt.scene()), m_settings(settings), m_radii(radii), m_lights(rt.scene()), m_media(rt) {
    if (!m_media.empty()) {
        const double media = std::max(0.0f, m_media.estimatedPower().luminance());
        const double lights = m_lights.sourceCount() > 0 ? std::max(0.0f, m_lights.totalPower().luminance()) : 0.0;
        m_mediaShare = lights > 0 ? float(std::clamp(media / (media + lights), 1e-3, 1.0 - 1e-3)) : 1.0f;
    }
    for (const Light& l : m_scene.lights)
        m_lightMedium.push_back(l.type == LightType::Directional ? m_scene.globalMedium : m_rt.mediumAt(l.position));
    for (const Medium& m : m_scene.media) m_anyHeterogeneous |= !m.homogeneous();
    m_directLight = settings.directLight;
    m_maxSegments = settings.maxPathLength > 0 ? settings.maxPathLength - 1 : -1;
    // No two points of the scene's media are farther apart than its diagonal.
    m_planeLengthCap = 1.001f * (m_scene.bounds.empty() ? 1.0f : length(m_scene.bounds.diagonal()));
    // The photon cone of an area light starts at its equivalent radius sqrt(area / 4 pi).
    for (const TriangleMesh& mesh : m_scene.meshes) {
        double area = 0;
        for (size_t t = 0; t < mesh.triangleCount(); ++t) area += 0.5 * double(length(mesh.geometricNormal(t)));
        m_emitterStart.push_back(std::sqrt(area / (4.0 * M_PI)));
    }
}

PhotonMap PhotonTracer::trace(uint64_t pass) const {
    uint32_t m = m_settings.photonsPerPass;
    return trace(pass, pass * uint64_t(m), 0, m, m, nullptr);
}

PhotonMap PhotonTracer::trace(uint64_t pass, uint64_t firstPath, uint32_t count) const {
    return trace(pass, firstPath, 0, count, count, nullptr);
}

PhotonMap PhotonTracer::traceBatch(uint64_t pass, uint32_t begin, uint32_t end) const {
    const uint32_t m = m_settings.photonsPerPass;
    end = std::min(end, m);
    begin = std::min(begin, end);
    return trace(pass, pass * uint64_t(m) + begin, begin, end - begin, m, nullptr);
}

PhotonMap PhotonTracer::traceRecordingRays(uint64_t pass, std::vector<Ray>* rays) const {
    uint32_t m = m_settings.photonsPerPass;
    return trace(pass, pass * uint64_t(m), 0, m, m, rays);
}

PhotonMap PhotonTracer::trace(uint64_t pass, uint64_t firstPath, uint32_t begin, uint32_t count, uint32_t divisor,
                              std::vector<Ray>* rays) const {
    // Blocks of 32 paths, one task each: the pass ends within ~one block's time of its last
    // thread, where the auto partitioner's chunks of several blocks left a thread idle longer.
    constexpr uint32_t kBlock = 32;
    uint32_t blocks = (count + kBlock - 1) / kBlock;
    std::vector<PhotonMap> parts(blocks);
    std::vector<std::vector<Ray>> partRays(rays ? blocks : 0);
    tbb::parallel_for(
        uint32_t(0), blocks,
        [&](uint32_t b) {
            PhotonMap& part = parts[b];
            part.beams.reserve(kBlock * 8);
            part.surfacePhotons.reserve(kBlock * 4);
            part.freeFlightsPerBeam = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
            std::vector<Ray>* blockRays = rays ? &partRays[b] : nullptr;
            uint32_t end = std::min(count, (b + 1) * kBlock);
            for (uint32_t k = b * kBlock; k < end; ++k)
                tracePath(pass, begin + k, firstPath + k, divisor, part, blockRays);
        },
        tbb::simple_partitioner());
    for (const std::vector<Ray>& r : partRays) rays->insert(rays->end(), r.begin(), r.end());
    PhotonMap out;
    out.pass = pass;
    out.firstPath = firstPath;
    out.pathCount = count;
    out.freeFlightsPerBeam = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
    size_t nb = 0, ns = 0, np = 0, npt = 0;
    for (const PhotonMap& p : parts) {
        nb += p.beams.size();
        ns += p.surfacePhotons.size();
        np += p.planes.size();
        npt += p.points.size();
        out.raysTraced += p.raysTraced;
    }
    out.beams.reserve(nb);
    out.surfacePhotons.reserve(ns);
    out.freeFlights.reserve(nb * size_t(out.freeFlightsPerBeam));
    out.planes.reserve(np);
    out.points.reserve(npt);
    for (const PhotonMap& p : parts) {
        out.beams.insert(out.beams.end(), p.beams.begin(), p.beams.end());
        out.surfacePhotons.insert(out.surfacePhotons.end(), p.surfacePhotons.begin(), p.surfacePhotons.end());
        out.freeFlights.insert(out.freeFlights.end(), p.freeFlights.begin(), p.freeFlights.end());
        out.beamSegments.insert(out.beamSegments.end(), p.beamSegments.begin(), p.beamSegments.end());
        out.planes.insert(out.planes.end(), p.planes.begin(), p.planes.end());
        out.points.insert(out.points.end(), p.points.begin(), p.points.end());
    }
    return out;
}

void PhotonTracer::tracePath(uint64_t pass, uint64_t pathInPass, uint64_t globalPath, uint32_t count, PhotonMap& out,
                             std::vector<Ray>* rays) const {
    Rng rng = Rng::forKey(m_settings.seed, pass, pathInPass, StreamPurpose::PhotonPath);
    // The source: a light, or an emissive medium (one more draw only when both exist).
    const bool fromMedium = m_mediaShare >= 1.0f || (m_mediaShare > 0 && rng.uniform() < m_mediaShare);
    EmittedPhoton e;
    MediumId mediumStart = kVacuum;
    if (fromMedium) {
        const MediumEmitters::Photon mp = m_media.sample(rng);
        e.ray = mp.ray;
        e.power = mp.power / m_mediaShare;
        mediumStart = mp.medium;
    } else {
        if (m_lights.sourceCount() == 0) return;
        e = m_lights.sample(rng);
        if (m_mediaShare > 0) e.power *= 1.0f / (1.0f - m_mediaShare);
    }
    Rgb power = e.power / float(count);
    const float startMax = power.maxComponent();
    if (!(startMax > 0)) return;
    float beamRadius, surfaceRadius;
    m_radii.radiiOf(globalPath, &beamRadius, &surfaceRadius);

    MediumId medium = fromMedium      ? mediumStart
                      : e.environment ? m_scene.globalMedium
                      : e.light >= 0 ? m_lightMedium[e.light]
                                     : m_scene.meshes[e.emitterMesh].exteriorMedium;
    // The ray is o + t d, t in (0, infinity), as every emitted and scattered ray is.
    Vec3 o = e.ray.o, d = e.ray.d;
    // Area-light photons start on their triangle: nudge them off it along the emitted direction.
    if (e.emitterMesh >= 0) o = m_rt.offsetOrigin(o, 0.0f, d, d);
    // SurfacePhoton::flags (core/photon_beam.h). deltaPath: from a point, spot or directional light
    // through delta interactions only, what glossy and coat-specular gathers use (docs/algorithm.md,
    // "Glossy vertices"); direct: no scattering vertex yet (interface crossings are none).
    // A photon from a medium is neither: no shadow ray carries a medium's light.
    bool deltaPath = !fromMedium && e.light >= 0;
    bool direct = !fromMedium;
    // --equiangular on: the camera paths estimate the single scattering of point, spot,
    // directional and area lights and the environment (cpu/equiangular.h), so such a path's beams are not stored while
    // it is still direct (no scattering vertex, no mirror, glass or other surface but Interfaces).
    const bool equiangularLight =
        m_settings.equiangular && !fromMedium && EquiangularScattering::handles(m_scene, e);
    // Path distance from the light at o (the photon cone, cpu/beam_cone.h).
    // Parallel light (directional, the environment) has no cone: it starts infinitely far away.
    double travelled = fromMedium || e.environment                                ? kInfinity
                       : e.light < 0                                              ? m_emitterStart[e.emitterMesh]
                       : m_scene.lights[e.light].type == LightType::Directional ? kInfinity
                                                                                  : 0.0;

    // The index of the segment about to be traced (RenderSettings::maxPathLength: a camera path
    // adds at least one, so a capped photon path ends after maxPathLength - 1).
    int segment = 1;
    // --photon-planes on: each beam in a homogeneous medium makes a plane from its own stream, so
    // the path's draws are those of --photon-planes off; the beam after a scattering on such a beam
    // is the plane's, and is not stored (core/photon_plane.h).
    Rng planeRng = m_settings.photonPlanes ? Rng::forKey(m_settings.seed, pass, pathInPass, StreamPurpose::PhotonPlane)
                                           : Rng();
    bool coveredByPlane = false;
    // The radius factor of the next beam: > 1 only for a beam that starts at a scattering in a
    // medium (RadiusSetup::scatteredScale), reset where a beam leaves a surface.
    float scatteredScale = 1.0f;
    // Whether the next beam starts at a scattering in a medium (or continues one through
    // Interfaces): in a dense homogeneous medium such a beam is not stored, its end's scattering is
    // stored as a photon point instead (RadiusSetup::pointScale).
    bool afterScattering = false;
    // Path length since the light last scattered diffusely (a diffuse surface, a medium, an
    // emissive medium's emission), through mirrors, glass and Interfaces; -1 while it has not
    // (direct and caustic light): the indirect photons' radius (RadiusSetup::indirectScale).
    double sinceDiffuse = fromMedium ? 0.0 : -1.0;
    for (int bounce = 0; bounce < m_settings.maxPhotonBounces; ++bounce) {
        if (m_maxSegments >= 0 && segment > m_maxSegments) return;
        const bool covered = coveredByPlane;
        coveredByPlane = false;
        RTCRayHit rh;
        initRayHit(rh, o, d);
        if (rays) rays->push_back(Ray{o, d, 0.0f, kInfinity});
        const bool surface = m_rt.intersectRaw(rh);
        out.raysTraced++;
        const float tHit = surface ? rh.ray.tfar : kInfinity;
        if (surface) m_rt.prefetchShadingNormal(int(rh.hit.geomID), rh.hit.primID);

        float t0, t1;
        if (medium != kVacuum && m_rt.globalMediumInterval(Ray{o, d, 0.0f, tHit}, &t0, &t1) && t1 > t0) {
            const Medium& med = m_scene.media[medium];
            const Ray seg{o + d * t0, d, 0.0f, t1 - t0};
            // A plane from this beam when the path could go on in the medium after a scattering.
            const bool plane = m_settings.photonPlanes && med.homogeneous() &&
                               bounce + 1 < m_settings.maxPhotonBounces &&
                               (m_maxSegments < 0 || segment + 1 <= m_maxSegments);
            if (plane) {
                PhotonPlane& p = out.planes.emplace_back();
                p.origin = seg.o;
                p.len1 = seg.tMax;
                p.dir1 = seg.d;
                p.dir2 = sampleHg(seg.d, med.g, planeRng.uniform(), planeRng.uniform());
                p.len2 = samplePlaneLength(med, m_planeLengthCap, planeRng.uniform());
                p.medium = medium;
                p.power = power;
                p.segment = uint16_t(std::min(segment + 1, 65535));
            }
            // Photon points: this beam's scattering (if it has one) stands for it.
            const float pointScale = afterScattering && !covered && !m_settings.photonPlanes && med.homogeneous()
                                         ? m_radii.pointScale(med.sigmaT().maxComponent())
                                         : 0.0f;
            if (!(direct && equiangularLight) && !covered && !(pointScale > 0)) {
                // The beam is written in place: a stack copy pushed back stalls on store forwarding.
                PhotonBeam& beam = out.beams.emplace_back();
                beam.origin = seg.o;
                beam.tMax = seg.tMax;
                beam.dir = seg.d;
                beam.radius = beamRadius * scatteredScale;
                beam.power = power;
                beam.medium = medium;
                if (const int n = out.freeFlightsPerBeam; n > 0) {
                    // Homogeneous beams in a scene with grid media keep analytic transmittance.
                    size_t at = out.freeFlights.size();
                    out.freeFlights.resize(at + size_t(n), kInfinity);
                    if (!med.homogeneous()) sampleCollisionDistances(med, seg, seg.tMax, rng, n, &out.freeFlights[at]);
                }
                if (const double s0 = travelled + double(t0); s0 < m_radii.coneReach) {
                    // Within the photon cone: stored again as its pieces.
                    const PhotonBeam whole = beam;
                    out.beams.pop_back();
                    const int n = out.freeFlightsPerBeam;
                    float stored[64];
                    if (n > 0) {
                        std::copy(out.freeFlights.end() - n, out.freeFlights.end(), stored);
                        out.freeFlights.resize(out.freeFlights.size() - size_t(n));
                    }
                    appendConeBeam(whole, s0, m_radii.coneReach, med, stored, n, out.beams, out.freeFlights);
                }
                if (m_maxSegments >= 0) out.beamSegments.resize(out.beams.size(), uint16_t(std::min(segment, 65535)));
            }
            const Rgb before = power;
            FreeFlight ff = sampleFreeFlight(med, seg, seg.tMax, rng);
            power *= ff.weight;
            if (pointScale > 0) {
                // The beam's points: its free flight's scattering (where the path goes on) and
                // kPointsPerBeam - 1 more free flights on it, each an unbiased sample of the beam,
                // with a share of its power.
                const int n = RenderSettings::kMediumPointsPerBeam;
                for (int k = 0; k < n; ++k) {
                    const FreeFlight f = k == 0 ? ff : sampleFreeFlight(med, seg, seg.tMax, rng);
                    if (!f.scattered) continue;
                    MediumPoint& point = out.points.emplace_back();
                    point.position = seg.at(f.t);
                    point.radius = beamRadius * pointScale;
                    point.dir = d;
                    point.segment = uint32_t(segment);
                    point.power = before * f.weight * (1.0f / float(n));
                    point.medium = medium;
                }
            }
            if (ff.scattered) {
                // Russian roulette keeps path power near its start value.
                float q = std::min(1.0f, power.maxComponent() / startMax);
                if (!(rng.uniform() < q)) return;
                power *= 1.0f / q;
                Vec3 x = seg.at(ff.t);
                // Wider only in a homogeneous medium: in a grid every beam a camera segment overlaps
                // costs its gather a transmittance estimate through the grid, so wide beams there
                // cost more passes than their lower noise gains (docs/performance.md).
                scatteredScale = med.homogeneous() ? m_radii.scatteredScale(med.sigmaT().maxComponent()) : 1.0f;
                d = sampleHg(d, med.g, rng.uniform(), rng.uniform());
                travelled += double(t0) + double(ff.t);
                sinceDiffuse = 0.0;
                o = x;
                ++segment;
                deltaPath = direct = false;
                afterScattering = true;
                coveredByPlane = plane;
                continue;
            }
        }
        if (!surface) return;

        // The hit record, only for paths that reach the surface.
        const Vec3 p = o + d * tHit;
        travelled += double(tHit);
        if (sinceDiffuse >= 0) sinceDiffuse += double(tHit);
        // Embree's Ng is cross(v1 - v0, v2 - v0): the same orientation as Scene's CCW convention.
        const Vec3 ng = normalize(Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
        const TriangleMesh& mesh = m_scene.meshes[rh.hit.geomID];
        const Material& mat = m_scene.materials[mesh.material];
        SurfaceHit hit;
        hit.mesh = int(rh.hit.geomID);
        hit.triangle = rh.hit.primID;
        hit.b1 = rh.hit.u;
        hit.b2 = rh.hit.v;
        hit.p = p;
        hit.ng = ng;
        hit.ns = !mat.usesVertexNormals()
                     ? ng
                     : m_rt.shadingNormal(int(rh.hit.geomID), rh.hit.primID, rh.hit.u, rh.hit.v, ng);
        applyNormalMap(m_scene, &hit, surfaceRadius);
        const bool partly = mat.isPartlyTransmissive();
        const bool plastic = mat.type == MaterialType::Plastic;
        const SurfacePoint at = surfaceAt(m_scene, hit, surfaceRadius);
        // Stored: what a gather here uses. A diffuse part gathers every photon except, with
        // --direct-light on, those that arrive without scattering (shadow rays carry that light);
        // glossy and coat-specular gathers use the kPhotonDeltaPath ones.
        const bool diffusePart = mat.type == MaterialType::Diffuse || plastic || (partly && at.transmission < 1.0f);
        if ((diffusePart && !(direct && m_directLight)) || (deltaPath && (plastic || mat.isGlossy()))) {
            const Vec3 nf = dot(d, ng) < 0 ? ng : -ng;  // hitSide(hit, d).nf
            SurfacePhoton& sp = out.surfacePhotons.emplace_back();
            sp.position = p;
            sp.radius = surfaceRadius * float(surfaceConeScale(travelled, m_radii.coneReach)) *
                        m_radii.indirectScale(sinceDiffuse);
            sp.wi = -d;
            sp.normal = nf;
            sp.power = power;
            sp.flags = uint8_t((direct ? kPhotonDirect : 0) | (deltaPath ? kPhotonDeltaPath : 0));
            sp.segments = uint16_t(std::min(segment, 65535));
            // alphaMode BLEND stops a photon with probability alpha (the filter): the stored photons
            // stand for the irradiance on the covered part, so they carry 1/alpha (the camera path
            // stops with probability alpha too, and must not apply the coverage twice).
            if (mat.alphaMode == AlphaMode::Blend) {
                float a = evalSurface(m_scene, mesh, rh.hit.primID, rh.hit.u, rh.hit.v, 0.0f).alpha;
                if (a > 0) sp.power *= 1.0f / a;
            }
        }
        if (mat.type != MaterialType::Interface) direct = false;  // a diffuse, glossy, mirror or glass vertex scatters
        // Not const: GCC keeps a const aggregate in memory (no scalar replacement).
        Bsdf bsdf = Bsdf::at(m_scene, hit, at, d, medium, TransportMode::Importance, rng);
        // Russian roulette keeps path power near its start value, at every vertex but delta ones.
        const bool roulette = (bsdf.lobes() & (kLobeDiffuse | kLobeGlossy)) != 0;
        BsdfSample s;
        if (!bsdf.sample(rng, &power, &s, kLobesAll, [&](const Rgb& beta, const Rgb& w) {
                return roulette ? std::min(1.0f, (beta * w).maxComponent() / startMax) : kNoRoulette;
            }))
            return;
        if (power.isBlack()) return;
        deltaPath = deltaPath && (s.lobe & kLobeSpecular);
        if (s.lobe & kLobeDiffuse) sinceDiffuse = 0.0;
        medium = s.medium;
        const bool diffuse = bsdf.lobes() == (kLobeReflection | kLobeDiffuse);
        Vec3 away = ng;  // by value: a pointer into the Bsdf (a ?: of lvalues) would keep it in memory
        if (diffuse) away = bsdf.side().nf;
        o = m_rt.offsetOrigin(p, tHit, away, s.wi);
        d = s.wi;
        if (!bsdf.isPassThrough()) {
            ++segment;
            scatteredScale = 1.0f;
            afterScattering = false;
        }
    }
}

}  // namespace tyndall
