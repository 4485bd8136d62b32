#include "cpu/camera_tracer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <optional>

#include "core/beam_estimator.h"
#include "core/film_light_sampler.h"
#include "core/pixel_jitter.h"
#include "core/transmittance.h"
#include "cpu/direct_light.h"
#include "cpu/surface_boundary.h"
#include "cpu/free_flight.h"
#include "cpu/plane_bvh.h"
#include "cpu/point_bvh.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

Rgb gatherBeams(const Scene& scene, const PhotonMap& photons, const std::vector<BeamHitRecord>& hits, MediumId medium,
                const Vec3& o, const Vec3& d, const float* segmentFreeFlights, int n, int maxBeamSegment) {
    const Medium& med = scene.media[medium];
    Rgb sum;
    const bool capped = maxBeamSegment > 0 && !photons.beamSegments.empty();
    auto beyondCap = [&](uint32_t b) { return capped && photons.beamSegments[b] > maxBeamSegment; };
    if (med.homogeneous()) {
        Rgb st = med.sigmaT();
        // A grey medium (the usual one): one exp a beam, the same values as three.
        const bool grey = st.r == st.g && st.r == st.b;
        for (const BeamHitRecord& h : hits) {
            const PhotonBeam& beam = photons.beams[h.beam];
            if (beam.medium != medium || beyondCap(h.beam)) continue;
            float s = h.hit.s, t = h.hit.t;
            Rgb tr = grey ? Rgb(std::exp(-st.r * (s + t)))
                          : exp(Rgb(-st.r * (s + t), -st.g * (s + t), -st.b * (s + t)));
            sum += beamRadiance(h.hit, beam, med.sigmaS, med.g, tr, Rgb(1.0f));
        }
        return sum;
    }
    const int nb = photons.freeFlightsPerBeam;
    for (const BeamHitRecord& h : hits) {
        const PhotonBeam& beam = photons.beams[h.beam];
        if (beam.medium != medium || beyondCap(h.beam)) continue;
        float trCam = storedTransmittance(segmentFreeFlights, n, h.hit.s);
        float trBeam = storedTransmittance(&photons.freeFlights[size_t(h.beam) * nb], nb, h.hit.t);
        if (trCam == 0 || trBeam == 0) continue;
        Rgb sigmaS = med.sigmaSAt(o + d * h.hit.s);
        sum += beamRadiance(h.hit, beam, sigmaS, med.g, Rgb(trCam), Rgb(trBeam));
    }
    return sum;
}

CameraTracer::CameraTracer(const EmbreeScene& rt, const RenderSettings& settings)
    : m_rt(rt), m_scene(rt.scene()), m_settings(settings) {
    bool gridEmission = false;
    for (const Medium& m : m_scene.media) {
        m_anyHeterogeneous |= !m.homogeneous();
        gridEmission |= !m.homogeneous() && m.emissive();
    }
    if (gridEmission) m_segmentEmission = std::make_unique<SegmentEmission>(m_scene);
    for (const TriangleMesh& mesh : m_scene.meshes)
        m_nonDiffuseMesh.push_back(m_scene.materials[size_t(mesh.material)].type != MaterialType::Diffuse);
    if (settings.surfaceBoundary) m_boundary = std::make_unique<SurfaceBoundary>(m_scene, m_rt);
    lightsChanged();
    if (settings.directLight) {
        // Photons from glossy and plastic surfaces (kPhotonDirect ones among them, for their
        // specular gathers) reach a diffuse gather where such a surface is in the kernel; without
        // those materials no stored photon is direct.
        for (const Material& m : m_scene.materials)
            m_skipDirectPhotons |= m.isGlossy() || m.type == MaterialType::Plastic;
    }
}

void CameraTracer::lightsChanged() {
    // The equiangular estimator's lights and their choice by power.
    m_equiangular.reset();
    if (m_settings.equiangular && !m_scene.media.empty()) {
        m_equiangular = std::make_unique<EquiangularScattering>(m_rt, m_settings.resolvedEquiangularSamples());
        if (!m_equiangular->any()) m_equiangular.reset();
    }
    m_filmLights.clear();
    if (m_equiangular && m_settings.filmLightSampling) {
        for (size_t index = 0; index < m_scene.lights.size(); ++index) {
            const Light& light = m_scene.lights[index];
            if (!(light.type == LightType::Point || light.type == LightType::Spot) || !(light.intensity.average() > 0))
                continue;
            const MediumId medium = m_rt.mediumAt(light.position);
            if (medium == kVacuum || !(m_scene.media[medium].sigmaS.maxComponent() > 0)) continue;
            m_filmLights.push_back(FilmLight{light.position, double(light.intensity.average()), int(index)});
        }
    }
    if (!m_settings.directLight) return;
    m_direct.reset();
    m_lights = std::make_unique<LightSampler>(m_scene);
    m_direct = std::make_unique<DirectLight>(m_rt, *m_lights);
    // Sources beyond Scene::lights: emissive triangles or the environment.
    m_glossyDirect = m_lights->sourceCount() > m_scene.lights.size();
}

namespace {
// The secondary stage's tiles: kTile x kTile pixels, row by row inside, from the image's corner.
constexpr int kTile = 8;

/// The whole tiles that `region` touches, inside the w x h image: what the primary stage traces and
/// the secondary stage walks for a render region.
PixelRegion secondaryTiles(const PixelRegion& region, int w, int h) {
    const int x0 = region.x / kTile * kTile, y0 = region.y / kTile * kTile;
    const int x1 = std::min(w, (region.x + region.width + kTile - 1) / kTile * kTile);
    const int y1 = std::min(h, (region.y + region.height + kTile - 1) / kTile * kTile);
    return PixelRegion{x0, y0, x1 - x0, y1 - y0};
}

struct ThreadScratch {
    std::vector<BeamHitRecord> hits;
    BeamQueryCache beamCache;  // reset at every tile's start: results independent of the thread count
    std::vector<float> freeFlights;
    std::vector<uint32_t> planes;  // a plane query's candidates
    CameraPassStats stats;
    // A path's equiangular legs (the primary segment's, a later segment's): 1 KB each, kept here
    // rather than made (and their values zeroed) for every pixel and segment; `n` set before use.
    EquiangularLegs primaryLegs, segmentLegs;
};
}  // namespace

PrimaryHitBuffer CameraTracer::acquireHits(size_t pixels) const {
    std::unique_ptr<std::vector<PrimaryHit>> hits;
    {
        std::lock_guard<std::mutex> lock(m_hitPool->mutex);
        auto& free = m_hitPool->free;
        auto it = std::find_if(free.begin(), free.end(), [&](const auto& v) { return v->size() == pixels; });
        if (it == free.end() && !free.empty()) it = free.begin();
        if (it != free.end()) {
            hits = std::move(*it);
            free.erase(it);
        }
    }
    if (!hits) hits = std::make_unique<std::vector<PrimaryHit>>();
    hits->resize(pixels);
    std::weak_ptr<HitPool> pool = m_hitPool;
    return PrimaryHitBuffer(hits.release(), [pool](std::vector<PrimaryHit>* v) {
        std::unique_ptr<std::vector<PrimaryHit>> owned(v);
        if (auto p = pool.lock()) {
            std::lock_guard<std::mutex> lock(p->mutex);
            if (p->free.size() < 2) p->free.push_back(std::move(owned));
        }
    });
}

namespace {
// A kept array whose size is `size` if there is one, else any (its capacity may fit), else none.
template <class T>
std::vector<T> takeFrom(std::vector<std::vector<T>>& kept, size_t size) {
    std::vector<T> out;
    auto it = std::find_if(kept.begin(), kept.end(), [&](const auto& v) { return v.size() == size; });
    if (it == kept.end() && !kept.empty()) it = kept.begin();
    if (it != kept.end()) {
        out = std::move(*it);
        kept.erase(it);
    }
    return out;
}
template <class T>
void keep(std::vector<std::vector<T>>& kept, std::vector<T>& v) {
    if (v.capacity() > 0 && kept.size() < 2) kept.push_back(std::move(v));
}

/// Below this a camera path's transmittance through a grid segment goes to Russian roulette.
constexpr float kTransmittanceRoulette = 0.25f;

/// The transmittance a camera path carries through the grid segment `seg`: residual ratio
/// tracking's estimate T (residualTransmittanceAlong), and below kTransmittanceRoulette Russian
/// roulette: kTransmittanceRoulette with probability T / kTransmittanceRoulette, else 0 (the path
/// ends). Unbiased; a path through thick smoke ends about as often as when all of the 4 stored
/// trackers stopped in it (the estimate this replaces), so it costs no more rays. The same tracker
/// is read at the segment's equiangular samples (`legs`, when there are any): their camera
/// transmittances, whose sum (their single scattering) goes to *single. Its draws do not depend on
/// the reads, so the path's stream is the same with and without them.
Rgb gridSegmentTransmittance(const Medium& med, const Ray& seg, Rng& rng, const EquiangularLegs& legs, Rgb* single) {
    float reads[EquiangularLegs::kMax];
    const float t = residualTransmittanceAlong(med, seg, seg.tMax, legs.t, legs.n, reads, rng);
    *single = legs.sum(reads);
    if (t >= kTransmittanceRoulette) return Rgb(t);
    return Rgb(rng.uniform() * kTransmittanceRoulette < t ? kTransmittanceRoulette : 0.0f);
}

/// A camera segment's transmittance in `med`: the closed form where it is homogeneous (*single 0:
/// the equiangular estimate there is whole), else gridSegmentTransmittance.
Rgb segmentTransmittance(const Medium& med, const Ray& seg, Rng& rng, const EquiangularLegs& legs, Rgb* single) {
    if (!med.homogeneous()) return gridSegmentTransmittance(med, seg, rng, legs, single);
    *single = Rgb(0.0f);
    return med.transmittance(seg.tMax);
}
}  // namespace

CameraPassStats& CameraPassStats::operator+=(const CameraPassStats& o) {
    rays += o.rays;
    beamQueries += o.beamQueries;
    beamHits += o.beamHits;
    return *this;
}

void PrimarySegmentPool::take(size_t pixels, size_t freeFlights, PrimarySegments& into) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        into.rays = takeFrom(m_rays, pixels);
        if (freeFlights > 0) into.freeFlights = takeFrom(m_freeFlights, freeFlights);
    }
    into.rays.resize(pixels);
    into.freeFlights.resize(freeFlights);
}

void PrimarySegmentPool::giveBack(PrimarySegments& from) {
    std::lock_guard<std::mutex> lock(m_mutex);
    keep(m_rays, from.rays);
    keep(m_freeFlights, from.freeFlights);
}

PrimaryPass CameraTracer::tracePrimary(uint64_t pass) const {
    const int w = m_settings.width, h = m_settings.height;
    const int nff = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
    const Camera& camera = m_scene.camera;
    const MediumId cameraMedium = m_rt.mediumAt(camera.position);
    PrimaryPass out;
    out.pass = pass;
    out.pool = m_segmentPool;
    PrimarySegments& primary = out.segments;
    primary.width = w;
    primary.height = h;
    m_segmentPool->take(size_t(w) * h, size_t(w) * h * nff, primary);  // every entry written below
    primary.freeFlightsPerRay = nff;
    primary.region = m_settings.region.in(w, h);
    const PixelRegion region = secondaryTiles(primary.region, w, h);
    out.hits = acquireHits(size_t(w) * h);
    std::vector<PrimaryHit>& hits = *out.hits;

    const Camera::RayGenerator generateRay(camera, w, h);

    // The pixel's keyed stream feeds the lens sample and a grid medium's stored distances: a
    // pinhole camera in a scene without grid media draws nothing from it.
    const bool jitterStream = camera.lensRadius > 0.0f || nff > 0;

    // --film-light-sampling: the pixels within FilmLightMixture::kReach of a light's image (with a
    // lens, of any of its images over the aperture), sorted by pixel, each with the light.
    struct FilmImage {
        Vec3 position;
        float depth;  // along the camera's forward axis
        double share;
        int light;    // index into Scene::lights
    };
    std::vector<FilmImage> filmImages;
    std::vector<std::pair<uint64_t, uint32_t>> filmPixels;
    for (const FilmLight& light : m_filmLights) {
        float fx, fy, depth;
        if (!camera.project(light.position, w, h, &fx, &fy, &depth)) continue;
        // The images over the lens: the pinhole image moved by up to this many pixels.
        const double confusion =
            camera.lensRadius > 0.0f
                ? double(camera.lensRadius) * std::abs(1.0 - double(camera.focusDistance) / depth) * double(h) /
                      (2.0 * double(camera.focusDistance) * std::tan(0.5 * double(camera.yFov)))
                : 0.0;
        const double reach = confusion + FilmLightMixture::kReach;
        const double x0 = std::max(double(region.x), std::floor(fx - reach - 1.0));
        const double x1 = std::min(double(region.x + region.width - 1), std::floor(fx + reach));
        const double y0 = std::max(double(region.y), std::floor(fy - reach - 1.0));
        const double y1 = std::min(double(region.y + region.height - 1), std::floor(fy + reach));
        if (x0 > x1 || y0 > y1 || (x1 - x0 + 1) * (y1 - y0 + 1) > 65536.0) continue;  // off the film, or a blur too wide
        const uint32_t index = uint32_t(filmImages.size());
        filmImages.push_back(FilmImage{light.position, depth, light.intensity / depth, light.light});
        for (int y = int(y0); y <= int(y1); ++y)
            for (int x = int(x0); x <= int(x1); ++x) filmPixels.emplace_back(uint64_t(y) * w + x, index);
    }
    std::sort(filmPixels.begin(), filmPixels.end());
    // The mixture q of the images of `lights` (FilmImage indices) that reach pixel (x, y) through
    // the lens point `lens` (with a lens, the image through it: where the ray from it to the light
    // meets the plane in focus, projected, the film position whose ray passes through the light).
    auto mixtureAt = [&](const uint32_t* lights, int count, int x, int y, Vec2 lens) {
        FilmLightMixture mixture;
        for (int j = 0; j < count; ++j) {
            const FilmImage& image = filmImages[lights[j]];
            float fx, fy, depth;
            if (camera.lensRadius > 0.0f) {
                const Vec2 disk = sampleConcentricDisk(lens.x, lens.y);
                const Vec3 o = camera.position + camera.right * (disk.x * camera.lensRadius) +
                               camera.up * (disk.y * camera.lensRadius);
                const Vec3 focus = o + (image.position - o) * (camera.focusDistance / image.depth);
                if (!camera.project(focus, w, h, &fx, &fy, &depth)) continue;
            } else if (!camera.project(image.position, w, h, &fx, &fy, &depth)) {
                continue;
            }
            const double px = double(fx) - x, py = double(fy) - y;
            if (FilmLightMixture::reaches(px, py)) mixture.add(px, py, image.share);
        }
        return mixture;
    };
    // Per pixel: its lights (at most FilmLightMixture::kMaxLights), the balance heuristic's scale
    // at its uniform film position (its jitter and lens point as the camera ray's below) and the
    // light-directed ray, from its own stream.
    for (size_t k = 0; k < filmPixels.size();) {
        const uint64_t pixel = filmPixels[k].first;
        uint32_t lights[FilmLightMixture::kMaxLights];
        int count = 0;
        for (; k < filmPixels.size() && filmPixels[k].first == pixel; ++k)
            if (count < FilmLightMixture::kMaxLights) lights[count++] = filmPixels[k].second;
        const int x = int(pixel % uint64_t(w)), y = int(pixel / uint64_t(w));
        FilmLightRay film;
        film.pixel = pixel;
        for (int j = 0; j < count; ++j) film.uniform.lights[film.uniform.n++] = filmImages[lights[j]].light;
        Vec2 lens{0.0f, 0.0f};
        if (jitterStream) {
            Rng jitter = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::PixelJitter);
            lens = Vec2{jitter.uniform(), jitter.uniform()};
        }
        const Vec2 uniform = pixelJitter(m_settings.seed, pass, pixel);
        film.uniform.scale = float(mixtureAt(lights, count, x, y, lens).uniformScale(uniform.x, uniform.y));
        Rng rng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::FilmLight);
        Vec2 extraLens{0.0f, 0.0f};
        if (camera.lensRadius > 0.0f) extraLens = Vec2{rng.uniform(), rng.uniform()};
        const FilmLightMixture mixture = mixtureAt(lights, count, x, y, extraLens);
        Vec2 position;
        if (mixture.sample(rng, &position)) {
            film.ray = generateRay(float(x) + position.x, float(y) + position.y, extraLens);
            film.extraScale = float(mixture.extraScale(position.x, position.y));
            film.rng = rng;
        }
        out.filmRays.push_back(film);
    }
    // Packets of 4 x 2 pixels (EmbreeScene::intersectCoherent): neighbouring camera rays share
    // most of their traversal.
    constexpr int kPacketWidth = EmbreeScene::kPacket / 2;
    const int rowPairs = (region.height + 1) / 2;
    std::atomic<uint64_t> nonDiffuseHits{0};
    tbb::parallel_for(0, rowPairs, [&](int pair) {
        uint64_t nonDiffuse = 0;
        const int y0 = region.y + 2 * pair, rows = std::min(2, region.y + region.height - y0);
        for (int x0 = region.x; x0 < region.x + region.width; x0 += kPacketWidth) {
            const int cols = std::min(kPacketWidth, region.x + region.width - x0);
            Ray rays[EmbreeScene::kPacket];
            SurfaceHit surfaceHits[EmbreeScene::kPacket];
            bool found[EmbreeScene::kPacket];
            Rng jitters[EmbreeScene::kPacket];
            uint64_t pixels[EmbreeScene::kPacket];
            int n = 0;
            for (int dy = 0; dy < rows; ++dy) {
                for (int dx = 0; dx < cols; ++dx, ++n) {
                    const int x = x0 + dx, y = y0 + dy;
                    const uint64_t pixel = uint64_t(y) * w + x;
                    pixels[n] = pixel;
                    Vec2 lens{0.0f, 0.0f};
                    if (jitterStream) {
                        jitters[n] = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::PixelJitter);
                        lens = Vec2{jitters[n].uniform(), jitters[n].uniform()};
                    }
                    const Vec2 film = pixelJitter(m_settings.seed, pass, pixel);
                    rays[n] = generateRay(float(x) + film.x, float(y) + film.y, lens);
                }
            }
            m_rt.intersectCoherent(rays, n, surfaceHits, found);
            for (int k = 0; k < n; ++k) {
                const uint64_t pixel = pixels[k];
                const Ray& ray = rays[k];
                PrimaryHit& ph = hits[pixel];
                if (nff > 0) std::fill_n(&primary.freeFlights[pixel * nff], nff, kInfinity);  // none stored
                ph.medium = cameraMedium;
                ph.throughput = Rgb(1.0f);
                ph.gridPending = false;
                ph.emitted = Rgb(0.0f);
                ph.surface = found[k];
                if (found[k]) {
                    ph.hit = surfaceHits[k];
                    nonDiffuse += m_nonDiffuseMesh[size_t(ph.hit.mesh)];
                }
                float tHit = ph.surface ? ph.hit.t : kInfinity;
                Ray seg;
                if (cameraMedium != kVacuum && m_rt.mediumSegment(ray.o, ray.d, tHit, &seg)) {
                    const Medium& med = m_scene.media[cameraMedium];
                    primary.rays[pixel] = PrimaryRay{seg.o, seg.tMax, seg.d, cameraMedium};
                    if (med.homogeneous()) {
                        ph.throughput = med.transmittance(seg.tMax);
                        ph.emitted = homogeneousEmission(med, seg.tMax);
                    } else {
                        float* ff = &primary.freeFlights[pixel * nff];
                        sampleCollisionDistances(med, seg, seg.tMax, jitters[k], nff, ff);
                        // ph.throughput: traceSecondary's, from the tracker its equiangular
                        // samples read (gridSegmentTransmittance).
                        ph.gridPending = true;
                        if (m_segmentEmission && med.emissive()) {
                            Rng emissionRng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::MediumEmission);
                            ph.emitted =
                                m_segmentEmission->estimate(cameraMedium, seg.o, seg.d, seg.tMax, emissionRng);
                        }
                    }
                } else {
                    primary.rays[pixel] = PrimaryRay{ray.o, 0.0f, ray.d, kVacuum};
                }
            }
        }
        nonDiffuseHits += nonDiffuse;
    });
    out.rays = uint64_t(region.width) * uint64_t(region.height);
    out.nonDiffuseHits = nonDiffuseHits.load();
    return out;
}

Rgb CameraTracer::filmLightRadiance(const FilmLightRay& film, int samples, Rgb* primary,
                                    uint64_t* rays) const {
    // Its stream after the film position and lens point tracePrimary drew from it.
    Rng rng = film.rng;
    EquiangularSubset lights = film.uniform;
    lights.only = true;
    lights.scale = film.extraScale;
    const int maxLength = m_settings.maxPathLength;
    const float spread = pixelSpread(m_scene.camera.yFov, m_settings.height);
    MediumId medium = m_rt.mediumAt(m_scene.camera.position);
    Ray ray = film.ray;
    Rgb throughput(1.0f), L;
    float pathLength = 0;
    // As a camera path's: `segment` counts the camera segments (Interface crossings start none);
    // single scattering along segment k is a light path of k + 1 segments.
    int segment = 1;
    for (int depth = 0;;) {
        if (maxLength > 0 && segment + 1 > maxLength) break;
        SurfaceHit hit;
        const bool surface = m_rt.intersect(ray, &hit);
        ++*rays;
        if (surface) pathLength += hit.t;
        Ray seg;
        if (medium != kVacuum && m_rt.mediumSegment(ray.o, ray.d, surface ? hit.t : kInfinity, &seg)) {
            const Medium& med = m_scene.media[medium];
            EquiangularLegs legs;
            Rgb single = m_equiangular->estimate(medium, seg.o, seg.d, seg.tMax, samples, rng,
                                                 med.homogeneous() ? nullptr : &legs, &lights);
            Rgb read;
            const Rgb transmittance = segmentTransmittance(med, seg, rng, legs, &read);
            single += read;
            L += throughput * single;
            if (segment == 1 && depth == 0) *primary = throughput * single;
            throughput *= transmittance;
        }
        if (!surface || throughput.isBlack()) break;
        // Through the lobes a camera path follows (mirrors, glass, glossy and a coat's specular
        // part, with its roulette); a diffuse end ends it.
        const float footprint = spread * pathLength;
        applyNormalMap(m_scene, &hit, footprint);
        const SurfacePoint sp = surfaceAt(m_scene, hit, footprint);
        const Bsdf bsdf = Bsdf::at(m_scene, hit, sp, ray.d, medium, TransportMode::Radiance, rng);
        const BsdfLobes lobes = bsdf.lobes();
        if (!(lobes & (kLobeGlossy | kLobeSpecular))) break;
        BsdfSample s;
        if (!bsdf.sample(rng, &throughput, &s, BsdfLobes(kLobesAll & ~kLobeDiffuse), [&](const Rgb&, const Rgb& w) {
                return (lobes & kLobeDiffuse) ? std::min(1.0f, 4.0f * w.maxComponent()) : kNoRoulette;
            }))
            break;
        if (!bsdf.isPassThrough() && ++segment > maxLength && maxLength > 0) break;
        medium = s.medium;
        ray = Ray{m_rt.offsetOrigin(hit.p, hit.t, hit.ng, s.wi), s.wi};
        if (++depth > m_settings.maxCameraBounces) break;
    }
    return L;
}

Image CameraTracer::traceSecondary(const PrimaryPass& primary, const PhotonMap& photons, const BeamBvh& beams,
                                   const SurfacePhotonGrid& surfacePhotons, CameraPassStats* stats,
                                   SecondaryLayers* layers, bool emission, Image* alpha) const {
    const int w = m_settings.width, h = m_settings.height;
    const int nff = m_anyHeterogeneous ? m_settings.freeFlightSamples : 0;
    const uint64_t pass = primary.pass;
    const float spread = pixelSpread(m_scene.camera.yFov, h);  // texture footprint per unit path length
    Image radiance(w, h);
    if (layers) *layers = SecondaryLayers{Image(w, h), Image(w, h), Image(w, h)};
    tbb::enumerable_thread_specific<ThreadScratch> scratch;
    // --photon-planes on: this batch's planes, gathered along every camera segment in a
    // homogeneous medium (cpu/plane_bvh.h).
    std::optional<PlaneBvh> planeBvh;
    if (!photons.planes.empty()) planeBvh.emplace(*m_rt.device(), photons.planes);
    // --medium-points: this batch's photon points in dense media, gathered along every camera
    // segment in a homogeneous medium (cpu/point_bvh.h).
    std::optional<PointBvh> pointBvh;
    std::vector<char> pointMedia(m_scene.media.size(), 0);  // the media that hold any
    // Whether a mesh is a boundary between two media (gatherPoints' bounded ends).
    auto boundsMedium = [&](int mesh) {
        return mesh >= 0 && m_scene.meshes[size_t(mesh)].interiorMedium != m_scene.meshes[size_t(mesh)].exteriorMedium;
    };
    if (!photons.points.empty()) {
        pointBvh.emplace(*m_rt.device(), photons.points);
        for (const MediumPoint& p : photons.points) pointMedia[size_t(p.medium)] = 1;
    }
    // The environment, where paths that leave the scene arrive (with the emission: one batch).
    const EnvironmentLight* environment = emission && m_scene.environment ? &*m_scene.environment : nullptr;
    // Camera paths that reach it straight (through Interface crossings alone) see it as the
    // background, unless it is hidden or the film is transparent.
    const bool background = environment && environment->visible() && !m_settings.transparentFilm;
    if (alpha) *alpha = Image(w, h);

    // Tiles of kTile x kTile pixels, row by row inside: neighbouring paths reuse each other's beam
    // candidates (BeamQueryCache) and surface-photon cells. With a render region, its tiles: every
    // pixel of each is traced, so the cache sees what it sees in the whole image's render, and
    // the region's pixels alone are stored (the others stay 0).
    const PixelRegion& stored = primary.segments.region;
    const PixelRegion region = secondaryTiles(stored, w, h);
    const int tilesX = (region.width + kTile - 1) / kTile, tilesY = (region.height + kTile - 1) / kTile;
    tbb::parallel_for(0, tilesX * tilesY, [&](int tile) {
        ThreadScratch& tls = scratch.local();
        tls.freeFlights.resize(std::max(nff, 1));
        tls.beamCache.reset();
        const int tx = tile % tilesX, ty = tile / tilesX;
        for (int i = 0; i < kTile * kTile; ++i) {
            const int x = region.x + tx * kTile + i % kTile, y = region.y + ty * kTile + i / kTile;
            if (x >= region.x + region.width || y >= region.y + region.height) continue;
            const bool keep = stored.contains(x, y);
            const uint64_t pixel = uint64_t(y) * w + x;
            // Written only for a grid's primary transmittance (PrimaryHit::throughput): by this
            // pixel's own task, while no other batch of the pass runs.
            PrimaryHit& ph = (*primary.hits)[pixel];
            Rgb throughput = ph.throughput, L, Lmedia, Lsurface, LmediaPrimary;
            float clear = 0;  // the share of this path that reached the background (transparent film)
            auto store = [&]() {
                if (!keep) return;
                radiance.at(x, y) = L;
                if (alpha) alpha->at(x, y) = Rgb(1.0f - clear);
                if (layers) {
                    layers->media.at(x, y) = Lmedia;
                    layers->surface.at(x, y) = Lsurface;
                    layers->mediaPrimary.at(x, y) = LmediaPrimary;
                }
            };
            // The primary segment's medium emission (the splatters add its beams) and, with
            // --equiangular on, its single scattering from point, spot, area and directional lights
            // and the environment (a light path of two segments), once per pass like the emission.
            if (emission) L = LmediaPrimary = ph.emitted;
            const int maxLength = m_settings.maxPathLength;
            // The pixel's distances per segment this pass: a fractional count's extra one spread
            // evenly over its passes (EquiangularScattering::samplesInPass).
            const int equiangularSamples =
                m_equiangular && emission
                    ? m_equiangular->samplesInPass(pass, EquiangularScattering::pixelPhase(m_settings.seed, pixel))
                    : 0;
            // Keyed only where it is drawn from: every use is an estimate of equiangularSamples
            // distances, which draws nothing for none (most pixels' passes at a fractional count).
            Rng equiangularRng = equiangularSamples > 0
                                     ? Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::Equiangular)
                                     : Rng();
            std::optional<Rng> emissionRng;  // keyed at the first later segment in an emitting grid
            // --film-light-sampling: near a light's image, this path's share of that light's single
            // scattering (FilmLightRay::uniform) and, with the emission, the light-directed ray's.
            const FilmLightRay* film = nullptr;
            if (!primary.filmRays.empty()) {
                auto it = std::lower_bound(primary.filmRays.begin(), primary.filmRays.end(), pixel,
                                           [](const FilmLightRay& f, uint64_t p) { return f.pixel < p; });
                if (it != primary.filmRays.end() && it->pixel == pixel) film = &*it;
            }
            const EquiangularSubset* filmSubset = film ? &film->uniform : nullptr;
            if (film && film->extraScale > 0 && equiangularSamples > 0) {
                Rgb primaryPart;
                const Rgb extra = filmLightRadiance(*film, equiangularSamples, &primaryPart, &tls.stats.rays);
                L += extra;
                LmediaPrimary += primaryPart;
                Lmedia += extra - primaryPart;
            }
            const PrimaryRay& pr = primary.segments.rays[pixel];
            // Through a grid the primary segment's transmittance is estimated here, by one tracker
            // that its equiangular samples read too (their camera legs), from its own stream.
            const bool primaryGrid =
                pr.medium != kVacuum && pr.tMax > 0 && !m_scene.media[pr.medium].homogeneous();
            EquiangularLegs& legs = tls.primaryLegs;
            legs.n = 0;
            if (((m_equiangular && emission) || planeBvh || pointBvh) && (maxLength == 0 || maxLength >= 2) &&
                pr.medium != kVacuum && pr.tMax > 0) {
                if (m_equiangular && emission) {
                    const Rgb single =
                        m_equiangular->estimate(pr.medium, pr.origin, pr.dir, pr.tMax, equiangularSamples,
                                                equiangularRng, primaryGrid ? &legs : nullptr, filmSubset);
                    L += single;
                    LmediaPrimary += single;
                }
                // --photon-planes on: this batch's planes along it too (the splatters draw only
                // beams), as along every later segment.
                if (planeBvh && m_scene.media[pr.medium].homogeneous()) {
                    const Rgb planes = gatherPlanes(m_rt, *planeBvh, pr.medium, pr.origin, pr.dir, pr.tMax,
                                                    maxLength > 0 ? maxLength - 1 : 0, tls.planes);
                    L += planes;
                    LmediaPrimary += planes;
                }
                // --medium-points: this batch's points along it too (the splatters draw only beams).
                if (pointBvh && pointMedia[size_t(pr.medium)]) {
                    // From the camera (no boundary) to a surface that may bound the medium.
                    const Rgb points = gatherPoints(m_scene, *pointBvh, pr.medium, pr.origin, pr.dir, pr.tMax,
                                                    maxLength > 0 ? maxLength - 1 : 0, 0.0f,
                                                    ph.surface && boundsMedium(ph.hit.mesh)
                                                        ? boundaryTangent(pr.dir, ph.hit.ng)
                                                        : 0.0f,
                                                    tls.planes);
                    L += points;
                    LmediaPrimary += points;
                }
            }
            // Its own keyed stream, so every batch of the pass would get the same estimate: it is
            // made once, in the emission batch (which reads it at the equiangular samples) or at
            // the first call, and kept for the others.
            if (primaryGrid && (emission || ph.gridPending)) {
                Rng trackerRng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::PrimaryTransmittance);
                Rgb single;
                ph.throughput = throughput = gridSegmentTransmittance(
                    m_scene.media[pr.medium], Ray{pr.origin, pr.dir, 0.0f, pr.tMax}, trackerRng, legs, &single);
                ph.gridPending = false;
                L += single;
                LmediaPrimary += single;
            }
            if (!ph.surface) {
                // Straight from the camera to the environment: its visible background (on a
                // transparent film, the coverage it leaves).
                clear = throughput.average();
                if (environment && background && !throughput.isBlack()) {
                    Lsurface = throughput * environment->eval(pr.dir);
                    L += Lsurface;
                }
                store();
                continue;
            }
            if (throughput.isBlack()) {
                store();
                continue;
            }
            Rng rng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::CameraPath);
            // Shadow rays draw from their own stream, so the path's other draws do not move; one
            // stream per path, so a path's shadow-ray vertices (a plastic, then the diffuse end)
            // draw different light samples.
            Rng neeRng = Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::DirectLight);
            // The first shadow ray's light choice from the pixel's sequence over the passes; a
            // later one (after a plastic's) from the stream.
            float lightChoice = lightChoiceUniform(m_settings.seed, pass, pixel);
            MediumId medium = ph.medium;
            SurfaceHit hit = ph.hit;
            Vec3 dir = pr.dir;
            float pathLength = hit.t;
            bool straight = true;  // no reflection or refraction yet (Interface crossings are none)
            // RenderSettings::maxPathLength: `segment` is the index of the camera segment that
            // reached `hit` (1 = primary; Interface crossings start none). A photon estimate here
            // joins a photon path of s segments into a light path of segment + s, a shadow ray
            // makes segment + 1; those beyond the cap are left out.
            int segment = 1;
            auto photonWithinCap = [&](const SurfacePhoton& p) {
                return maxLength == 0 || segment + int(p.segments) <= maxLength;
            };
            auto shadowRayWithinCap = [&]() { return maxLength == 0 || segment + 1 <= maxLength; };
            // After a rough vertex whose shadow ray could also reach area lights and the
            // environment (DirectLight::glossy): the continuation's density and where it left,
            // for the MIS weight of the emitter or environment it reaches; 0 = weight 1.
            float continuationPdf = 0;
            Vec3 continuationFrom;

            for (int depth = 0;;) {
                const TriangleMesh& mesh = m_scene.meshes[hit.mesh];
                const Material& mat = m_scene.materials[mesh.material];
                const float footprint = spread * pathLength;
                applyNormalMap(m_scene, &hit, footprint);
                HitSide side = hitSide(hit, dir);
                const SurfacePoint sp = surfaceAt(m_scene, hit, footprint);
                if (emission && mat.isEmissive() && side.entering) {
                    Rgb Le = throughput * sp.emission;
                    if (continuationPdf > 0)
                        Le *= m_direct->continuationWeight(continuationPdf, continuationFrom, hit.mesh, hit.triangle,
                                                           hit.p);
                    L += Le;
                    Lsurface += Le;
                }
                const Bsdf bsdf = Bsdf::at(m_scene, hit, sp, dir, medium, TransportMode::Radiance, rng);
                const BsdfLobes lobes = bsdf.lobes();
                // A rough continuation lobe (glossy, a rough coat's specular part) lit by area
                // lights or the environment: a shadow ray for them, MIS against the continuation
                // (docs/algorithm.md "Glossy vertices").
                const bool glossyDirect =
                    m_glossyDirect && emission && (lobes & kLobeGlossy) && shadowRayWithinCap();
                if (!(lobes & (kLobeGlossy | kLobeSpecular))) {
                    // With a shading normal each photon is weighted by its light-side cosine ratio
                    // (core/surface_hit.h, shadingCosineRatio); the same photons as density().
                    // With direct light, photons straight from a light are not counted (the photon
                    // tracer stores none on diffuse surfaces; glossy ones hold some).
                    const uint8_t skip = m_skipDirectPhotons ? kPhotonDirect : 0;
                    Rgb E;
                    if (m_boundary) {
                        // --surface-boundary on: each photon's kernel over the part of its disc
                        // on this surface (cpu/surface_boundary.h). Nothing to gather for a black
                        // surface.
                        const bool shading = hasShadingNormal(hit);
                        if (!sp.baseColor.isBlack()) {
                            SurfaceBoundary::AtPoint coverage(*m_boundary, hit.p, hit.ng);
                            // The photons on the path's side alone (SurfaceBoundary::kNormalAgreement).
                            static_assert(SurfaceBoundary::kNormalAgreement == kSurfaceNormalAgreement);
                            // Farther than the largest radius from every edge, with no shading
                            // normal, no photon skipped and no cap, every weight below is exactly
                            // 1: the unweighted sum, bit for bit (most gather points).
                            if (!shading && skip == 0 && maxLength == 0 &&
                                coverage.clearUpTo(surfacePhotons.maxRadius())) {
                                E = surfacePhotons.density(hit.p, side.nf);
                            } else {
                                E = surfacePhotons.gatherFacing(hit.p, side.nf, [&](const SurfacePhoton& p) {
                                    if ((p.flags & skip) || !photonWithinCap(p)) return 0.0f;
                                    // Divided only where the coverage is not 1: x / 1 is x.
                                    const float c = coverage(p.radius);
                                    const float ratio = shading ? shadingCosineRatio(side, p.wi) : 1.0f;
                                    return c == 1.0f ? ratio : ratio / c;
                                });
                            }
                        }
                    } else {
                        E = !hasShadingNormal(hit) && skip == 0 && maxLength == 0
                                ? surfacePhotons.density(hit.p, side.nf)
                                : surfacePhotons.gatherFacing(hit.p, side.nf, [&](const SurfacePhoton& p) {
                                      return (p.flags & skip) || !photonWithinCap(p) ? 0.0f
                                                                                     : shadingCosineRatio(side, p.wi);
                                  });
                    }
                    // Direct light by a shadow ray (once per pass: with the emission); none toward
                    // a black surface.
                    if (m_direct && emission && !sp.baseColor.isBlack() && shadowRayWithinCap()) {
                        // The source chosen by what it sends into this pixel's colour and cosine.
                        const DirectReceiver receiver{side.nf, side.nsf, throughput * sp.baseColor, lightChoice};
                        lightChoice = -1.0f;
                        E += m_direct->diffuse(hit, side, medium, neeRng, false, &receiver);
                    }
                    Rgb density = throughput * sp.baseColor * kInvPi * E;
                    L += density;
                    Lsurface += density;
                    break;
                }
                if (lobes & kLobeDiffuse) {
                    // docs/algorithm.md "Coated (plastic) vertices". The diffuse part is this path's
                    // end: the density estimate of the photons stored here, weighted by f_d, and with
                    // --direct-light on a shadow ray for the light that arrives unscattered (whose
                    // photons the diffuse part then skips), as at a diffuse end. The specular part:
                    // the delta-path photons with f_s (light the continuation cannot find), then the
                    // path continues through the specular lobe alone (below). Shading normal: times
                    // |wi . ns| / |wi . ng|.
                    const bool shading = hasShadingNormal(hit);
                    const uint8_t directLit = m_direct ? kPhotonDirect : 0;
                    auto photonWeight = [&](const SurfacePhoton& p) {
                        if (!photonWithinCap(p)) return Rgb(0.0f);
                        const BsdfLobes parts = ((p.flags & directLit) ? 0 : kLobeDiffuse) |
                                                ((p.flags & kPhotonDeltaPath) ? kLobeGlossy | kLobeSpecular : 0);
                        Rgb f = bsdf.f(p.wi, parts);
                        return shading ? f * shadingOverGeometricCosine(hit, p.wi) : f;
                    };
                    // --surface-boundary on: both parts' density estimates over the part of the
                    // kernel's disc on this surface, as at a diffuse end.
                    std::optional<SurfaceBoundary::AtPoint> coverage;
                    if (m_boundary) coverage.emplace(*m_boundary, hit.p, hit.ng);
                    Rgb coated = throughput * surfacePhotons.gatherFacing(hit.p, side.nf, [&](const SurfacePhoton& p) {
                        return coverage ? photonWeight(p) / (*coverage)(p.radius) : photonWeight(p);
                    });
                    if (m_direct && emission && !sp.baseColor.isBlack() && shadowRayWithinCap()) {
                        const DirectReceiver receiver{side.nf, side.nsf, throughput * sp.baseColor, lightChoice};
                        lightChoice = -1.0f;
                        coated += throughput * m_direct->reflected(
                                                   hit, side, medium, neeRng,
                                                   [&](const DirectLightSample& ls) {
                                                       return bsdf.f(ls.wi, kLobeDiffuse) * diffuseCosine(side, ls.wi);
                                                   },
                                                   &receiver);
                    }
                    if (glossyDirect) coated += throughput * m_direct->glossy(bsdf, kLobeGlossy, hit, medium, neeRng);
                    L += coated;
                    Lsurface += coated;
                } else if (lobes & kLobeGlossy) {
                    // docs/algorithm.md "Glossy vertices": photons stored here from delta lights
                    // through delta interactions only (kPhotonDeltaPath) with the BSDF evaluated,
                    // then continue by sampling it. Surfaces that also store photons for a diffuse
                    // part (partly transmissive, plastic) hold others too: the flag skips them.
                    const bool shading = hasShadingNormal(hit);
                    Rgb glossy =
                        throughput * surfacePhotons.gather(hit.p, hit.ng, [&](const SurfacePhoton& p) {
                            if (!(p.flags & kPhotonDeltaPath) || !photonWithinCap(p)) return Rgb(0.0f);
                            Rgb f = bsdf.f(p.wi);
                            return shading ? f * shadingOverGeometricCosine(hit, p.wi) : f;
                        });
                    if (glossyDirect) glossy += throughput * m_direct->glossy(bsdf, kLobeGlossy, hit, medium, neeRng);
                    L += glossy;
                    Lsurface += glossy;
                }
                // The path goes on through the lobes the photons cannot stand for. The coat's
                // specular part alone, with Russian roulette: kept with probability 4x its weight
                // (the weight is ~F, 0.04 at normal incidence: continuing every path would cost a ray
                // and a beam query per plastic hit for little; keeping only F of them, at weight 1,
                // made the reflections speckle at tens of passes).
                BsdfSample s;
                if (!bsdf.sample(rng, &throughput, &s, BsdfLobes(kLobesAll & ~kLobeDiffuse), [&](const Rgb&, const Rgb& w) {
                        return (lobes & kLobeDiffuse) ? std::min(1.0f, 4.0f * w.maxComponent()) : kNoRoulette;
                    }))
                    break;
                if (!bsdf.isPassThrough()) {
                    continuationPdf = glossyDirect && (s.lobe & kLobeGlossy) ? s.pdf : 0.0f;
                    continuationFrom = hit.p;
                    if (++segment > maxLength && maxLength > 0) break;
                }
                medium = s.medium;
                straight = straight && bsdf.isPassThrough();
                Ray ray{m_rt.offsetOrigin(hit.p, hit.t, hit.ng, s.wi), s.wi};
                dir = ray.d;
                if (++depth > m_settings.maxCameraBounces) break;

                // The surface the segment leaves: gatherPoints' bounded start.
                const float tanStart = boundsMedium(hit.mesh) ? boundaryTangent(dir, hit.ng) : 0.0f;
                bool surface = m_rt.intersect(ray, &hit);
                tls.stats.rays++;
                if (surface) pathLength += hit.t;
                float tHit = surface ? hit.t : kInfinity;
                Ray seg;
                if (medium != kVacuum && m_rt.mediumSegment(ray.o, ray.d, tHit, &seg)) {
                    const Medium& med = m_scene.media[medium];
                    float* ff = tls.freeFlights.data();
                    Rgb emitted;  // the segment's medium emission, with the pass's emission only
                    EquiangularLegs& legs = tls.segmentLegs;  // its equiangular samples' camera legs, in a grid
                    legs.n = 0;
                    if (!med.homogeneous()) {
                        sampleCollisionDistances(med, seg, seg.tMax, rng, nff, ff);
                        if (emission && m_segmentEmission && med.emissive()) {
                            if (!emissionRng)
                                emissionRng.emplace(
                                    Rng::forKey(m_settings.seed, pass, pixel, StreamPurpose::LaterMediumEmission));
                            emitted = m_segmentEmission->estimate(medium, seg.o, seg.d, seg.tMax, *emissionRng);
                        }
                    } else if (emission) {
                        emitted = homogeneousEmission(med, seg.tMax);
                    }
                    // Beams of photon paths that fit the cap with this segment (none when it is full);
                    // the medium's own emission is a path of `segment` segments, always within it.
                    const int maxBeamSegment = maxLength > 0 ? maxLength - segment : 0;
                    if (maxLength == 0 || maxBeamSegment > 0) {
                        beams.query(seg.o, seg.d, seg.tMax, tls.hits, tls.beamCache);
                        tls.stats.beamQueries++;
                        tls.stats.beamHits += tls.hits.size();
                        emitted += gatherBeams(m_scene, photons, tls.hits, medium, seg.o, seg.d, ff, nff, maxBeamSegment);
                        if (m_equiangular && emission)
                            emitted += m_equiangular->estimate(medium, seg.o, seg.d, seg.tMax, equiangularSamples,
                                                               equiangularRng, med.homogeneous() ? nullptr : &legs,
                                                               filmSubset);
                        if (planeBvh && med.homogeneous())
                            emitted += gatherPlanes(m_rt, *planeBvh, medium, seg.o, seg.d, seg.tMax, maxBeamSegment,
                                                    tls.planes);
                        if (pointBvh && pointMedia[size_t(medium)])
                            emitted += gatherPoints(m_scene, *pointBvh, medium, seg.o, seg.d, seg.tMax, maxBeamSegment,
                                                    tanStart,
                                                    surface && boundsMedium(hit.mesh) ? boundaryTangent(seg.d, hit.ng)
                                                                                      : 0.0f,
                                                    tls.planes);
                    }
                    // The segment's transmittance, and in a grid its equiangular legs' from the
                    // same tracker.
                    Rgb single;
                    const Rgb transmittance = segmentTransmittance(med, seg, rng, legs, &single);
                    emitted += single;
                    Rgb media = throughput * emitted;
                    L += media;
                    Lmedia += media;
                    throughput *= transmittance;
                }
                if (!surface) {
                    // Left the scene: the environment (hidden from straight paths when not visible
                    // or on a transparent film, where they leave their coverage instead).
                    if (straight) clear = throughput.average();
                    if (environment && (!straight || background) && !throughput.isBlack()) {
                        Rgb Le = throughput * environment->eval(dir);
                        if (continuationPdf > 0)
                            Le *= m_direct->continuationWeight(continuationPdf, continuationFrom, dir);
                        L += Le;
                        Lsurface += Le;
                    }
                    break;
                }
                if (throughput.isBlack()) break;
            }
            store();
        }
    });
    if (stats) {
        for (const ThreadScratch& s : scratch) *stats += s.stats;
    }
    return radiance;
}

}  // namespace tyndall
