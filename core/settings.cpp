#include "core/settings.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"

namespace tyndall {

const char* gpuModeText(GpuMode mode) {
    switch (mode) {
        case GpuMode::On: return "on";
        case GpuMode::Off: return "off";
        case GpuMode::Auto: break;
    }
    return "auto";
}

std::optional<GpuMode> gpuModeFromText(std::string_view text) {
    if (text == "auto") return GpuMode::Auto;
    if (text == "on") return GpuMode::On;
    if (text == "off") return GpuMode::Off;
    return std::nullopt;
}

const char* onOffText(bool on) { return on ? "on" : "off"; }

std::optional<bool> onOffFromText(std::string_view text) {
    if (text == "on") return true;
    if (text == "off") return false;
    return std::nullopt;
}

SettingError::SettingError(std::string k, std::string p)
    : Error("render setting '" + k + "' " + p), key(std::move(k)), problem(std::move(p)) {}

void RenderSettings::validate() const {
    auto fail = [](const char* key, const std::string& problem) { throw SettingError(key, problem); };
    if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
        fail("size", "must be in 1..16384 per side (got " + std::to_string(width) + "x" + std::to_string(height) + ")");
    if (!region.fits(width, height))
        fail("region", "must be X Y W H with W, H >= 1 inside the " + std::to_string(width) + "x" +
                           std::to_string(height) + " image (got " + std::to_string(region.x) + " " +
                           std::to_string(region.y) + " " + std::to_string(region.width) + " " +
                           std::to_string(region.height) + ")");
    if (!(alpha > 0.0 && alpha < 1.0)) fail("alpha", "must lie strictly between 0 and 1 (got " + std::to_string(alpha) + ")");
    if (passes == 0 && timeBudget <= 0) fail("passes", "must be positive");
    if (!(timeBudget >= 0) || !std::isfinite(timeBudget)) fail("time", "must be a non-negative number of seconds");
    if (photonsPerPass == 0) fail("photons", "must be positive");
    if (!(radius >= 0) || !std::isfinite(radius)) fail("radius", "must be >= 0 (0 = automatic)");
    if (!(surfaceRadius >= 0) || !std::isfinite(surfaceRadius)) fail("surface_radius", "must be >= 0 (0 = automatic)");
    if (!(photonAngle >= 0 || photonAngle == kAutoPhotonAngle) || !std::isfinite(photonAngle))
        fail("photon_angle", "must be >= 0 radians (0 = off) or automatic");
    if (threads < 0) fail("threads", "must be >= 0 (0 = all cores)");
    if (maxPhotonBounces <= 0) fail("max_photon_bounces", "must be positive");
    if (maxCameraBounces <= 0) fail("max_camera_bounces", "must be positive");
    if (maxPathLength < 0 || maxPathLength > 65535) fail("max_path_length", "must be in 0..65535 (0 = uncapped)");
    if (freeFlightSamples < 1 || freeFlightSamples > 64) fail("free_flights", "must be in 1..64");
    if (equiangularSamples != kAutoEquiangularSamples &&
        !(equiangularSamples > 0 && equiangularSamples <= kMaxEquiangularSamples))
        fail("equiangular_samples", "must be a number in (0, 64] or auto (got " + std::to_string(equiangularSamples) + ")");
    if (!(scatteredBeamMfp >= 0 && scatteredBeamMfp <= kMaxScatteredBeamMfp))
        fail("scattered_beam_mfp", "must be a number of mean free paths in [0, 10] (0 = off; got " +
                                       std::to_string(scatteredBeamMfp) + ")");
    if (!(mediumPointMfp >= 0 && mediumPointMfp <= kMaxMediumPointMfp))
        fail("medium_point_mfp", "must be a number of mean free paths in [0, 10] (0 = off; got " +
                                     std::to_string(mediumPointMfp) + ")");
    if (!(indirectPhotonSpread >= 0 && indirectPhotonSpread <= kMaxIndirectPhotonSpread))
        fail("indirect_photon_spread", "must be a number in [0, 1] (0 = off; got " +
                                           std::to_string(indirectPhotonSpread) + ")");
    if (memoryMiB < 64 || memoryMiB > (uint64_t(1) << 30))
        fail("memory", "must be in 64..2^30 MiB (got " + std::to_string(memoryMiB) + ")");
}

nlohmann::json RenderSettings::toJson() const {
    nlohmann::json j = {{"width", width},
            {"height", height},
            {"passes", passes},
            {"time", timeBudget},
            {"photons", photonsPerPass},
            {"alpha", alpha},
            {"radius", radius},
            {"surface_radius", surfaceRadius},
            {"radius_offset", radiusOffset == kAutoRadiusOffset ? nlohmann::json("auto") : nlohmann::json(radiusOffset)},
            {"planned_paths", plannedPaths},
            {"photon_angle", photonAngle == kAutoPhotonAngle ? nlohmann::json("auto") : nlohmann::json(photonAngle)},
            {"seed", seed},
            {"threads", threads},
            {"max_photon_bounces", maxPhotonBounces},
            {"max_camera_bounces", maxCameraBounces},
            {"max_path_length", maxPathLength},
            {"free_flights", freeFlightSamples},
            {"gpu", gpuModeText(gpu)},
            {"memory", memoryMiB},
            {"simd", onOffText(simd)},
            {"direct_light", onOffText(directLight)},
            {"surface_boundary", onOffText(surfaceBoundary)},
            {"equiangular", onOffText(equiangular)},
            {"equiangular_samples", equiangularSamples == kAutoEquiangularSamples ? nlohmann::json("auto")
                                                                                   : nlohmann::json(equiangularSamples)},
            {"film_light_sampling", onOffText(filmLightSampling)},
            {"photon_planes", onOffText(photonPlanes)},
            {"scattered_beam_mfp", scatteredBeamMfp},
            {"medium_point_mfp", mediumPointMfp},
            {"indirect_photon_spread", indirectPhotonSpread},
            {"transparent", onOffText(transparentFilm)}};
    if (!region.whole()) j["region"] = {region.x, region.y, region.width, region.height};
    return j;
}

namespace {
template <typename T>
void read(const nlohmann::json& j, const char* key, T& out, const std::string& where) {
    auto it = j.find(key);
    if (it == j.end()) return;
    try {
        if constexpr (std::is_same_v<T, std::string>) {
            if (!it->is_string()) throw Error("expected a string");
        } else if constexpr (std::is_floating_point_v<T>) {
            if (!it->is_number()) throw Error("expected a number");
        } else {
            if (!it->is_number_integer()) throw Error("expected an integer");
            if constexpr (std::is_unsigned_v<T>)
                if (it->template get<int64_t>() < 0) throw Error("expected a non-negative integer");
        }
        out = it->template get<T>();
    } catch (const std::exception& e) {
        throw Error(where + "/" + key + ": " + e.what());
    }
}

void read(const nlohmann::json& j, const char* key, GpuMode& out, const std::string& where) {
    auto it = j.find(key);
    if (it == j.end()) return;
    std::optional<GpuMode> mode = it->is_string() ? gpuModeFromText(it->get<std::string>()) : std::nullopt;
    if (!mode) throw Error(where + "/" + key + ": expected \"auto\", \"on\" or \"off\"");
    out = *mode;
}

void read(const nlohmann::json& j, const char* key, PixelRegion& out, const std::string& where) {
    auto it = j.find(key);
    if (it == j.end()) return;
    if (it->is_null()) {
        out = PixelRegion{};
        return;
    }
    bool ok = it->is_array() && it->size() == 4;
    for (size_t i = 0; ok && i < 4; ++i) ok = (*it)[i].is_number_integer() && (*it)[i].get<int64_t>() >= 0 &&
                                              (*it)[i].get<int64_t>() <= 16384;
    if (!ok) throw Error(where + "/" + key + ": expected [x, y, width, height] in pixels (or null: the whole image)");
    out = PixelRegion{(*it)[0].get<int>(), (*it)[1].get<int>(), (*it)[2].get<int>(), (*it)[3].get<int>()};
}

void read(const nlohmann::json& j, const char* key, bool& out, const std::string& where) {
    auto it = j.find(key);
    if (it == j.end()) return;
    std::optional<bool> on = it->is_boolean()  ? std::optional<bool>(it->get<bool>())
                             : it->is_string() ? onOffFromText(it->get<std::string>())
                                               : std::nullopt;
    if (!on) throw Error(where + "/" + key + ": expected \"on\" or \"off\" (or true or false)");
    out = *on;
}

/// A value, or "auto" for `automatic`; `expected` names the value in the error.
template <typename T>
void readOrAuto(const nlohmann::json& j, const char* key, T& out, T automatic, const char* expected,
                const std::string& where) {
    if (auto it = j.find(key); it != j.end() && it->is_string()) {
        if (*it != "auto") throw Error(where + "/" + key + ": expected " + expected + " or \"auto\"");
        out = automatic;
    } else {
        read(j, key, out, where);
    }
}
}  // namespace

RenderSettings RenderSettings::fromJson(const nlohmann::json& j, const std::string& where) {
    return fromJson(j, where, RenderSettings());
}

RenderSettings RenderSettings::fromJson(const nlohmann::json& j, const std::string& where, RenderSettings s) {
    if (!j.is_object()) throw Error(where + ": expected an object of render settings");
    static const char* kKeys[] = {"width", "height", "passes", "time", "photons", "alpha", "radius",
                                  "surface_radius", "radius_offset", "planned_paths", "photon_angle", "seed", "threads",
                                  "max_photon_bounces", "max_camera_bounces", "free_flights", "gpu", "memory", "simd",
                                  "direct_light", "surface_boundary", "max_path_length", "region", "equiangular",
                                  "equiangular_samples", "film_light_sampling", "photon_planes", "scattered_beam_mfp", "medium_point_mfp",
                                  "indirect_photon_spread", "transparent"};
    for (auto it = j.begin(); it != j.end(); ++it) {
        bool known = false;
        for (const char* k : kKeys) known |= it.key() == k;
        if (!known) throw Error(where + "/" + it.key() + ": unknown render setting");
    }
    read(j, "width", s.width, where);
    read(j, "height", s.height, where);
    read(j, "region", s.region, where);
    read(j, "passes", s.passes, where);
    read(j, "time", s.timeBudget, where);
    read(j, "photons", s.photonsPerPass, where);
    read(j, "alpha", s.alpha, where);
    read(j, "radius", s.radius, where);
    read(j, "surface_radius", s.surfaceRadius, where);
    readOrAuto(j, "radius_offset", s.radiusOffset, kAutoRadiusOffset, "a non-negative integer", where);
    read(j, "planned_paths", s.plannedPaths, where);
    readOrAuto(j, "photon_angle", s.photonAngle, kAutoPhotonAngle, "a number of radians >= 0", where);
    read(j, "seed", s.seed, where);
    read(j, "threads", s.threads, where);
    read(j, "max_photon_bounces", s.maxPhotonBounces, where);
    read(j, "max_camera_bounces", s.maxCameraBounces, where);
    read(j, "max_path_length", s.maxPathLength, where);
    read(j, "free_flights", s.freeFlightSamples, where);
    read(j, "gpu", s.gpu, where);
    read(j, "memory", s.memoryMiB, where);
    read(j, "simd", s.simd, where);
    read(j, "direct_light", s.directLight, where);
    read(j, "surface_boundary", s.surfaceBoundary, where);
    read(j, "equiangular", s.equiangular, where);
    readOrAuto(j, "equiangular_samples", s.equiangularSamples, kAutoEquiangularSamples, "a number in (0, 64]", where);
    read(j, "film_light_sampling", s.filmLightSampling, where);
    read(j, "photon_planes", s.photonPlanes, where);
    read(j, "scattered_beam_mfp", s.scatteredBeamMfp, where);
    read(j, "medium_point_mfp", s.mediumPointMfp, where);
    read(j, "indirect_photon_spread", s.indirectPhotonSpread, where);
    read(j, "transparent", s.transparentFilm, where);
    return s;
}

namespace {
// "auto": 4 equiangular samples per segment at 64x64 with 4000 photon paths per pass (the quality
// bench), where 4 measured better than 8 and 1 noisier (docs/performance.md); an equiangular
// sample costs a shadow ray per pixel, a photon path is the beams' share of a pass, and the
// equal-time optimum of N against the rest of a pass falls as sqrt(pixels / photon paths).
constexpr double kAutoEquiangularAt64 = 4;
constexpr double kAutoEquiangularPathsPerPixelAt64 = 4000.0 / (64 * 64);
constexpr double kAutoEquiangularMin = 0.25;
}  // namespace

double RenderSettings::autoEquiangularSamples(int width, int height, uint32_t photonsPerPass) {
    const double pixels = std::max(1.0, double(width) * double(height));
    const double n =
        kAutoEquiangularAt64 * std::sqrt(double(photonsPerPass) / pixels / kAutoEquiangularPathsPerPixelAt64);
    // Rounded to 1/64 so the recorded number reads plainly (and a resume reads it back exactly).
    return std::clamp(std::round(n * 64) / 64, kAutoEquiangularMin, kAutoEquiangularAt64);
}

double RenderSettings::resolvedEquiangularSamples() const {
    return equiangularSamples == kAutoEquiangularSamples ? autoEquiangularSamples(width, height, photonsPerPass)
                                                         : equiangularSamples;
}

RenderSettings resolveEquiangularSamples(RenderSettings s) {
    s.equiangularSamples = s.resolvedEquiangularSamples();
    return s;
}

}  // namespace tyndall
