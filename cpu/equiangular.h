#pragma once
// Single scattering from point, spot, area and directional lights along a camera segment inside a
// medium (docs/algorithm.md "Single scattering by equiangular sampling"). For the segment o + s d,
// s in [0, sMax], and each such source, one point x = o + s d is drawn and a shadow ray sent from
// it toward the light.
//
// Point, spot and area lights, by equiangular sampling (core/equiangular.h): a light point p is
// taken (a point or spot light's position; for the area lights, a point on an emissive triangle
// chosen by power, uniform on it, with area density pdf_A) and
//   L = sigma_s(x) p_HG(w_l . -d) E / |x - p|^2 Tr_light(p -> x) Tr_cam(0 -> s) / pdf(s)
// with E = I F for a point or spot light (intensity, spot falloff) and Le cos_l / pdf_A for an
// area light (cos_l the emitter's cosine toward x; one-sided: the segment is first clipped to the
// half-space in front of the triangle), w_l the light's travel direction (p -> x), Tr_light a shadow
// ray's transmittance (cpu/direct_light.h: analytic, or ratio tracking through grid media on the
// way, through Interfaces, blocked by every other surface) and Tr_cam the segment's own (analytic,
// or residual ratio tracking in a grid: one tracker for all of a segment's samples, the camera
// tracer's for the segment's own transmittance where it takes them as EquiangularLegs). In a
// homogeneous medium pdf(s) is equiangular, proportional to
// 1 / |x - p|^2; in a grid it is that times the majorant along the segment (the majorant grid's
// pieces, cpu/free_flight.h MajorantPieces), so no sample lands where the grid is empty and
// sigma_s(x) / pdf(s) stays bounded. For a spot the segment is first clipped to the spot's outer
// cone.
//
// Directional lights (parallel light, no point to aim at), by distance sampling: s is drawn in
// proportion to the camera's transmittance (homogeneous: the mean of the channels' exponentials
// truncated to [0, sMax]; in a grid, the same weighted majorant pieces without the inverse square)
// and
//   L = sigma_s(x) p_HG(w_l . -d) E Tr_light(x -> sun) Tr_cam(0 -> s) / pdf(s)
// with E the irradiance and w_l the light's direction. In a medium that such light cannot enter
// without crossing a surface that blocks shadow rays (not the global medium, bounded only by opaque
// non-Interface surfaces: the sea under a refracting water surface) the estimate is 0 and is not
// drawn.
//
// The environment, the same way after a direction drawn by its importance sampling (pdf_w), with
// E = L_env(w) / pdf_w.
//
// Unbiased for the light that reaches the segment from these lights with no scattering vertex on
// the way: the light the photon tracer's unscattered first beams carry, which it then leaves out
// (RenderSettings::equiangular), so nothing counts twice.
//
// Sources: each point, spot and directional light of non-zero power, all area lights together as
// one, and the environment. A sample that chooses a parallel source (directional, environment) is
// traced for one in kParallelThinning of the samples, weighted up.
//
// A segment gets N = RenderSettings::resolvedEquiangularSamples() distances in all, whatever the
// number of sources (a fractional N: floor(N), and one more on a share N - floor(N) of the
// pixel's passes, samplesInPass; the sum divided by N): stratified uniforms (k + xi) / n,
// k = 0..n-1, each mapped through the sources' choice for the segment (its cdf; the uniform's place inside the chosen source's
// interval is that source's distance uniform), the sample divided by the source's probability.
// Up to kWeighedUpTo sources the choice follows each source's share of this segment's light,
// estimated in closed form (segmentWeight: intensity x the inverse square's integral over the
// segment, clipped to a spot's cone, x the phase function at the foot of the light on it; a
// directional light's irradiance x the integral of the camera's transmittance over the segment x
// the phase function), mixed
// with kDefensive of a uniform choice among the sources with a share; beyond, it follows the
// sources' powers. One source: every sample is its own, as with one light per segment.
// Randomness only from the caller's stream.
#include <memory>
#include <vector>

#include "core/light_sampler.h"
#include "core/rng.h"
#include "cpu/embree_scene.h"

namespace tyndall {

class SegmentPieces;  // a grid segment's majorant pieces, kept for its samples (equiangular.cpp)

/// A grid segment's equiangular samples with the camera's transmittance left out, for the caller
/// to read from the tracker it runs through the segment anyway (its path's throughput): each
/// sample's distance, ascending, and its value (already divided by the samples' mean count).
struct EquiangularLegs {
    static constexpr int kMax = 64;  ///< more samples per segment: each tracks its own leg
    int n = 0;
    float t[kMax];
    Rgb value[kMax];
    /// Sum of value[i] x read[i], the tracker's reads at t[i].
    Rgb sum(const float* read) const {
        Rgb s;
        for (int i = 0; i < n; ++i) s += value[i] * read[i];
        return s;
    }
};

/// Some of the point and spot lights (indices into Scene::lights), for the camera rays near a
/// light's image (docs/algorithm.md "Camera rays near a light's image"): a segment's samples that
/// choose one of them are scaled by `scale` (the uniform film position's share of their light), or
/// with `only` the segment's samples are drawn among them alone (their choice the segment's, over
/// their part of it), scaled the same.
struct EquiangularSubset {
    static constexpr int kMax = 4;
    int n = 0;
    int lights[kMax];
    float scale = 1.0f;
    bool only = false;
    bool contains(int light) const {
        for (int j = 0; j < n; ++j)
            if (lights[j] == light) return true;
        return false;
    }
};

class EquiangularScattering {
public:
    /// Keeps a reference to `rt` (it must outlive this); reads the scene's lights now. `samples`:
    /// distances per segment, all sources together (> 0; a fraction as RenderSettings::
    /// equiangularSamples says).
    EquiangularScattering(const EmbreeScene& rt, double samples);

    /// True for the lights this estimator stands for (point, spot and directional; area lights
    /// too, below): their unscattered beams must not be stored when it is used.
    static bool handles(const Light& light) {
        return light.type == LightType::Point || light.type == LightType::Spot || light.type == LightType::Directional;
    }
    /// True for photons from the lights it stands for: point, spot, directional and area lights,
    /// and the environment.
    static bool handles(const Scene& scene, const EmittedPhoton& photon);
    /// False when the scene has no such light of non-zero power (nothing to estimate).
    bool any() const { return !m_lights.empty(); }

    /// The single-scattered radiance arriving at `o` along -d from the segment o + s d, s in
    /// [0, sMax], inside `medium`, before the camera path's throughput. Draws from `rng`: one
    /// uniform for the fraction's extra sample (a fractional count only: a coin per call; the
    /// renderer decides it per pixel and pass instead, below); per sample, one uniform (three more
    /// for an area light's point, two for the environment's direction), then its shadow ray's
    /// transmittance estimate (grid media only); in a grid, after the samples, one residual
    /// tracker for the camera's transmittance to all of them (to each its own where n >
    /// kMaxSharedLegs); one more uniform per call where a parallel source exists.
    Rgb estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax, Rng& rng) const;
    /// The same with `n` distances (samplesInPass's count), still divided by samples(): the
    /// caller has already decided the fraction's extra sample. In a grid with `legs` non-null and
    /// n <= EquiangularLegs::kMax the samples' camera transmittances are left to the caller: the
    /// samples go to *legs (sorted by distance) and the return is 0; else (legs null, a
    /// homogeneous medium) the whole estimate.
    /// With `subset`, its lights' samples are scaled (or drawn alone) as EquiangularSubset says;
    /// without one, or with one that is not `only`, the draws are the same.
    Rgb estimate(MediumId medium, const Vec3& o, const Vec3& d, float sMax, int n, Rng& rng,
                 EquiangularLegs* legs = nullptr, const EquiangularSubset* subset = nullptr) const;

    /// The distances a pixel's segments get in pass `pass`: floor(N) and, for a fraction f =
    /// N - floor(N), one more in the passes k where floor((k + 1) f + phase) > floor(k f + phase),
    /// `phase` in [0, 1) the pixel's own (pixelPhase). Over any run of K consecutive passes a pixel
    /// gets K f extra samples within one, and with the phase uniform each pass has the extra one
    /// with probability f: unbiased like a random choice per segment, without the random count's
    /// variance (f (1 - f) of the mean's square per pass; docs/algorithm.md).
    int samplesInPass(uint64_t pass, double phase) const;
    /// A pixel's phase for samplesInPass: uniform in [0, 1), from the seed and the pixel alone.
    static double pixelPhase(uint64_t seed, uint64_t pixel);

    /// The sources' choice for the segment, as a cdf over sources() (the last entry 1); false when
    /// none can light it. Public for the tests.
    bool segmentCdf(const Medium& med, const Vec3& o, const Vec3& d, float sMax, double* cdf) const;
    size_t sources() const { return m_lights.size(); }
    double samples() const { return m_samples; }

    /// A parallel source (directional light, environment) traces one in this many of the samples
    /// that choose it, weighted by it: its light has no singularity, so a sample's variance is
    /// low against its shadow ray's cost (docs/performance.md).
    static constexpr int kParallelThinning = 4;
    /// Sources chosen per segment by their estimated share; beyond, by power.
    static constexpr size_t kWeighedUpTo = 8;
    /// The uniform choice's part in the per-segment mixture: bounds a source's weight 1 / p by
    /// kWeighedUpTo / kDefensive where the estimate misjudges its share (shadows, a grid's density
    /// and the transmittances are not in it).
    static constexpr double kDefensive = 0.1;
    /// Most samples per segment whose camera legs share one tracker in a grid (beyond, each its own).
    static constexpr int kMaxSharedLegs = EquiangularLegs::kMax;

private:
    /// The estimated light of source `i` (an index into m_lights) along the segment, up to the
    /// factors all sources share (sigma_s; the camera's transmittance, except a directional
    /// light's, whose share along the segment is nothing else); 0 when it cannot light it.
    double segmentWeight(size_t i, const Medium& med, const Vec3& o, const Vec3& d, float sMax) const;
    /// segmentCdf, with the parallel sources left out in a sealed medium.
    bool segmentCdf(const Medium& med, bool sealed, const Vec3& o, const Vec3& d, float sMax, double* cdf) const;
    /// True when source `i` sends parallel light (a directional light, the environment).
    bool parallel(size_t i) const;
    /// False where a segment gets nothing: no light, vacuum, an empty segment, a medium that does
    /// not scatter, or a sealed medium whose one source is parallel (no sample is drawn there).
    bool lit(MediumId medium, float sMax) const;
    /// One sample of parallel light travelling along `travel` (a directional light's, or the
    /// environment's from one sampled direction) with `incident` its irradiance (the environment:
    /// radiance over the direction's pdf), its distance drawn from `u` in proportion to the
    /// camera's transmittance. `pieces`: the grid segment's (nullptr in a homogeneous medium).
    /// `tCam` non-null: the camera's transmittance left out, the sample's distance written there
    /// (left alone when the sample is 0).
    Rgb fromDirection(const Vec3& travel, const Rgb& incident, const Medium& med, MediumId medium, const Vec3& o,
                      const Vec3& d, float sMax, float u, SegmentPieces* pieces, float* tCam, Rng& rng) const;
    /// One sample of the source `source` (an index into Scene::lights, kAreaLights or
    /// kEnvironment), its distance drawn from the uniform `u`; `pieces` and `tCam` as
    /// fromDirection's.
    Rgb fromSource(int source, const Medium& med, MediumId medium, const Vec3& o, const Vec3& d, float sMax, float u,
                   SegmentPieces* pieces, float* tCam, Rng& rng) const;

    static constexpr int kAreaLights = -1;   ///< all emissive triangles together, as one source
    static constexpr int kEnvironment = -2;  ///< the environment light

    const EmbreeScene& m_rt;
    double m_samples;  ///< per segment: m_whole, and one more on a share m_fraction of them
    int m_whole;
    float m_fraction;
    std::vector<int> m_lights;  ///< indices into Scene::lights, and kAreaLights when they emit
    std::vector<double> m_cdf;  ///< over the luminance of their powers, normalised
    /// luminance: a light's intensity (a directional light's irradiance); the area lights' power /
    /// pi; the environment's integral over the sphere
    std::vector<double> m_intensity;
    /// The area lights as one point for segmentWeight: their bounds' centre, and the distance
    /// below which the inverse square is flattened (the bounds' half diagonal).
    Vec3 m_areaCentre;
    float m_areaReach = 0;
    std::unique_ptr<LightSampler> m_areaLights;  ///< the emitters' choice by power, when they emit
    /// Per medium: true where parallel light cannot arrive unscattered (bounded only by surfaces
    /// that block shadow rays; not the global medium), so its sources are not drawn there.
    std::vector<bool> m_sealed;
    bool m_anyParallel = false;  ///< a directional light or the environment among the sources
};

}  // namespace tyndall
