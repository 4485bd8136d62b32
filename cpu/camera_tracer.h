#pragma once
// Camera paths (PPB step 2 and the CPU half of step 3/4): one jittered path per pixel per pass,
// in two stages so a scheduler can splat the primary segments while the CPU does the rest:
//   tracePrimary(i)                         the first segment (camera -> first surface) of every
//                                           pixel: recorded for a beam splatter (CPU rasterizer or
//                                           GL), which adds its medium radiance; needs no photons;
//                                           also estimates the segment's medium emission
//                                           (cpu/segment_emission.h)
//   traceSecondary(i, primary, photons...)  the rest of each path: the primary segment's medium
//                                           emission, emission at the first hit, then
//                                           through mirrors and glass (Fresnel choice), every later
//                                           segment inside a medium gathering the pass's beams
//                                           through the BeamBvh (and its medium emission), a diffuse hit ending the path with
//                                           the surface-photon estimate (with --surface-boundary on
//                                           divided by its kernel's coverage, cpu/surface_boundary.h)
//                                           and, with --direct-light on,
//                                           a shadow ray to a light (cpu/direct_light.h) for the
//                                           light that arrives there without scattering; with
//                                           --equiangular on, every segment in a medium (the
//                                           primary one too) adds the single scattering of point,
//                                           spot, area and directional lights and the environment
//                                           (cpu/equiangular.h), and with
//                                           --film-light-sampling on a pixel near a point or spot
//                                           light's image also traces a light-directed ray for
//                                           that light's single scattering (FilmLightRay); with
//                                           --photon-planes on, every segment in a homogeneous
//                                           medium (the primary one too) gathers the batch's
//                                           photon planes (cpu/plane_bvh.h); a path
//                                           that leaves the scene adds the environment's radiance
//                                           (Scene::environment; one straight from the camera only
//                                           when it is visible)
// PassRenderer::traceCamera runs both. The camera is read from the scene at each tracePrimary call, so a camera
// that moves between passes (the viewer's reset) is followed, the medium it sits in included.
//
// Deterministic: pixel p of pass i takes its film jitter from pixelJitter(seed, i, p) (a
// low-discrepancy sequence over the passes, core/pixel_jitter.h), draws its lens sample and its
// primary stored distances from Rng::forKey(seed, i, p, PixelJitter), the rest of its path from (seed, i, p, CameraPath) and
// its shadow ray from (seed, i, p, DirectLight) and its equiangular samples from (seed, i, p,
// Equiangular), a pixel near a light's image its light-directed ray from (seed, i, p, FilmLight),
// so the split changes no bit of the image.
#include <cstdint>
#include <memory>
#include <mutex>

#include "core/image.h"
#include "core/photon_beam.h"
#include "core/primary_segments.h"
#include "core/settings.h"
#include "cpu/beam_bvh.h"
#include "cpu/direct_light.h"
#include "cpu/embree_scene.h"
#include "cpu/equiangular.h"
#include "cpu/segment_emission.h"
#include "cpu/surface_boundary.h"
#include "cpu/surface_photon_grid.h"

namespace tyndall {

struct CameraPassStats {
    uint64_t rays = 0;         ///< surface rays traced
    uint64_t beamQueries = 0;  ///< secondary segments gathered through the BVH
    uint64_t beamHits = 0;     ///< beam x ray pairs found by those queries

    CameraPassStats& operator+=(const CameraPassStats& o);
};

/// Where a pixel's primary segment ended, for the secondary stage (CPU only, not uploaded).
struct PrimaryHit {
    SurfaceHit hit;
    /// Transmittance of the primary segment. Through a grid traceSecondary estimates it (its
    /// emission batch, or the first call to find `gridPending`) and keeps it here for the pass's
    /// other batches.
    Rgb throughput;
    Rgb emitted;                ///< the medium's emission along it (estimate; cpu/free_flight.h)
    MediumId medium = kVacuum;  ///< the medium the camera ray ran through
    bool surface = false;       ///< false: the ray left the scene
    bool gridPending = false;   ///< a grid's `throughput` not estimated yet
};

/// Per-pixel primary hits, taken from and given back to the CameraTracer's pool: a 1080p pass's
/// hits are 160 MB, and allocating and zeroing them anew every pass cost about 15% of its time in
/// page faults and initialisation (perf; CHANGELOG.md, 2026-12-02). Given back when the last PrimaryPass
/// holding them goes; the pool keeps at most two (a pass and the one a scheduler overlaps with it).
using PrimaryHitBuffer = std::shared_ptr<std::vector<PrimaryHit>>;

/// Where PrimaryPass gives its segments' arrays back (CameraTracer's pool; see PrimaryPass).
class PrimarySegmentPool {
public:
    /// Storage for `pixels` rays and `freeFlights` distances (contents stale).
    void take(size_t pixels, size_t freeFlights, PrimarySegments& into);
    void giveBack(PrimarySegments& from);

private:
    std::mutex m_mutex;
    std::vector<std::vector<PrimaryRay>> m_rays;  // at most two of each kept
    std::vector<std::vector<float>> m_freeFlights;
};

/// --film-light-sampling: a pixel near the image of point or spot lights in a medium (docs/
/// algorithm.md "Camera rays near a light's image"). Its camera path keeps its uniform film
/// position; its estimate of those lights' single scattering is scaled by `uniform.scale`
/// (1 / (1 + q) at that position), and one more camera ray, from a film position drawn from q,
/// carries those lights' single scattering alone, scaled by `extraScale` (1 / (1 + q) at its own).
struct FilmLightRay {
    uint64_t pixel = 0;
    EquiangularSubset uniform;  ///< the lights, and the uniform position's scale (not `only`)
    Ray ray;                    ///< the light-directed camera ray
    float extraScale = 0;       ///< 0: no such ray this pass (no light's image within reach)
    Rng rng;                    ///< the ray's stream (seed, pass, pixel, FilmLight) after its position
};

/// The primary stage of a pass: the splatters' input and where the secondary stage goes on.
/// Move-only. Its segments' arrays (66 MB of rays at 1080p) go back to the CameraTracer's pool
/// when it is destroyed, unless they were moved out first, so the next pass reuses them instead
/// of allocating and page-faulting them anew (CHANGELOG.md, 2026-12-02).
struct PrimaryPass {
    uint64_t pass = 0;
    PrimarySegments segments;
    PrimaryHitBuffer hits;  ///< per pixel, row-major like segments.rays
    uint64_t rays = 0;      ///< surface rays traced
    /// Pixels whose camera ray first meets a surface whose material is not diffuse: about the
    /// secondary stage's beam queries (BeamBvh::piecesFor). Counted while tracing, so no serial
    /// walk over the hits is needed.
    uint64_t nonDiffuseHits = 0;
    /// The pixels near a light's image (--film-light-sampling), sorted by pixel.
    std::vector<FilmLightRay> filmRays;
    std::shared_ptr<PrimarySegmentPool> pool;

    PrimaryPass() = default;
    PrimaryPass(PrimaryPass&&) = default;
    PrimaryPass& operator=(PrimaryPass&&) = default;
    ~PrimaryPass() {
        if (pool) pool->giveBack(segments);
    }
};

/// The secondary stage's radiance split by what it comes from (AOV layers); the three add up to
/// the stage's radiance (up to float rounding).
struct SecondaryLayers {
    Image media;         ///< media seen through mirrors and glass (the secondary segments)
    Image surface;       ///< surface photons and emission
    Image mediaPrimary;  ///< the primary segments' medium light not splatted: emission, equiangular, planes
};

struct CameraPassResult {
    Image radiance;  ///< everything except the primary segments' medium radiance
    PrimarySegments primary;
    CameraPassStats stats;
};

class CameraTracer {
public:
    CameraTracer(const EmbreeScene& rt, const RenderSettings& settings);
    /// The scene's lights changed (powers, positions; not their number): rebuilds the shadow
    /// rays' light sampler and the equiangular estimator, whose source choices follow the powers
    /// they were built with. Call between passes (PassRenderer::sceneChanged).
    void lightsChanged();

    PrimaryPass tracePrimary(uint64_t pass) const;
    /// The pass's radiance except the primary segments' media; `stats.rays` counts this stage's.
    /// With `photons` one batch of the pass, the photon estimates of that batch; `emission` adds
    /// what the paths see of emitters and the direct light of their shadow rays, which belong to
    /// one batch only (the pass's first).
    /// `layers`, when given, also receives that radiance split in two (it does not change it).
    /// With RenderSettings::transparentFilm, paths that reach the environment straight (through
    /// Interface crossings alone) do not see it. `alpha`, when given (with `emission`: once per
    /// pass), receives each pixel's coverage: 1 minus the mean over r, g, b of such a path's
    /// throughput (its transmittance through the media it crossed), in every channel; 1 where the
    /// path met a visible surface. Averaged over passes: 1 minus the share of the pixel's camera
    /// paths that reached the background (Cycles' transparent film).
    Image traceSecondary(const PrimaryPass& primary, const PhotonMap& photons, const BeamBvh& beams,
                         const SurfacePhotonGrid& surface, CameraPassStats* stats,
                         SecondaryLayers* layers = nullptr, bool emission = true, Image* alpha = nullptr) const;

private:
    struct HitPool {
        std::mutex mutex;
        std::vector<std::unique_ptr<std::vector<PrimaryHit>>> free;
    };
    /// `pixels` hits from the pool (contents stale: tracePrimary overwrites every pixel).
    PrimaryHitBuffer acquireHits(size_t pixels) const;
    /// The light-directed camera ray of `film`: its lights'
    /// single scattering (`samples` equiangular distances a segment) along its camera segments
    /// in media, through mirrors and glass as a camera path goes, scaled by film.extraScale; the
    /// part along its primary segment also goes to *primary. Draws from film.rng; counts its
    /// surface rays in *rays.
    Rgb filmLightRadiance(const FilmLightRay& film, int samples, Rgb* primary, uint64_t* rays) const;

    const EmbreeScene& m_rt;
    const Scene& m_scene;
    RenderSettings m_settings;
    bool m_anyHeterogeneous = false;
    std::vector<uint8_t> m_nonDiffuseMesh;  ///< per mesh: its material is not diffuse (PrimaryPass::nonDiffuseHits)
    /// --direct-light on: the light sampler and shadow rays of the diffuse ends; null when off.
    std::unique_ptr<LightSampler> m_lights;
    std::unique_ptr<DirectLight> m_direct;
    /// With m_direct, the scene has area lights or an environment: rough continuation lobes get
    /// shadow rays for them too (DirectLight::glossy), MIS-weighted against the continuation.
    bool m_glossyDirect = false;
    /// --surface-boundary on: the surface kernel's coverage at edges (cpu/surface_boundary.h).
    std::unique_ptr<SurfaceBoundary> m_boundary;
    /// --equiangular on (and a point, spot, area or directional light, or an environment): single
    /// scattering along every camera segment in a medium (cpu/equiangular.h); null otherwise.
    std::unique_ptr<EquiangularScattering> m_equiangular;
    /// --film-light-sampling on (with m_equiangular): the point and spot lights inside a
    /// scattering medium, whose images draw the film positions of the pixels near them
    /// (core/film_light_sampler.h), with their intensities' means and indices into Scene::lights.
    struct FilmLight {
        Vec3 position;
        double intensity = 0;
        int light = 0;
    };
    std::vector<FilmLight> m_filmLights;
    /// The emission of grid media along every camera segment (cpu/segment_emission.h); null when
    /// no grid medium emits.
    std::unique_ptr<SegmentEmission> m_segmentEmission;
    bool m_skipDirectPhotons = false;  ///< the diffuse gather must test kPhotonDirect (glossy photons)
    std::shared_ptr<HitPool> m_hitPool = std::make_shared<HitPool>();
    std::shared_ptr<PrimarySegmentPool> m_segmentPool = std::make_shared<PrimarySegmentPool>();
};

/// Medium radiance gathered from `beams` along the segment o + s d, s in [0, sMax], inside
/// `medium`, before the camera path's throughput. `segmentFreeFlights` (n distances from `o`) are
/// the segment's own stored transmittance samples for grid media (ignored for homogeneous ones).
/// `maxBeamSegment` > 0 (a capped path length): only beams whose PhotonMap::beamSegments index is
/// at most that; 0 = every beam.
Rgb gatherBeams(const Scene& scene, const PhotonMap& photons, const std::vector<BeamHitRecord>& hits, MediumId medium,
                const Vec3& o, const Vec3& d, const float* segmentFreeFlights, int n, int maxBeamSegment = 0);

}  // namespace tyndall
