#pragma once
// Light sampling. Photon emission: picks a light (point, spot, directional, one emissive
// triangle or the environment) with probability proportional to its power and samples an emitted
// ray (the photon tracer). Next-event estimation (the reference path tracer, PPB's shadow rays): a
// source chosen by what it can send to the shading point (directChoiceProbability), then a point
// (or, for the environment, a direction) on it. Sources are indexed lights first (Scene::lights),
// then Scene::emitters, then the environment (Scene::environment, when it has any radiance).
//
// The environment's photons leave a disc of the scene's bounding-sphere radius R, centred on the
// sphere's centre and pushed out past the sphere along the sampled direction wi, facing -wi (the
// direction they travel): a uniform point on the disc and wi ~ EnvironmentLight::sample, so a
// photon carries L(wi) pi R^2 / pdf(wi) and the total power is pi R^2 x the integral of L: every
// point of the sphere receives each direction's parallel light, unbiased.
#include <unordered_map>
#include <vector>

#include "core/math.h"
#include "core/rng.h"
#include "core/scene.h"

namespace tyndall {

/// One emitted photon path start. `power` is (emitted power sample)/(pdf of choosing it): the
/// expected value of `power` over many samples is the scene's total emitted power (W).
struct EmittedPhoton {
    Ray ray;
    Rgb power;
    /// Index into Scene::lights for point/spot/directional; -1 for an area light or the environment.
    int light = -1;
    /// Area lights: the emitting mesh (the path starts in its exterior medium); else -1.
    int emitterMesh = -1;
    /// From the environment: starts outside the scene's bounds, in the global medium.
    bool environment = false;
};

/// A light point chosen for next-event estimation from a shading point x. The estimate of the
/// light arriving at x along `wi` is incident * (visibility, transmittance) / pdf.
struct DirectLightSample {
    Vec3 wi;             ///< unit direction from x toward the light
    float distance = 0;  ///< from x to `point`; +infinity for directional lights and the environment
    Vec3 point;          ///< light position, or the point on the emissive triangle
    Vec3 normal;         ///< area lights: the triangle's unit front (emitting) normal
    /// Area lights and the environment: radiance (W m^-2 sr^-1), zero when x is behind the
    /// triangle. Point/spot: I * falloff / distance^2; directional: the irradiance E (both W m^-2).
    Rgb incident;
    /// Area lights and the environment: solid-angle pdf at x of this direction (choice probability
    /// included); delta lights (point, spot, directional): the choice probability alone.
    float pdf = 0;
    bool delta = false;  ///< point, spot or directional: no other strategy can reach it
    int source = -1;     ///< the chosen source index
};

/// The diffuse point a shadow ray leaves from, for sampleDirect's choice of source (PPB's diffuse
/// ends): the side it is seen from (HitSide's nf and nsf) and the colour it reflects. The
/// contribution of a point, spot or directional light there is tint x incident x cosine(wi).
struct DirectReceiver {
    Vec3 nf;   ///< geometric normal on the seen side
    Vec3 nsf;  ///< shading normal on the same side
    Rgb tint;  ///< the reflectance's colour (the base colour), weighting the channels
    /// The uniform in [0, 1) that chooses the source, in place of the stream's first draw (which is
    /// drawn all the same); negative: the stream's (core/pixel_jitter.h, lightChoiceUniform).
    float choice = -1.0f;
    /// The diffuse base's cosine for light along `wi`: max(0, wi . nsf) above the geometric surface,
    /// else 0 (cpu/direct_light.h's diffuseCosine, the factor the estimate applies).
    float cosine(const Vec3& wi) const { return dot(wi, nf) > 0 ? std::max(0.0f, dot(wi, nsf)) : 0.0f; }
};

class LightSampler {
public:
    /// Throws Error when nothing in the scene emits. A scene lit by emissive media alone (no light,
    /// or only lights of zero power) has no sources here: sourceCount() is 0, sample() must not be
    /// called and sampleDirect() returns pdf 0 (the media are cpu/medium_emitters.h's).
    explicit LightSampler(const Scene& scene);

    EmittedPhoton sample(Rng& rng) const;
    /// Total emitted power summed over all lights (W, luminance-weighted selection uses it).
    Rgb totalPower() const { return m_totalPower; }
    /// Emitted power of source `i` (lights first, then Scene::emitters).
    Rgb sourcePower(size_t i) const { return m_power[i]; }
    size_t sourceCount() const { return m_power.size(); }

    /// The source index of the environment, or -1 when the scene has none (or a black one).
    int environmentSource() const { return m_environmentSource; }

    /// Power of one light as emitted into the scene (spot cone integrated, directional over the
    /// disk that covers the scene's bounding sphere).
    static Rgb lightPower(const Light& light, const Bounds3& sceneBounds);

    /// Power-proportional choice of a source from u in [0, 1); never a zero-power source.
    size_t chooseSource(float u) const;
    /// Probability that chooseSource picks source `i` (luminance of its power over the total).
    float sourceProbability(size_t i) const { return float(m_cdf[i] - (i > 0 ? m_cdf[i - 1] : 0.0)); }
    /// The source index of emissive triangle `triangle` of mesh `mesh`, or -1 when it is not one.
    int emitterSource(int mesh, uint32_t triangle) const;

    /// Next-event estimation from shading point `x`: a source chosen with directChoiceProbability,
    /// then a point on it (uniform over an emissive triangle's area). Draws three uniforms from `rng`.
    DirectLightSample sampleDirect(const Vec3& x, Rng& rng, const DirectReceiver* receiver = nullptr) const;
    /// Probability that sampleDirect(x) picks source `i`. With two or more sources of which at
    /// most kMaxSpatialChoiceLights are point, spot or directional lights, the choice follows what
    /// each could send to x unoccluded, the receiver's cosine left out: I falloff / d^2 for point
    /// and spot lights (0 outside a spot's cone), E for directional ones, and, for all emissive
    /// triangles together, their power / (pi max(d^2, area / pi)) with d the distance from x to
    /// their bounding box (then a triangle by power). A spot that cannot reach x costs no shadow
    /// rays there, and a dim light near x is not starved by a bright far one (power alone spent
    /// 3/4 of the caustic box's shadow rays on its spot outside the spot's cone). Otherwise
    /// (one source, or more lights than that) sourceProbability(i), the power-proportional choice.
    /// The environment's weight is the mean over orientations of the irradiance it sends to a
    /// plane, (1/4) x the integral of its luminance over the sphere (pi L for a constant L).
    /// With a `receiver` (a diffuse point, PPB's shadow rays) the weights are what each source sends
    /// into the receiver's colour: a point, spot or directional light's by the L2 norm over the
    /// channels of tint x intensity, times the receiver's cosine toward it (0 below the surface,
    /// where its light adds nothing), the emitters' and the environment's by the tint's L2 norm (their
    /// luminance-based weights, no cosine). The sum of the channels' variances of a one-sample
    /// estimate is smallest with each source's probability proportional to the L2 norm of its RGB
    /// contribution; this is that, but for shadows and the media's transmittance. Without a receiver
    /// (the reference tracer, whose MIS weights use directPdf) the weights are the ones above.
    float directChoiceProbability(size_t i, const Vec3& x, const DirectReceiver* receiver = nullptr) const;
    /// Beyond this many point, spot and directional lights the choice is by power (the per-point
    /// weights cost one evaluation per light).
    static constexpr size_t kMaxSpatialChoiceLights = 32;
    /// The pdf sampleDirect(x) has of reaching point `y` on area-light `source` (solid angle at
    /// x, choice included); for MIS when a scattered path hits that emitter. 0 for delta lights
    /// and when x is behind the triangle.
    float directPdf(size_t source, const Vec3& x, const Vec3& y) const;
    /// The pdf sampleDirect(x) has of choosing the environment in direction `wi` (solid angle,
    /// choice included); 0 without an environment. For MIS when a scattered path escapes.
    float environmentPdf(const Vec3& x, const Vec3& wi) const;

    /// A point on the area lights (the emissive triangles), for estimators that aim at the light
    /// first (the equiangular estimator's, cpu/equiangular.h): a triangle chosen by power among
    /// them, then a uniform point on it. pdfArea is the density over the union of their areas
    /// (0, and nothing else set, when no emitter has power). Draws three uniforms from `rng`.
    struct EmitterPoint {
        Vec3 point;
        Vec3 normal;   ///< the triangle's unit front (emitting) normal
        Rgb radiance;  ///< Le there
        float pdfArea = 0;
        int source = -1;  ///< its source index (lights first, then Scene::emitters)
    };
    EmitterPoint sampleEmitterPoint(Rng& rng) const;
    /// The emitters' summed power, luminance (0: none emits).
    double emitterPower() const { return m_emitterPower; }

private:
    /// Le at barycentrics b of an emitter: the material's emission times its emissiveTexture there
    /// (the source pmf follows the untextured power; the texture weights the sample, unbiased).
    Rgb emittedRadiance(const EmissiveTriangle& e, Vec2 b) const;
    /// The point at barycentrics b of an emitter and the triangle's unit front normal: where
    /// direct light, photon emission and sampleEmitterPoint put their point on an area light.
    void emitterPointAt(const EmissiveTriangle& e, Vec2 b, Vec3* point, Vec3* normal) const;

    /// The spatial choice's weights at x: w[k] for light k, w[lights] for all emitters together,
    /// w[lights + 1] for the environment; returns their sum.
    double directWeights(const Vec3& x, double* w, const DirectReceiver* receiver = nullptr) const;
    /// Emitter `e` (index into Scene::emitters) chosen by power among the emitters from u in [0, 1).
    size_t chooseEmitter(double u) const;
    double emitterShare(size_t e) const { return m_emitterCdf[e] - (e > 0 ? m_emitterCdf[e - 1] : 0.0); }

    const Scene& m_scene;
    std::vector<Rgb> m_power;
    std::vector<double> m_cdf;  // over luminance of m_power
    bool m_spatialChoice = false;
    std::vector<double> m_emitterCdf;  // over luminance of the emitters' power, normalised
    double m_emitterPower = 0;         // luminance, summed
    double m_emitterArea = 0;
    int m_environmentSource = -1;
    double m_environmentWeight = 0;  // the spatial choice's weight of the environment
    Bounds3 m_emitterBounds;
    Rgb m_totalPower;
    Vec3 m_sceneCenter;
    float m_sceneRadius = 1.0f;
    std::unordered_map<uint64_t, int> m_emitterSource;  // (mesh << 32 | triangle) -> source
};

}  // namespace tyndall
