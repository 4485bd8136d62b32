#pragma once
// The in-tree reference: an unbiased volumetric path tracer on the same scene representation as
// PPB, the ground truth for tests and for `tyndall reference`.
//
// It estimates the same integral as the PPB renderer, treating everything the same way:
//   - camera rays: the film/lens jitter convention of CameraTracer (uniform jitter inside the
//     pixel, Camera::generateRay's concentric lens sample), starting in mediumAt(camera);
//   - media: every path segment inside a medium (the global medium clipped to the scene bounds,
//     as EmbreeScene::globalMediumInterval does for photon and camera paths) samples a free
//     flight (sampleFreeFlight: spectral MIS for homogeneous media, delta tracking for grid
//     media); at a real collision the path scatters with the HG phase function. (PPB's camera
//     paths never scatter in media: they gather beams instead. Different estimator, same answer.)
//   - surfaces: diffuse (Lambertian about the geometric normal, like photon bounces and the
//     surface-photon estimate), every material through Bsdf (core/bsdf.h) in
//     TransportMode::Radiance (Fresnel choice, 1/eta^2 radiance scaling), Interface surfaces
//     pass straight through and switch the medium;
//   - emission: from the front (normal) side of emissive triangles only; emissive media add
//     estimateEmission along every medium segment (cpu/free_flight.h: exact for homogeneous
//     media, ratio tracking in grids), never sampled by NEE.
//
// Next-event estimation at every diffuse and medium-scattering vertex: one light sample
// (LightSampler::sampleDirect, the source chosen by what it can send to the vertex) with a shadow ray that passes through Interface
// surfaces (switching medium, multiplying their transmittance: analytic, or ratio tracking in
// grid media) and is blocked by any other surface. Area lights combine NEE with BSDF/phase
// sampling by multiple importance sampling (power heuristic); emission reached after a mirror or
// glass event is counted with weight 1, since NEE cannot reach it.
//
// Point and spot lights inside media: with free-flight vertices alone, NEE to a point light has
// infinite variance (the 1/d^2 near the light is not matched by the vertex density), which shows
// as fireflies that never settle. With `equiangular` on, the light these lights scatter into each
// medium segment is estimated instead by equiangular sampling along the segment (Kulla & Fajardo
// 2012: distance pdf proportional to 1/(h^2 + (t - t_c)^2), h the light's distance to the line),
// and the free-flight vertices leave point and spot lights out of their NEE. Each strategy divides
// by its own choice probability (the segment's by power, the vertex's sampleDirect's), so each
// part is unbiased on its own lights and the two add up to the whole.
//
// LIMITATION (inherent to path tracing, not a bug): delta lights (point, spot, directional)
// seen only through or via a mirror or glass surface are unreachable: NEE is blocked by the
// specular surface and a scattered path can never hit a point. So the reference misses every
// caustic from a delta light (light -> mirror/glass -> diffuse surface or medium), e.g. the
// volumetric caustic of the default scene and any light sitting inside glass. PPB renders those
// (photons start at the light). Scenes used to validate PPB against the reference must keep
// delta lights from shining directly onto specular surfaces, or use area lights, which the
// reference reaches by direction sampling.
//
// Deterministic: sample s of pixel p draws everything (jitter, lens, path) from
// Rng::forKey(seed, s, p, ReferencePath), so any thread count gives the same image.
// Paths are terminated by Russian roulette after `rouletteDepth` scattering vertices and cut at
// `maxDepth`. Paths that leave the scene (the global medium ends at the scene's bounds) see the
// environment, if any: weighted by MIS against its light samples after a diffuse, glossy or medium
// vertex, fully after the camera or a mirror or glass event, and not at all straight from the
// camera when it is not visible.
#include <cstdint>
#include <functional>
#include <nlohmann/json_fwd.hpp>

#include "core/image.h"
#include "core/light_sampler.h"
#include "cpu/direct_light.h"
#include "cpu/embree_scene.h"

namespace tyndall {

struct ReferenceSettings {
    int width = 512;
    int height = 512;
    uint32_t samplesPerPixel = 64;
    uint64_t seed = 1;
    /// Most scattering vertices on a path: diffuse, mirror, glass or medium events (Interface
    /// crossings do not count). 1 = direct lighting and single scattering only.
    int maxDepth = 64;
    /// Most segments of a path, camera to light (RenderSettings::maxPathLength: a path of d
    /// scattering vertices has d + 1); 0 = uncapped. Paths stop at min(maxDepth, this - 1) vertices.
    int maxPathLength = 0;
    /// Russian roulette from this many scattering vertices on (survival = max throughput, <= 1).
    int rouletteDepth = 5;
    /// Off: no light sampling; only emissive surfaces hit by scattered paths contribute (delta
    /// lights then contribute nothing). For testing the MIS weights.
    bool nextEventEstimation = true;
    /// Equiangular sampling of point/spot in-scattering along medium segments (see above); off:
    /// those lights are sampled from free-flight vertices like the others. Needs NEE.
    bool equiangular = true;
    /// The transparent film (RenderSettings::transparentFilm, as PPB's camera paths define it):
    /// paths that reach the environment straight (no scattering vertex, through Interface
    /// crossings alone) do not see it, and ReferenceImage::alpha gets each pixel's coverage, 1
    /// minus the mean over its paths of that share (the channels' mean of their throughput, an
    /// unbiased estimate of the fog's transmittance along them).
    bool transparentFilm = false;

    /// Throws Error naming the option when a value is out of range.
    void validate() const;
    nlohmann::json toJson() const;
};

/// A reference render: the per-pixel mean of the samples and the variance of that mean
/// (unbiased sample variance / samples per pixel), both in radiance units.
struct ReferenceImage {
    Image mean;
    Image varianceOfMean;
    Image alpha;  ///< ReferenceSettings::transparentFilm only: the coverage (in every channel)
};

class ReferenceTracer {
public:
    ReferenceTracer(const EmbreeScene& rt, const ReferenceSettings& settings);

    /// All pixels, TBB-parallel over rows. `onRow` (optional) is called after each finished
    /// row with the number of rows done so far, from worker threads but never concurrently.
    ReferenceImage render(const std::function<void(int rowsDone)>& onRow = {}) const;

    /// One radiance sample of pixel (x, y): sample `s` of the pixel's deterministic sequence.
    /// `clear` (optional): the share of the path that reached the environment straight (its
    /// throughput's channel mean then, else 0), the transparent film's complement of coverage.
    Rgb sample(int x, int y, uint32_t s, float* clear = nullptr) const;

    /// One estimate of the radiance arriving at `ray.o` from direction -ray.d (ray.d unit), the
    /// ray starting inside `medium`. For tests that probe single rays.
    Rgb radiance(Ray ray, MediumId medium, Rng& rng, float* clear = nullptr) const;

    MediumId cameraMedium() const { return m_cameraMedium; }
    const ReferenceSettings& settings() const { return m_settings; }

private:
    /// Equiangular estimate of the light point/spot lights scatter toward seg.o along the medium
    /// segment `seg` (seg.d unit, length seg.tMax) inside `medium`, before the path throughput.
    Rgb pointLightInScattering(const Ray& seg, MediumId medium, Rng& rng) const;
    /// A point or spot light (the lights the equiangular strategy handles).
    bool isPointLike(int source) const;

    const EmbreeScene& m_rt;
    const Scene& m_scene;
    ReferenceSettings m_settings;
    int m_maxVertices;  ///< maxDepth, or maxPathLength - 1 when that is fewer
    LightSampler m_lights;
    DirectLight m_direct;  ///< light sampling and shadow rays (cpu/direct_light.h), shared with PPB
    MediumId m_cameraMedium;
};

/// `scene` with every mirror and glass surface (smooth or rough) made an index-matched Interface,
/// media kept: no delta light reaches anything through a specular bounce, so the path tracer is
/// valid on it (docs/reference.md, "What it cannot compute"). Used to compare PPB with it on the
/// scene library (the SceneLibrary tests, build/bench/tyndall_quality --library).
Scene withoutSpecularSurfaces(const Scene& scene);

}  // namespace tyndall
