#include "cpu/reference_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "core/phase.h"
#include "core/sampling.h"
#include "cpu/direct_light.h"
#include "cpu/free_flight.h"
#include "cpu/surface_scattering.h"

namespace tyndall {

namespace {
// Interface crossings neither scatter nor count as depth; this only stops pathological loops.
constexpr int kMaxPathInterfaceCrossings = 256;
}  // namespace

void ReferenceSettings::validate() const {
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        throw Error("--size: width and height must be in 1..16384 (got " + std::to_string(width) + "x" +
                    std::to_string(height) + ")");
    if (samplesPerPixel == 0) throw Error("--spp must be positive");
    if (maxDepth <= 0) throw Error("--max-depth must be positive");
    if (maxPathLength < 0) throw Error("--max-path-length must be >= 0 (0 = uncapped)");
    if (rouletteDepth <= 0) throw Error("reference roulette depth must be positive");
}

nlohmann::json ReferenceSettings::toJson() const {
    return {{"width", width},
            {"height", height},
            {"spp", samplesPerPixel},
            {"seed", seed},
            {"max_depth", maxDepth},
            {"max_path_length", maxPathLength},
            {"roulette_depth", rouletteDepth},
            {"nee", nextEventEstimation},
            {"equiangular", equiangular},
            {"transparent", transparentFilm}};
}

ReferenceTracer::ReferenceTracer(const EmbreeScene& rt, const ReferenceSettings& settings)
    : m_rt(rt),
      m_scene(rt.scene()),
      m_settings(settings),
      m_maxVertices(settings.maxPathLength > 0 ? std::min(settings.maxDepth, settings.maxPathLength - 1)
                                               : settings.maxDepth),
      m_lights(rt.scene()),
      m_direct(rt, m_lights, GridTransmittance::Ratio),
      m_cameraMedium(rt.mediumAt(rt.scene().camera.position)) {
    m_settings.validate();
}

ReferenceImage ReferenceTracer::render(const std::function<void(int)>& onRow) const {
    const int w = m_settings.width, h = m_settings.height;
    const uint32_t spp = m_settings.samplesPerPixel;
    ReferenceImage out{Image(w, h), Image(w, h), m_settings.transparentFilm ? Image(w, h) : Image()};
    std::mutex progressMutex;
    int rowsDone = 0;
    tbb::parallel_for(tbb::blocked_range<int>(0, h, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            for (int x = 0; x < w; ++x) {
                double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, clearSum = 0;
                for (uint32_t s = 0; s < spp; ++s) {
                    float clear = 0;
                    Rgb L = sample(x, y, s, m_settings.transparentFilm ? &clear : nullptr);
                    clearSum += clear;
                    for (int c = 0; c < 3; ++c) {
                        sum[c] += L[c];
                        sum2[c] += double(L[c]) * L[c];
                    }
                }
                for (int c = 0; c < 3; ++c) {
                    double mean = sum[c] / spp;
                    double var = spp > 1 ? std::max(0.0, (sum2[c] - spp * mean * mean) / (spp - 1)) : 0.0;
                    out.mean.at(x, y)[c] = float(mean);
                    out.varianceOfMean.at(x, y)[c] = float(var / spp);
                }
                if (m_settings.transparentFilm) out.alpha.at(x, y) = Rgb(float(1.0 - clearSum / spp));
            }
            if (onRow) {
                std::lock_guard<std::mutex> lock(progressMutex);
                onRow(++rowsDone);
            }
        }
    });
    return out;
}

Rgb ReferenceTracer::sample(int x, int y, uint32_t s, float* clear) const {
    const int w = m_settings.width, h = m_settings.height;
    Rng rng = Rng::forKey(m_settings.seed, s, uint64_t(y) * w + x, StreamPurpose::ReferencePath);
    // Same jitter convention as CameraTracer: film offset inside the pixel, then the lens sample.
    float jx = rng.uniform(), jy = rng.uniform();
    Vec2 lens{rng.uniform(), rng.uniform()};
    Ray ray = m_scene.camera.generateRay(float(x) + jx, float(y) + jy, w, h, lens);
    return radiance(ray, m_cameraMedium, rng, clear);
}

Rgb ReferenceTracer::radiance(Ray ray, MediumId medium, Rng& rng, float* clear) const {
    const bool nee = m_settings.nextEventEstimation;
    const bool equiangular = nee && m_settings.equiangular;
    Rgb L, beta(1.0f);
    float etaScale = 1.0f;      // undoes the 1/eta^2 radiance scaling for the roulette decision
    int vertices = 0;           // scattering vertices so far
    bool afterSpecular = true;  // no NEE-capable vertex since the camera or the last mirror/glass event
    float lastPdf = 0;          // solid-angle pdf of the direction sampled at the last diffuse/medium vertex
    Vec3 lastVertex;
    int crossings = 0;
    float pathLength = 0;  // texture footprint = pixel spread x distance travelled
    const float spread = pixelSpread(m_scene.camera.yFov, m_settings.height);
    ray.tMin = 0.0f;
    ray.tMax = kInfinity;

    // After a diffuse or medium vertex sampled its continuation: roulette, then go on.
    auto survives = [&]() {
        if (vertices < m_settings.rouletteDepth) return true;
        float q = std::min(1.0f, beta.maxComponent() * etaScale);
        if (!(rng.uniform() < q)) return false;
        beta *= 1.0f / q;
        return true;
    };

    while (true) {
        SurfaceHit hit;
        bool surface = m_rt.intersect(ray, &hit);
        float tHit = surface ? hit.t : kInfinity;
        if (surface) pathLength += hit.t;

        if (medium != kVacuum) {
            const Medium& med = m_scene.media[medium];
            Ray seg;
            if (m_rt.mediumSegment(ray.o, ray.d, tHit, &seg)) {
                if (equiangular && vertices < m_maxVertices) L += beta * pointLightInScattering(seg, medium, rng);
                // The medium's own emission along the whole segment (its own estimate, before the
                // free flight decides where the path goes on).
                if (med.emissive()) L += beta * estimateEmission(med, seg, seg.tMax, rng);
                FreeFlight ff = sampleFreeFlight(med, seg, seg.tMax, rng);
                if (ff.scattered) {
                    if (vertices >= m_maxVertices) break;
                    ++vertices;
                    beta *= ff.weight;
                    Vec3 x = seg.at(ff.t);
                    if (nee) {
                        DirectLightSample ls = m_lights.sampleDirect(x, rng);
                        bool handled = equiangular && isPointLike(ls.source);  // by the segment estimate
                        if (!handled && ls.pdf > 0 && !ls.incident.isBlack()) {
                            float phase = hgPhase(dot(ray.d, ls.wi), med.g);
                            Rgb tr = m_direct.shadowTransmittance(x, ls, medium, rng);
                            float mis = ls.delta ? 1.0f : powerHeuristic(ls.pdf, phase);
                            L += beta * ls.incident * tr * (phase * mis / ls.pdf);
                        }
                    }
                    Vec3 d = sampleHg(ray.d, med.g, rng.uniform(), rng.uniform());
                    lastPdf = hgPhase(dot(ray.d, d), med.g);  // the phase weight itself is 1
                    lastVertex = x;
                    afterSpecular = false;
                    if (beta.isBlack() || !survives()) break;
                    ray = Ray{x, d};
                    continue;
                }
                beta *= ff.weight;
                if (beta.isBlack()) break;
            }
        }
        if (!surface) {
            // The environment: hidden from paths straight from the camera when not visible; MIS
            // against next-event estimation where the last vertex could have sampled it.
            const EnvironmentLight* env = m_scene.environment ? &*m_scene.environment : nullptr;
            if (vertices == 0 && clear) *clear = beta.average();
            if (env && (vertices > 0 || (env->visible() && !m_settings.transparentFilm))) {
                float mis = 1.0f;
                if (nee && !afterSpecular) mis = powerHeuristic(lastPdf, m_lights.environmentPdf(lastVertex, ray.d));
                L += beta * env->eval(ray.d) * mis;
            }
            break;
        }

        const TriangleMesh& mesh = m_scene.meshes[hit.mesh];
        const Material& mat = m_scene.materials[mesh.material];
        applyNormalMap(m_scene, &hit, spread * pathLength);
        HitSide side = hitSide(hit, ray.d);
        const SurfacePoint sp = surfaceAt(m_scene, hit, spread * pathLength);
        if (mat.isEmissive() && side.entering) {
            float mis = 1.0f;
            if (nee && !afterSpecular) {
                int source = m_lights.emitterSource(hit.mesh, hit.triangle);
                if (source >= 0) mis = powerHeuristic(lastPdf, m_lights.directPdf(size_t(source), lastVertex, hit.p));
            }
            L += beta * sp.emission * mis;
        }

        const Bsdf bsdf = Bsdf::at(m_scene, hit, sp, ray.d, medium, TransportMode::Radiance, rng);
        if (bsdf.isPassThrough()) {
            if (++crossings > kMaxPathInterfaceCrossings) break;
            medium = bsdf.mediumBeyond();
            ray = Ray{m_rt.offsetOrigin(hit.p, hit.ng, ray.d), ray.d};
            continue;
        }
        if (vertices >= m_maxVertices) break;
        ++vertices;

        const BsdfLobes lobes = bsdf.lobes();
        const Vec3 wo = -ray.d;
        if (nee && !(lobes & (kLobeGlossy | kLobeSpecular))) {
            // The diffuse base (with a shading normal: surface_hit.h, shadingCosineRatio).
            L += beta * sp.baseColor * kInvPi * m_direct.diffuse(hit, side, medium, rng, true);
        } else if (nee && (lobes & kLobeDiffuse)) {
            // The coated diffuse: the full f (both lobes), MIS against the mixture pdf; the smooth
            // coat's mirror direction is a delta (no MIS, like glass).
            L += beta * m_direct.reflected(hit, side, medium, rng, [&](const DirectLightSample& ls) {
                const float cosine = dot(ls.wi, bsdf.normal());
                if (!(cosine > 0) || !(dot(ls.wi, side.nf) > 0)) return Rgb(0.0f);
                const float mis = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdf.pdf(ls.wi));
                return bsdf.f(ls.wi) * (cosine * mis);
            });
        } else if (nee && (lobes & kLobeGlossy)) {
            DirectLightSample ls = m_lights.sampleDirect(hit.p, rng);
            Rgb f = ls.pdf > 0 && !ls.incident.isBlack() ? bsdf.f(ls.wi) : Rgb();
            if (!f.isBlack()) {
                bool crosses = dot(ls.wi, hit.ng) * dot(wo, hit.ng) < 0;
                MediumId shadowMedium = crosses ? bsdf.mediumBeyond() : medium;
                Rgb tr = m_direct.shadowTransmittance(m_rt.offsetOrigin(hit.p, hit.ng, ls.wi), ls, shadowMedium, rng);
                float mis = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdf.pdf(ls.wi));
                float cosine = std::abs(dot(ls.wi, bsdf.normal()));
                L += beta * f * ls.incident * tr * (cosine * mis / ls.pdf);
            }
        }

        BsdfSample s;
        if (!bsdf.sample(rng, &beta, &s)) break;
        // Roulette on the throughput without the 1/eta^2 radiance scaling.
        if (s.lobe & kLobeTransmission) etaScale /= s.eta * s.eta;
        lastPdf = s.pdf;
        lastVertex = hit.p;
        afterSpecular = (s.lobe & kLobeSpecular) != 0;
        medium = s.medium;
        if (beta.isBlack() || !survives()) break;
        // Diffuse and coated vertices leave from the arriving side, glossy and specular ones
        // from either.
        ray = Ray{m_rt.offsetOrigin(hit.p, (lobes & kLobeDiffuse) ? side.nf : hit.ng, s.wi), s.wi};
    }
    return L;
}

bool ReferenceTracer::isPointLike(int source) const {
    return source >= 0 && source < int(m_scene.lights.size()) && m_scene.lights[source].type != LightType::Directional;
}

Rgb ReferenceTracer::pointLightInScattering(const Ray& seg, MediumId medium, Rng& rng) const {
    // The light chosen by power (sourceProbability); the free-flight NEE that skips these lights
    // divides by its own choice probability, so the two parts still add up.
    size_t source = m_lights.chooseSource(rng.uniform());
    float uDistance = rng.uniform();
    if (!isPointLike(int(source))) return Rgb(0.0f);
    const Light& light = m_scene.lights[source];
    const Medium& med = m_scene.media[medium];
    // Its own equiangular sampler, in double precision and over the whole segment (no cone clip),
    // written apart from core/equiangular.h so a pdf bug there cannot move both sides of a test.
    const double tc = dot(light.position - seg.o, seg.d);  // the line's closest approach to the light
    const double h = length(seg.o + seg.d * float(tc) - light.position);
    if (!(h > 1e-7)) return Rgb(0.0f);  // the line runs through the light: a set of measure zero
    const double thetaA = std::atan2(-tc, h), thetaB = std::atan2(double(seg.tMax) - tc, h);
    if (!(thetaB > thetaA)) return Rgb(0.0f);
    const double tSample = std::clamp(tc + h * std::tan(thetaA + uDistance * (thetaB - thetaA)), 0.0, double(seg.tMax));
    const float t = float(tSample);
    const float pdfT = float(h / ((thetaB - thetaA) * (h * h + (tSample - tc) * (tSample - tc))));
    Vec3 x = seg.at(t);

    DirectLightSample ls;
    ls.source = int(source);
    ls.delta = true;
    ls.point = light.position;
    Vec3 toLight = light.position - x;
    float d2 = lengthSquared(toLight);
    ls.distance = std::sqrt(d2);
    ls.wi = toLight / ls.distance;
    float falloff = light.type == LightType::Spot ? light.spotFalloff(dot(-ls.wi, light.direction)) : 1.0f;
    if (!(falloff > 0) || !(d2 > 0)) return Rgb(0.0f);
    ls.incident = light.intensity * (falloff / d2);
    ls.pdf = m_lights.sourceProbability(source);

    Rgb trCamera = ratioTrackingTransmittance(med, seg, t, rng);
    if (trCamera.isBlack()) return Rgb(0.0f);
    Rgb trLight = m_direct.shadowTransmittance(x, ls, medium, rng);
    float phase = hgPhase(dot(seg.d, ls.wi), med.g);
    return trCamera * med.sigmaSAt(x) * ls.incident * trLight * (phase / (pdfT * ls.pdf));
}

Scene withoutSpecularSurfaces(const Scene& scene) {
    Scene s = scene;
    for (Material& m : s.materials)
        if (m.type == MaterialType::Mirror || m.type == MaterialType::Dielectric) m.type = MaterialType::Interface;
    s.validate();
    return s;
}

}  // namespace tyndall
