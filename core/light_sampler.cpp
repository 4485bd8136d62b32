#include "core/light_sampler.h"

#include <algorithm>

#include "core/error.h"
#include "core/material_eval.h"
#include "core/sampling.h"

namespace tyndall {

namespace {
float boundingRadius(const Bounds3& b) { return b.empty() ? 1.0f : std::max(0.5f * length(b.diagonal()), 1e-3f); }
}  // namespace

Rgb LightSampler::lightPower(const Light& light, const Bounds3& sceneBounds) {
    switch (light.type) {
        case LightType::Point:
            return light.intensity * (4.0f * kPi);
        case LightType::Spot: {
            // Integral of the smoothstep falloff over the cone: full inside the inner cone, half the
            // inner-outer band (the smoothstep integrates to 1/2 in cos(theta)).
            float band = std::max(light.cosInnerAngle - light.cosOuterAngle, 0.0f);
            return light.intensity * (2.0f * kPi * ((1.0f - light.cosInnerAngle) + 0.5f * band));
        }
        case LightType::Directional: {
            float r = boundingRadius(sceneBounds);
            return light.intensity * (kPi * r * r);
        }
    }
    return Rgb(0.0f);
}

LightSampler::LightSampler(const Scene& scene) : m_scene(scene) {
    m_sceneCenter = scene.bounds.empty() ? Vec3(0.0f) : scene.bounds.center();
    m_sceneRadius = boundingRadius(scene.bounds);
    for (const Light& l : scene.lights) m_power.push_back(lightPower(l, scene.bounds));
    for (const EmissiveTriangle& e : scene.emitters) m_power.push_back(e.radiance * (kPi * e.area));
    if (scene.environment && scene.environment->integral().luminance() > 0) {
        m_environmentSource = int(m_power.size());
        m_power.push_back(scene.environment->integral() * (kPi * m_sceneRadius * m_sceneRadius));
        m_environmentWeight = 0.25 * double(scene.environment->integral().luminance());
    }
    double sum = 0.0;
    for (const Rgb& p : m_power) {
        sum += std::max(0.0f, p.luminance());
        m_cdf.push_back(sum);
        m_totalPower += p;
    }
    if (sum <= 0.0) {
        bool emissiveMedium = false;
        for (const Medium& m : scene.media) emissiveMedium |= m.emissive();
        if (!emissiveMedium) throw Error("scene '" + scene.name + "' emits no light (every light has zero power)");
        // Lit by its media alone (cpu/medium_emitters.h): no source here.
        m_power.clear();
        m_cdf.clear();
        return;
    }
    for (double& c : m_cdf) c /= sum;
    for (size_t e = 0; e < scene.emitters.size(); ++e)
        m_emitterSource[(uint64_t(scene.emitters[e].mesh) << 32) | scene.emitters[e].triangle] =
            int(scene.lights.size() + e);
    for (size_t e = 0; e < scene.emitters.size(); ++e) {
        const EmissiveTriangle& t = scene.emitters[e];
        m_emitterPower += std::max(0.0f, m_power[scene.lights.size() + e].luminance());
        m_emitterCdf.push_back(m_emitterPower);
        m_emitterArea += t.area;
        for (int v = 0; v < 3; ++v) m_emitterBounds.extend(scene.meshes[size_t(t.mesh)].vertex(t.triangle, v));
    }
    if (m_emitterPower > 0)
        for (double& c : m_emitterCdf) c /= m_emitterPower;
    const size_t groups = scene.lights.size() + (m_emitterPower > 0 ? 1 : 0) + (m_environmentSource >= 0 ? 1 : 0);
    m_spatialChoice = groups >= 2 && scene.lights.size() <= kMaxSpatialChoiceLights;
}

double LightSampler::directWeights(const Vec3& x, double* w, const DirectReceiver* receiver) const {
    // With a receiver: each light's colour weighted by the receiver's tint (the L2 norm over the
    // channels), its cosine there; the emitters' and the environment's weights (no one direction)
    // by the tint's norm alone, as a white light's would be.
    const double tintNorm = receiver ? double(std::sqrt(lengthSquared(Vec3(receiver->tint.r, receiver->tint.g,
                                                                           receiver->tint.b))))
                                     : 1.0;
    if (receiver && !(tintNorm > 0)) receiver = nullptr;
    double sum = 0;
    for (size_t k = 0; k < m_scene.lights.size(); ++k) {
        const Light& l = m_scene.lights[k];
        double intensity;
        if (receiver) {
            const Rgb c = l.intensity * receiver->tint;
            intensity = std::sqrt(double(c.r) * c.r + double(c.g) * c.g + double(c.b) * c.b);
        } else {
            intensity = std::max(0.0f, l.intensity.luminance());
        }
        if (l.type == LightType::Directional) {
            w[k] = intensity * (receiver ? double(receiver->cosine(-l.direction)) : 1.0);
        } else {
            // The falloff (and direction) exactly as sampleDirect evaluates it, so a light it can
            // light is never given weight 0.
            Vec3 toLight = l.position - x;
            float d2 = lengthSquared(toLight);
            if (!(d2 > 0)) {
                w[k] = 0;
                continue;
            }
            const float d = std::sqrt(d2);
            const Vec3 wi = toLight / d;
            float falloff = l.type == LightType::Spot ? l.spotFalloff(dot(-wi, l.direction)) : 1.0f;
            w[k] = intensity * double(falloff) / double(d2) * (receiver ? double(receiver->cosine(wi)) : 1.0);
        }
        sum += w[k];
    }
    double& group = w[m_scene.lights.size()];
    group = 0;
    if (m_emitterPower > 0) {
        Vec3 lo = m_emitterBounds.lo - x, hi = x - m_emitterBounds.hi;
        Vec3 out(std::max({lo.x, hi.x, 0.0f}), std::max({lo.y, hi.y, 0.0f}), std::max({lo.z, hi.z, 0.0f}));
        double d2 = std::max(double(lengthSquared(out)), m_emitterArea / kPi);
        group = tintNorm * m_emitterPower / (kPi * std::max(d2, 1e-30));
    }
    w[m_scene.lights.size() + 1] = tintNorm * m_environmentWeight;
    return sum + group + w[m_scene.lights.size() + 1];
}

size_t LightSampler::chooseEmitter(double u) const {
    size_t e = size_t(std::lower_bound(m_emitterCdf.begin(), m_emitterCdf.end(), u) - m_emitterCdf.begin());
    e = std::min(e, m_emitterCdf.size() - 1);
    while (e > 0 && m_emitterCdf[e] == m_emitterCdf[e - 1]) --e;  // never a zero-power emitter
    return e;
}

float LightSampler::directChoiceProbability(size_t i, const Vec3& x, const DirectReceiver* receiver) const {
    if (!m_spatialChoice) return sourceProbability(i);
    double w[kMaxSpatialChoiceLights + 2];
    const double sum = directWeights(x, w, receiver);
    if (!(sum > 0)) return 0.0f;
    const size_t lights = m_scene.lights.size();
    if (i < lights) return float(w[i] / sum);
    if (int(i) == m_environmentSource) return float(w[lights + 1] / sum);
    return float(w[lights] / sum * emitterShare(i - lights));
}

size_t LightSampler::chooseSource(float u) const {
    size_t i = size_t(std::lower_bound(m_cdf.begin(), m_cdf.end(), double(u)) - m_cdf.begin());
    i = std::min(i, m_cdf.size() - 1);
    while (i > 0 && m_cdf[i] == m_cdf[i - 1]) --i;  // never pick a zero-power source
    return i;
}

int LightSampler::emitterSource(int mesh, uint32_t triangle) const {
    auto it = m_emitterSource.find((uint64_t(mesh) << 32) | triangle);
    return it == m_emitterSource.end() ? -1 : it->second;
}

DirectLightSample LightSampler::sampleDirect(const Vec3& x, Rng& rng, const DirectReceiver* receiver) const {
    DirectLightSample s;
    const float drawn = rng.uniform();
    const float u = receiver && receiver->choice >= 0.0f ? receiver->choice : drawn;
    float u1 = rng.uniform(), u2 = rng.uniform();
    size_t i = 0;
    float pick = 0;
    if (m_power.empty()) return s;  // no light at all (a scene lit by emissive media alone)
    if (!m_spatialChoice) {
        i = chooseSource(u);
        pick = sourceProbability(i);
    } else {
        double w[kMaxSpatialChoiceLights + 2];
        const double sum = directWeights(x, w, receiver);
        if (!(sum > 0)) return s;  // no source can reach x
        const size_t lights = m_scene.lights.size();
        double target = double(u) * sum, below = 0;
        i = lights;  // the emitters or the environment, unless a light's interval holds the target
        for (size_t k = 0; k < lights; ++k) {
            if (w[k] > 0 && target < below + w[k]) {
                i = k;
                break;
            }
            below += w[k];
        }
        const bool environment =
            i == lights && w[lights + 1] > 0 && (target >= below + w[lights] || !(w[lights] > 0));
        if (i < lights) {
            pick = float(w[i] / sum);
        } else if (environment) {
            i = size_t(m_environmentSource);
            pick = float(w[lights + 1] / sum);
        } else if (w[lights] > 0) {
            size_t e = chooseEmitter(std::clamp((target - below) / w[lights], 0.0, std::nextafter(1.0, 0.0)));
            i = lights + e;
            pick = float(w[lights] / sum * emitterShare(e));
        } else {  // rounding put the target past the last light's interval: take the last lit one
            i = lights;
            while (i > 0 && !(w[i - 1] > 0)) --i;
            if (i == 0) return s;
            i -= 1;
            pick = float(w[i] / sum);
        }
    }
    s.source = int(i);
    if (int(i) == m_environmentSource) {
        const EnvironmentSample es = m_scene.environment->sample(u1, u2);
        if (!(es.pdf > 0)) return DirectLightSample{};
        s.wi = es.wi;
        s.distance = kInfinity;
        s.point = x + es.wi;
        s.normal = -es.wi;
        s.incident = es.radiance;
        s.pdf = pick * es.pdf;
        return s;
    }
    if (i < m_scene.lights.size()) {
        const Light& l = m_scene.lights[i];
        s.delta = true;
        s.pdf = pick;
        if (l.type == LightType::Directional) {
            s.wi = -l.direction;
            s.distance = kInfinity;
            s.incident = l.intensity;
            return s;
        }
        Vec3 toLight = l.position - x;
        float d2 = lengthSquared(toLight);
        if (!(d2 > 0)) return DirectLightSample{};
        s.distance = std::sqrt(d2);
        s.wi = toLight / s.distance;
        s.point = l.position;
        float falloff = l.type == LightType::Spot ? l.spotFalloff(dot(-s.wi, l.direction)) : 1.0f;
        s.incident = l.intensity * (falloff / d2);
        return s;
    }
    const EmissiveTriangle& e = m_scene.emitters[i - m_scene.lights.size()];
    Vec2 b = sampleUniformTriangle(u1, u2);
    emitterPointAt(e, b, &s.point, &s.normal);
    Vec3 toLight = s.point - x;
    float d2 = lengthSquared(toLight);
    if (!(d2 > 0)) return DirectLightSample{};
    s.distance = std::sqrt(d2);
    s.wi = toLight / s.distance;
    float cosLight = -dot(s.wi, s.normal);
    if (!(cosLight > 0)) return DirectLightSample{};  // x sees the back of the triangle
    s.incident = emittedRadiance(e, b);
    s.pdf = pick * d2 / (cosLight * e.area);
    return s;
}

float LightSampler::directPdf(size_t source, const Vec3& x, const Vec3& y) const {
    if (source < m_scene.lights.size() || int(source) == m_environmentSource) return 0.0f;
    const EmissiveTriangle& e = m_scene.emitters[source - m_scene.lights.size()];
    Vec3 n = normalize(m_scene.meshes[e.mesh].geometricNormal(e.triangle));
    Vec3 toLight = y - x;
    float d2 = lengthSquared(toLight);
    float cosLight = -dot(toLight, n) / std::sqrt(d2);
    if (!(cosLight > 0)) return 0.0f;
    return directChoiceProbability(source, x) * d2 / (cosLight * e.area);
}

float LightSampler::environmentPdf(const Vec3& x, const Vec3& wi) const {
    if (m_environmentSource < 0) return 0.0f;
    return directChoiceProbability(size_t(m_environmentSource), x) * m_scene.environment->pdf(wi);
}

EmittedPhoton LightSampler::sample(Rng& rng) const {
    size_t i = chooseSource(rng.uniform());
    double pick = m_cdf[i] - (i > 0 ? m_cdf[i - 1] : 0.0);
    float u1 = rng.uniform(), u2 = rng.uniform();

    EmittedPhoton ph;
    Rgb power;  // power sample / pdf of the direction (and point) given the source
    if (i < m_scene.lights.size()) {
        const Light& l = m_scene.lights[i];
        ph.light = int(i);
        switch (l.type) {
            case LightType::Point:
                ph.ray.o = l.position;
                ph.ray.d = sampleUniformSphere(u1, u2);
                power = l.intensity / uniformSpherePdf();
                break;
            case LightType::Spot: {
                Vec3 local = sampleUniformCone(u1, u2, l.cosOuterAngle);
                ph.ray.o = l.position;
                ph.ray.d = Frame(l.direction).toWorld(local);
                power = l.intensity * (l.spotFalloff(local.z) / uniformConePdf(l.cosOuterAngle));
                break;
            }
            case LightType::Directional: {
                Vec2 disk = sampleConcentricDisk(u1, u2);
                Frame f(l.direction);
                ph.ray.o = m_sceneCenter - l.direction * (1.01f * m_sceneRadius) +
                           (f.s * disk.x + f.t * disk.y) * m_sceneRadius;
                ph.ray.d = l.direction;
                power = l.intensity * (kPi * m_sceneRadius * m_sceneRadius);
                break;
            }
        }
    } else if (int(i) == m_environmentSource) {
        const EnvironmentSample es = m_scene.environment->sample(u1, u2);
        const Vec2 disk = sampleConcentricDisk(rng.uniform(), rng.uniform());
        const Frame f(-es.wi);
        ph.ray.o = m_sceneCenter + es.wi * (1.01f * m_sceneRadius) + (f.s * disk.x + f.t * disk.y) * m_sceneRadius;
        ph.ray.d = -es.wi;
        ph.environment = true;
        // L (pi R^2) / pdf(wi): the disc's area over the pdf of the direction.
        power = es.pdf > 0 ? es.radiance * (kPi * m_sceneRadius * m_sceneRadius / es.pdf) : Rgb(0.0f);
    } else {
        const EmissiveTriangle& e = m_scene.emitters[i - m_scene.lights.size()];
        Vec2 b = sampleUniformTriangle(u1, u2);
        Vec3 n;
        emitterPointAt(e, b, &ph.ray.o, &n);
        ph.ray.d = Frame(n).toWorld(sampleCosineHemisphere(rng.uniform(), rng.uniform()));
        ph.emitterMesh = e.mesh;
        // Le cos / (cos/pi * 1/area) = Le * pi * area.
        power = emittedRadiance(e, b) * (kPi * e.area);
    }
    ph.power = power / float(pick);
    return ph;
}

LightSampler::EmitterPoint LightSampler::sampleEmitterPoint(Rng& rng) const {
    EmitterPoint p;
    const double u = rng.uniform();
    const float u1 = rng.uniform(), u2 = rng.uniform();
    if (!(m_emitterPower > 0)) return p;
    const size_t i = chooseEmitter(u);
    const EmissiveTriangle& e = m_scene.emitters[i];
    const Vec2 b = sampleUniformTriangle(u1, u2);
    emitterPointAt(e, b, &p.point, &p.normal);
    p.radiance = emittedRadiance(e, b);
    p.pdfArea = float(emitterShare(i) / double(e.area));
    p.source = int(m_scene.lights.size() + i);
    return p;
}

void LightSampler::emitterPointAt(const EmissiveTriangle& e, Vec2 b, Vec3* point, Vec3* normal) const {
    const TriangleMesh& mesh = m_scene.meshes[size_t(e.mesh)];
    *point = mesh.vertex(e.triangle, 0) * (1.0f - b.x - b.y) + mesh.vertex(e.triangle, 1) * b.x +
             mesh.vertex(e.triangle, 2) * b.y;
    *normal = normalize(mesh.geometricNormal(e.triangle));
}

Rgb LightSampler::emittedRadiance(const EmissiveTriangle& e, Vec2 b) const {
    const TriangleMesh& mesh = m_scene.meshes[size_t(e.mesh)];
    if (!m_scene.materials[size_t(mesh.material)].emissiveTexture.present()) return e.radiance;
    return evalSurface(m_scene, mesh, e.triangle, b.x, b.y, 0.0f).emission;
}

}  // namespace tyndall
