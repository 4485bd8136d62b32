#include "cpu/direct_light.h"

#include <cmath>

#include "cpu/free_flight.h"

namespace tyndall {

namespace {
// Interface crossings on one shadow ray; this only stops pathological loops.
constexpr int kMaxShadowRayCrossings = 256;
}  // namespace

Rgb shadowTransmittance(const EmbreeScene& rt, const Vec3& origin, const DirectLightSample& light, MediumId medium,
                        Rng& rng, GridTransmittance estimator) {
    const Scene& scene = rt.scene();
    auto transmittance = [&](const Medium& m, const Ray& seg) {
        return estimator == GridTransmittance::Ratio ? ratioTrackingTransmittance(m, seg, seg.tMax, rng)
                                                     : estimateTransmittance(m, seg, seg.tMax, rng);
    };
    const Vec3 d = light.wi;
    const bool finite = std::isfinite(light.distance);
    // Stop just short of an emissive triangle so the shadow ray does not hit the light itself; where
    // float rounding of an oblique hit still finds that triangle first (it did at cos 0.6, 2.4 units
    // away), reaching it is arriving.
    const Vec3 target = light.delta ? light.point : rt.offsetOrigin(light.point, light.normal, -d);
    const EmissiveTriangle* emitter =
        !light.delta && light.source >= int(scene.lights.size()) &&
                light.source < int(scene.lights.size() + scene.emitters.size())
            ? &scene.emitters[size_t(light.source) - scene.lights.size()]
            : nullptr;
    Ray ray{origin, d, 0.0f, finite ? dot(target - origin, d) : kInfinity};
    Rgb tr(1.0f);
    // Where every surface blocks, the light is no emissive triangle (reaching that one is arriving)
    // and the medium draws nothing (vacuum or homogeneous): the loop below would trace one ray and
    // either return 0 at the first surface or the medium's transmittance to the light. An
    // occluded query answers which, without the closest hit's record.
    if (rt.everySurfaceBlocks() && !emitter && (medium == kVacuum || scene.media[medium].homogeneous())) {
        if (!(ray.tMax > 0)) return tr;
        if (rt.occluded(ray)) return Rgb(0.0f);
        Ray seg;
        if (medium != kVacuum && rt.mediumSegment(ray.o, d, ray.tMax, &seg))
            tr *= transmittance(scene.media[medium], seg);
        return tr;
    }
    for (int crossing = 0; crossing <= kMaxShadowRayCrossings; ++crossing) {
        if (!(ray.tMax > 0)) return tr;
        SurfaceHit hit;
        bool surface = rt.intersect(ray, &hit);
        float tEnd = surface ? hit.t : ray.tMax;
        if (medium != kVacuum) {
            Ray seg;
            if (rt.mediumSegment(ray.o, d, tEnd, &seg)) {
                tr *= transmittance(scene.media[medium], seg);
                if (tr.isBlack()) return tr;
            }
        }
        if (!surface) return tr;
        if (emitter && hit.mesh == emitter->mesh && hit.triangle == emitter->triangle) return tr;
        const TriangleMesh& mesh = scene.meshes[hit.mesh];
        if (scene.materials[mesh.material].type != MaterialType::Interface) return Rgb(0.0f);
        medium = dot(d, hit.ng) < 0 ? mesh.interiorMedium : mesh.exteriorMedium;
        ray.o = rt.offsetOrigin(hit.p, hit.ng, d);
        ray.tMax = finite ? dot(target - ray.o, d) : kInfinity;
    }
    return Rgb(0.0f);
}

Rgb DirectLight::diffuse(const SurfaceHit& hit, const HitSide& side, MediumId medium, Rng& rng,
                         bool misWithCosineSampling, const DirectReceiver* receiver) const {
    return reflected(
        hit, side, medium, rng,
        [&](const DirectLightSample& ls) {
            const float cosine = diffuseCosine(side, ls.wi);
            const float mis = ls.delta || !misWithCosineSampling ? 1.0f : powerHeuristic(ls.pdf, cosine * kInvPi);
            return Rgb(cosine > 0 ? cosine * mis : 0.0f);
        },
        receiver);
}

Rgb DirectLight::glossy(const Bsdf& bsdf, BsdfLobes lobes, const SurfaceHit& hit, MediumId medium, Rng& rng) const {
    const DirectLightSample ls = m_lights.sampleDirect(hit.p, rng);
    if (ls.delta || !(ls.pdf > 0) || ls.incident.isBlack()) return Rgb(0.0f);
    const Rgb f = bsdf.f(ls.wi, lobes);
    if (f.isBlack()) return Rgb(0.0f);
    // Through the surface or back from it, in the lobe's (shading) frame and geometrically alike:
    // where they disagree the continuation ends (Bsdf::sample), and so does this.
    const bool through = dot(ls.wi, bsdf.side().nf) < 0;
    if (through != (dot(ls.wi, bsdf.normal()) * dot(bsdf.wo(), bsdf.normal()) < 0)) return Rgb(0.0f);
    const Rgb tr = shadowTransmittance(m_rt.offsetOrigin(hit.p, hit.ng, ls.wi), ls,
                                       through ? bsdf.mediumBeyond() : medium, rng);
    const float mis = powerHeuristic(ls.pdf, bsdf.pdf(ls.wi, lobes));
    return f * ls.incident * tr * (std::abs(dot(ls.wi, bsdf.normal())) * mis / ls.pdf);
}

float DirectLight::continuationWeight(float bsdfPdf, const Vec3& from, int mesh, uint32_t triangle,
                                      const Vec3& p) const {
    const int source = m_lights.emitterSource(mesh, triangle);
    return source < 0 ? 1.0f : powerHeuristic(bsdfPdf, m_lights.directPdf(size_t(source), from, p));
}

float DirectLight::continuationWeight(float bsdfPdf, const Vec3& from, const Vec3& wi) const {
    return powerHeuristic(bsdfPdf, m_lights.environmentPdf(from, wi));
}

}  // namespace tyndall
