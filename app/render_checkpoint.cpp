#include "app/render_checkpoint.h"

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace tyndall::app {

namespace {
constexpr const char* kFormat = "tyndall render checkpoint";
constexpr int kVersion = 1;

template <class T>
uint64_t hashVector(const std::vector<T>& v, uint64_t h) {
    return fnv1a(v.data(), v.size() * sizeof(T), h);
}
uint64_t hashRgb(const Rgb& c, uint64_t h) {
    float f[3] = {c.r, c.g, c.b};
    return fnv1a(f, sizeof f, h);
}
template <class T>
uint64_t hashValue(const T& v, uint64_t h) {
    return fnv1a(&v, sizeof v, h);
}

/// A grid medium's fields as the passes see them: the whole density grid and emission field
/// (DensityGrid::contentHash, EmissionField::contentHash: for OpenVDB grids every stored value),
/// so a grid file rewritten behind an unchanged scene file, even in one voxel, or an emission grid,
/// scale or temperature mapping that changed, changes the hash.
uint64_t hashGridMedium(const Medium& m, uint64_t h) {
    h = m.density->contentHash(h);
    if (m.emissionField) h = m.emissionField->contentHash(h, m.density->bounds());
    return h;
}
}  // namespace

uint64_t sceneHash(const std::string& scenePath, const Scene& scene) {
    uint64_t h = fnv1a("tyndall-scene", 13);
    if (!scenePath.empty()) {
        std::ifstream in(scenePath, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        const std::string s = bytes.str();
        h = fnv1a(s.data(), s.size(), h);
    }
    for (const TriangleMesh& m : scene.meshes) {
        h = hashVector(m.positions, h);
        h = hashVector(m.indices, h);
        int32_t ids[3] = {m.material, m.interiorMedium, m.exteriorMedium};
        h = fnv1a(ids, sizeof ids, h);
    }
    for (const Material& m : scene.materials) h = hashRgb(m.emission, hashRgb(m.albedo, h));
    for (const Medium& m : scene.media) {
        h = hashRgb(m.sigmaA, hashRgb(m.sigmaS, h));
        h = hashValue(m.g, h);
        h = hashRgb(m.emission, h);
        h = hashValue(m.emissionScale, h);
        const uint8_t kinds[2] = {m.density != nullptr, m.emissionField != nullptr};
        h = fnv1a(kinds, sizeof kinds, h);
        if (m.density) h = hashGridMedium(m, h);
    }
    uint64_t lights = scene.lights.size();
    return fnv1a(&lights, sizeof lights, h);
}

std::string hashText(uint64_t hash) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)hash);
    return buf;
}

Checkpoint makeCheckpoint(const RenderRecord& r, std::vector<std::pair<std::string, Accumulator>> layers) {
    Checkpoint c;
    c.header = {{"format", kFormat},
                {"version", kVersion},
                {"scene", r.scenePath},
                {"camera", r.camera},
                {"environment", r.environment},
                {"scene_hash", hashText(r.sceneHash)},
                {"settings", r.settings.toJson()},
                {"output", r.output},
                {"exposure", r.exposure},
                {"aov", r.aov},
                {"elapsed", r.elapsed},
                {"passes_done", layers.empty() ? uint64_t(0) : layers.front().second.passCount()}};
    c.layers = std::move(layers);
    return c;
}

bool CheckpointWrites::save(const Checkpoint& checkpoint, uint64_t passes, const std::function<void()>& midWrite) {
    ++m_writes;
    try {
        saveCheckpoint(m_path, checkpoint, midWrite);
    } catch (const Error& e) {
        if (m_failures++ == 0)
            std::fprintf(stderr,
                         "\ntyndall: warning: checkpoints are failing: %s; the render goes on, the previous "
                         "checkpoint is kept, and later failures are counted silently\n",
                         e.what());
        return false;
    }
    m_anyGood = true;
    m_lastGoodPasses = passes;
    return true;
}

std::string CheckpointWrites::summary() const {
    if (m_failures == 0) return "";
    return std::to_string(m_failures) + " of " + std::to_string(m_writes) + " checkpoint writes failed; '" + m_path +
           "' " + (m_anyGood ? "holds the checkpoint of pass " + std::to_string(m_lastGoodPasses)
                             : std::string("holds no checkpoint written by this run"));
}

RenderRecord readRecord(const Checkpoint& c, const std::string& where) {
    const nlohmann::json& j = c.header;
    if (!j.is_object() || j.value("format", "") != kFormat)
        throw Error(where + ": not a checkpoint of `tyndall render` (format '" +
                    (j.is_object() ? j.value("format", "") : std::string()) + "')");
    if (j.value("version", 0) != kVersion)
        throw Error(where + ": checkpoint version " + std::to_string(j.value("version", 0)) + ", this tyndall reads " +
                    std::to_string(kVersion));
    RenderRecord r;
    try {
        r.scenePath = j.at("scene").get<std::string>();
        r.camera = j.at("camera").get<std::string>();
        r.environment = j.value("environment", std::string());  // absent before --environment
        r.sceneHash = std::stoull(j.at("scene_hash").get<std::string>(), nullptr, 16);
        r.settings = RenderSettings::fromJson(j.at("settings"), where + ": settings");
        // Checkpoints from before --direct-light rendered with surface photons alone.
        if (!j.at("settings").contains("direct_light")) r.settings.directLight = false;
        // ... and from before --surface-boundary with the plain kernel.
        if (!j.at("settings").contains("surface_boundary")) r.settings.surfaceBoundary = false;
        // ... and from before --equiangular with beams alone.
        if (!j.at("settings").contains("equiangular")) r.settings.equiangular = false;
        // ... and from before --equiangular-samples with 4 per light (the nearest: 4 per segment).
        if (!j.at("settings").contains("equiangular_samples")) r.settings.equiangularSamples = 4;
        // ... and from before --scattered-beam-mfp with every beam at the schedule's radius.
        if (!j.at("settings").contains("scattered_beam_mfp")) r.settings.scatteredBeamMfp = 0;
        // ... and from before --medium-points with beams alone.
        if (!j.at("settings").contains("medium_point_mfp")) r.settings.mediumPointMfp = 0;
        // ... and from before --indirect-photon-spread with every surface photon at the schedule's radius.
        if (!j.at("settings").contains("indirect_photon_spread")) r.settings.indirectPhotonSpread = 0;
        // ... and from before --film-light-sampling with uniform film positions.
        if (!j.at("settings").contains("film_light_sampling")) r.settings.filmLightSampling = false;
        r.output = j.at("output").get<std::string>();
        r.exposure = j.at("exposure").get<float>();
        r.aov = j.at("aov").get<bool>();
        r.elapsed = j.at("elapsed").get<double>();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(where + ": malformed checkpoint header: " + e.what());
    }
    return r;
}

}  // namespace tyndall::app
