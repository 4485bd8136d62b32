#pragma once
// Next-event estimation (direct light by shadow rays), shared by the reference path tracer and
// PPB's camera paths (the diffuse end of a camera path with `--direct-light on`,
// docs/algorithm.md "Direct light by shadow rays"):
//   - a light sample: LightSampler::sampleDirect's source (chosen by what it can send to the point),
//     then a point on it
//     (point, spot, directional, or uniform over an emissive triangle);
//   - a shadow ray toward it that passes through Interface surfaces (switching medium) and through
//     alpha-masked or blended geometry as EmbreeScene's occlusion filter decides, and is blocked by
//     every other surface;
//   - the transmittance of every medium on the way: analytic in homogeneous media, residual ratio
//     tracking (unbiased) in density-grid media (estimateTransmittance; the reference path tracer
//     keeps plain ratio tracking, ratioTrackingTransmittance, as an independent check).
// Randomness comes only from the caller's keyed stream.
#include <cmath>

#include "core/light_sampler.h"
#include "core/rng.h"
#include "cpu/embree_scene.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

/// Multiple importance sampling, power heuristic (beta = 2) for strategy A against B: 0 where A
/// cannot draw the sample, 1 where only A can. From the ratio B / A, so pdfs beyond 1.8e19 (whose
/// squares overflow a float: a nearly smooth GGX lobe's peak) give the limit, not inf / inf.
inline float powerHeuristic(float pdfA, float pdfB) {
    if (!(pdfA > 0)) return 0.0f;
    if (!(pdfB > 0)) return 1.0f;
    const double r = double(pdfB) / double(pdfA);
    if (std::isnan(r)) return 0.5f;  // both infinite
    return float(1.0 / (1.0 + r * r));
}

/// The diffuse base's cosine for light arriving along `wi` (docs/algorithm.md "Normal maps"):
/// max(0, wi . nsf) for wi above the geometric surface (wi . nf > 0), else 0. It equals
/// shadingCosineRatio(side, wi) x (wi . nf), the weight the surface-photon gather gives a photon.
inline float diffuseCosine(const HitSide& side, const Vec3& wi) {
    return dot(wi, side.nf) > 0 ? std::max(0.0f, dot(wi, side.nsf)) : 0.0f;
}

/// Which estimate of a grid medium's transmittance shadow rays use (cpu/free_flight.h).
enum class GridTransmittance {
    Residual,  ///< residual ratio tracking against a density comb (estimateTransmittance)
    Ratio,     ///< plain ratio tracking (ratioTrackingTransmittance): the reference path tracer's
};

/// Light arriving at `origin` along `light`'s direction, starting in `medium`: the product of the
/// transmittances of the medium segments on the way (analytic in homogeneous media, `estimator`
/// in grid media: draws from `rng` only there), or 0 when a surface other than an Interface blocks
/// it. Stops just short of an emissive triangle. DirectLight's shadow rays and the equiangular
/// estimator's (cpu/equiangular.h). In a scene where every surface blocks (EmbreeScene::
/// everySurfaceBlocks), toward a light that is no emissive triangle, through vacuum or a
/// homogeneous medium: one occluded query instead of the closest hit, with the same result.
Rgb shadowTransmittance(const EmbreeScene& rt, const Vec3& origin, const DirectLightSample& light, MediumId medium,
                        Rng& rng, GridTransmittance estimator = GridTransmittance::Residual);

class DirectLight {
public:
    /// Keeps references to both: they must outlive this.
    DirectLight(const EmbreeScene& rt, const LightSampler& lights,
                GridTransmittance estimator = GridTransmittance::Residual)
        : m_rt(rt), m_lights(lights), m_estimator(estimator) {}

    /// tyndall::shadowTransmittance in this scene.
    Rgb shadowTransmittance(const Vec3& origin, const DirectLightSample& light, MediumId medium, Rng& rng) const {
        return tyndall::shadowTransmittance(m_rt, origin, light, medium, rng, m_estimator);
    }

    /// One-sample estimate of the cosine-weighted light arriving at the diffuse point `hit` seen
    /// from `side` (the path's side; `medium` the medium there):
    ///   E = incident x Tr x diffuseCosine(side, wi) / pdf   (x the MIS weight, see below)
    /// so the radiance the diffuse base sends back is baseColor / pi x E. Draws sampleDirect's three
    /// uniforms from `rng`, then the shadow ray's (only when the sample can contribute).
    /// `misWithCosineSampling`: area-light samples are weighted by the power heuristic against
    /// cosine sampling of the direction (the reference tracer, which also reaches area lights by
    /// hitting them); false: weight 1 (PPB's camera path ends at the diffuse vertex).
    Rgb diffuse(const SurfaceHit& hit, const HitSide& side, MediumId medium, Rng& rng, bool misWithCosineSampling,
                const DirectReceiver* receiver = nullptr) const;

    /// One-sample estimate of incident x Tr x weight(sample) / pdf at `hit`, `weight` the caller's
    /// BSDF x cosine (x a MIS weight where the path also reaches the light by sampling) for the
    /// light sample (DirectLightSample: wi, pdf, delta). Draws sampleDirect's three uniforms from
    /// `rng`, then the shadow ray's only when the weight is not black. `diffuse` is this with the
    /// diffuse base's cosine.
    /// `receiver`: the source is chosen by what it sends into the receiver's colour and cosine
    /// (LightSampler::directChoiceProbability); nullptr: by what it sends to the point.
    template <class Weight>
    Rgb reflected(const SurfaceHit& hit, const HitSide& side, MediumId medium, Rng& rng, Weight&& weight,
                  const DirectReceiver* receiver = nullptr) const {
        const DirectLightSample ls = m_lights.sampleDirect(hit.p, rng, receiver);
        if (!(ls.pdf > 0) || ls.incident.isBlack()) return Rgb(0.0f);
        const Rgb w = weight(ls);
        if (w.isBlack()) return Rgb(0.0f);
        return ls.incident * w * shadowTransmittance(m_rt.offsetOrigin(hit.p, side.nf, ls.wi), ls, medium, rng) *
               (1.0f / ls.pdf);
    }

    /// One-sample estimate of the light from area lights and the environment that a rough vertex
    /// sends back along its `lobes` (a camera path's continuation lobes: the glossy ones, a coat's
    /// specular part): incident x Tr x f_lobes(wi) |wi . n| / pdf, weighted by the power heuristic
    /// against bsdf.pdf(wi, lobes), the continuation's density, whose hits continuationWeight
    /// weights with the rest. A point, spot or directional sample counts 0: at a glossy vertex their
    /// light is the delta-path photons' (docs/algorithm.md "Glossy vertices"). A sample through the
    /// surface (rough transmission) starts its shadow ray in bsdf.mediumBeyond(). Draws
    /// sampleDirect's three uniforms from `rng`, then the shadow ray's where the weight is not 0.
    Rgb glossy(const Bsdf& bsdf, BsdfLobes lobes, const SurfaceHit& hit, MediumId medium, Rng& rng) const;
    /// The power-heuristic weight of a continuation drawn with density `bsdfPdf` at `from` (after
    /// glossy() there) that reaches the emissive triangle (mesh, triangle) at `p`, against the
    /// shadow ray's density of that point: glossy()'s weight and this sum to 1 for every direction.
    float continuationWeight(float bsdfPdf, const Vec3& from, int mesh, uint32_t triangle, const Vec3& p) const;
    /// The same for a continuation that leaves the scene along `wi` (the environment).
    float continuationWeight(float bsdfPdf, const Vec3& from, const Vec3& wi) const;

    const LightSampler& lights() const { return m_lights; }

private:
    const EmbreeScene& m_rt;
    const LightSampler& m_lights;
    GridTransmittance m_estimator;
};

}  // namespace tyndall
