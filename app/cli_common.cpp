#include "app/cli_common.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>

#include "loading/default_scene.h"
#include "core/error.h"
#include "loading/scene_environment.h"
#include "loading/scene_file.h"

namespace tyndall::app {

CLI::Validator nonNegativeInteger() {
    return CLI::Validator(
        [](std::string& v) {
            return !v.empty() && v[0] == '-' ? "expected a non-negative integer, got '" + v + "'" : std::string();
        },
        "", "non-negative");
}

CLI::Validator positiveInteger() {
    return CLI::Validator(
        [](std::string& v) {
            std::string error = "expected a positive integer, got '" + v + "'";
            if (v.empty() || v[0] == '-') return error;
            // Leave text that is no number to CLI11's conversion error; only zero is caught here.
            char* end = nullptr;
            unsigned long long n = std::strtoull(v.c_str(), &end, 10);
            return end != v.c_str() && *end == '\0' && n == 0 ? error : std::string();
        },
        "", "positive");
}

CLI::Validator positiveNumber() {
    return CLI::Validator(
        [](std::string& v) {
            char* end = nullptr;
            double x = std::strtod(v.c_str(), &end);
            bool number = end != v.c_str() && *end == '\0';
            return number && !(x > 0 && std::isfinite(x)) ? "expected a positive number, got '" + v + "'"
                                                          : std::string();
        },
        "", "positive");
}

void addSceneAndOutputOptions(CLI::App* cmd, CommonOptions& o, const std::string& defaultOutput) {
    o.output = defaultOutput;
    o.command = cmd;
    cmd->add_option("scene", o.scene, "Scene file (.json, .gltf, .glb); omitted = the built-in default scene");
    cmd->add_option("--camera", o.camera, "Camera by name or index (default: the scene's first camera)");
    cmd->add_option("--environment", o.environment,
                    "Latitude-longitude image (.exr, .hdr) lighting the scene from all around, in place of the "
                    "scene's own environment (default: the scene's own, if any; docs/scene-format.md)");
    if (!defaultOutput.empty())
        cmd->add_option("-o,--output", o.output,
                        "Output image: .exr (linear, settings in metadata) or .png (tone-mapped)")
            ->capture_default_str();
    cmd->add_option("--size", o.size, "Image size WxH in pixels")->capture_default_str();
    cmd->add_option("--seed", o.settings.seed, "Random seed: the same seed gives the same passes")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    cmd->add_option("--threads", o.settings.threads, "Worker threads (0 = all cores)")->capture_default_str();
    cmd->add_option("--load-memory", o.loadMemoryMiB,
                    "Loading memory budget in MiB: what the scene's grids, buffers and textures may take; a file "
                    "asking for more is refused before it is read. Default: 16384, or 3/4 of the machine's memory "
                    "or of ulimit -v when less (docs/production.md)")
        ->check(positiveInteger())
        ->capture_default_str();
    if (!defaultOutput.empty())
        cmd->add_option("--exposure", o.exposure, "Exposure multiplier for PNG output")->capture_default_str();
}

void addPpbOptions(CLI::App* cmd, CommonOptions& o) {
    // Unsigned options reject "-3" explicitly: CLI11 would otherwise wrap it to 2^64 - 3.
    auto* passes = cmd->add_option("--passes", o.settings.passes, "Number of passes")
                       ->check(nonNegativeInteger())
                       ->capture_default_str();
    auto* time = cmd->add_option("--time", o.settings.timeBudget,
                                 "Time budget in seconds, instead of --passes (default: off, --passes decides)")
                     ->check(positiveNumber());
    passes->excludes(time);
    cmd->add_option("--photons", o.settings.photonsPerPass, "Photon paths per pass")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    cmd->add_option("--alpha", o.settings.alpha, "Radius reduction alpha in (0,1): lower = less noise, more bias")
        ->capture_default_str();
    cmd->add_option("--radius", o.settings.radius,
                    "Beam radius of the first photon path, scene units (0 = automatic: from the pixel footprint "
                    "where the media are and the budget, see docs/algorithm.md)")
        ->capture_default_str();
    cmd->add_option("--surface-radius", o.settings.surfaceRadius,
                    "Surface photon radius of the first photon path (0 = automatic, from the footprint on the surfaces)")
        ->capture_default_str();
    cmd->add_option("--radius-offset", o.settings.radiusOffset,
                    "Photon paths the radius schedule treats as already traced (default: automatic, so the beam "
                    "radius ends the budget near a pixel footprint; see docs/algorithm.md)")
        ->check(nonNegativeInteger());
    cmd->add_option("--planned-paths", o.settings.plannedPaths,
                    "Photon paths the automatic radii plan for (default: passes x photons; with --time, the "
                    "open-ended horizon of 100 paths per pixel)")
        ->check(nonNegativeInteger());
    cmd->add_option("--photon-angle", o.settings.photonAngle,
                    "Photon cone angle of the first photon path, radians: near a light a beam's radius is at most "
                    "this x its path distance from the light, 0 = off (default: automatic, see docs/algorithm.md)");
    cmd->add_option("--free-flights", o.settings.freeFlightSamples,
                    "Stored free-flight distances per beam and pixel (heterogeneous media)")
        ->capture_default_str();
    cmd->add_option("--memory", o.settings.memoryMiB,
                    "Working-memory budget in MiB: the image buffers (~400 bytes per pixel) plus the photon "
                    "batches a pass is traced in, whatever --photons is; peak use is about this plus the "
                    "scene and ~100 MiB (docs/performance.md)")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    addSimdOption(cmd, o);
    addDirectLightOption(cmd, o);
}

namespace {
/// An on|off option read into a bool (the text forms are core's: onOffFromText).
void addOnOffOption(CLI::App* cmd, const std::string& name, bool& target, const std::string& help) {
    cmd->add_option_function<std::string>(
           name,
           [&target, name](const std::string& text) {
               std::optional<bool> on = onOffFromText(text);
               if (!on) throw CLI::ValidationError(name, "expected on or off, got '" + text + "'");
               target = *on;
           },
           help)
        ->type_name("TEXT")
        ->default_str(onOffText(target));
}

/// The command-line option that sets each render setting (SettingError::key).
const std::pair<const char*, const char*> kOptionKeys[] = {
    {"--passes", "passes"},
    {"--time", "time"},
    {"--photons", "photons"},
    {"--alpha", "alpha"},
    {"--radius", "radius"},
    {"--surface-radius", "surface_radius"},
    {"--radius-offset", "radius_offset"},
    {"--planned-paths", "planned_paths"},
    {"--photon-angle", "photon_angle"},
    {"--free-flights", "free_flights"},
    {"--seed", "seed"},
    {"--threads", "threads"},
    {"--gpu", "gpu"},
    {"--memory", "memory"},
    {"--simd", "simd"},
    {"--direct-light", "direct_light"},
    {"--surface-boundary", "surface_boundary"},
    {"--equiangular", "equiangular"},
    {"--equiangular-samples", "equiangular_samples"},
    {"--film-light-sampling", "film_light_sampling"},
    {"--photon-planes", "photon_planes"},
    {"--scattered-beam-mfp", "scattered_beam_mfp"},
    {"--medium-points", "medium_point_mfp"},
    {"--indirect-photon-spread", "indirect_photon_spread"},
    {"--max-path-length", "max_path_length"},
    {"--region", "region"}};

/// settings.validate(), its errors naming the command-line option.
void validateOptions(const RenderSettings& settings) {
    try {
        settings.validate();
    } catch (const SettingError& e) {
        std::string option = e.key == "size" ? "--size" : "the " + e.key + " setting";
        for (const auto& [flag, key] : kOptionKeys)
            if (e.key == key) option = flag;
        throw Error(option + " " + e.problem);
    }
}
}  // namespace

void addGpuOption(CLI::App* cmd, CommonOptions& o, const std::string& help) {
    cmd->add_option_function<std::string>(
           "--gpu",
           [&o](const std::string& text) {
               std::optional<GpuMode> mode = gpuModeFromText(text);
               if (!mode) throw CLI::ValidationError("--gpu", "expected auto, on or off, got '" + text + "'");
               o.settings.gpu = *mode;
           },
           help)
        ->type_name("TEXT")
        ->default_str(gpuModeText(o.settings.gpu));
}

void addDirectLightOption(CLI::App* cmd, CommonOptions& o) {
    addOnOffOption(cmd, "--direct-light", o.settings.directLight,
                   "on|off: direct light on diffuse surfaces by shadow rays; off = surface photons only "
                   "(docs/algorithm.md)");
    addOnOffOption(cmd, "--surface-boundary", o.settings.surfaceBoundary,
                   "on|off: divide the surface photon kernel by the part of its disc that lies on the "
                   "surface, so edges and corners are not darkened; off = the plain kernel (docs/algorithm.md)");
    addOnOffOption(cmd, "--equiangular", o.settings.equiangular,
                   "on|off: single scattering from point, spot, area and directional lights and the environment "
                   "along camera rays in media by equiangular (directional, environment: distance) sampling; off = "
                   "those lights' first photon beams (docs/algorithm.md)");
    cmd->add_option_function<std::string>(
           "--equiangular-samples",
           [&o](const std::string& text) {
               double n = RenderSettings::kAutoEquiangularSamples;
               if (text != "auto") {
                   size_t used = 0;
                   try {
                       n = std::stod(text, &used);
                   } catch (const std::exception&) {
                       used = 0;
                   }
                   if (used == 0 || used != text.size() || !(n > 0 && n <= RenderSettings::kMaxEquiangularSamples))
                       throw CLI::ValidationError("--equiangular-samples",
                                                  "expected auto or a number in (0, 64], got '" + text + "'");
               }
               o.settings.equiangularSamples = n;
           },
           "N|auto: equiangular distances per camera segment in a medium, all lights together (a fraction: "
           "one more on that share of the segments); auto = 4 at 64x64 pixels and 4000 photon paths per pass, "
           "falling as sqrt(pixels / photon paths), at least 1/4 (docs/algorithm.md)")
        ->type_name("TEXT")
        ->default_str("auto");
    addOnOffOption(cmd, "--film-light-sampling", o.settings.filmLightSampling,
                   "on|off: with --equiangular on, pixels near the image of a point or spot light in a medium trace "
                   "one more camera ray drawn towards it for that light's single scattering, combined with the "
                   "uniform one by MIS (finite variance for the light's glow); off = uniform film positions alone "
                   "(docs/algorithm.md)");
    addOnOffOption(cmd, "--photon-planes", o.settings.photonPlanes,
                   "on|off: photon planes in homogeneous media (a beam swept along its next direction, "
                   "no kernel) instead of the beams after a scattering there; off = beams only (docs/algorithm.md)");
    cmd->add_option("--scattered-beam-mfp", o.settings.scatteredBeamMfp,
                    "C: beams that start at a scattering in a homogeneous medium end the plan with a radius of at "
                    "least C of its mean free paths (at most 8 automatic radii), shrinking like every beam; 0 = the "
                    "automatic radius for every beam (docs/algorithm.md)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxScatteredBeamMfp).description(""))
        ->capture_default_str();
    cmd->add_option("--medium-points", o.settings.mediumPointMfp,
                    "C: in a homogeneous medium whose mean free path is short against the beam radius (C mfp at "
                    "most 16 automatic radii at the plan's end), photon points at the scatterings instead of the "
                    "beams after a scattering, gathered with a radius of C mean free paths at the plan's end "
                    "(at least the automatic one); 0 = beams only (docs/algorithm.md)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxMediumPointMfp).description(""))
        ->capture_default_str();
    cmd->add_option("--indirect-photon-spread", o.settings.indirectPhotonSpread,
                    "C: surface photons whose light scattered diffusely (at a surface or in a medium) end the plan "
                    "with a radius of at least C times their path length from that scattering (at most 8 "
                    "automatic radii), shrinking like every surface photon; caustic photons keep the automatic "
                    "radius; 0 = the automatic radius for every photon (docs/algorithm.md)")
        ->check(CLI::Range(0.0, RenderSettings::kMaxIndirectPhotonSpread).description(""))
        ->capture_default_str();
}

void addPathLengthOption(CLI::App* cmd, CommonOptions& o) {
    cmd->add_option("--max-path-length", o.settings.maxPathLength,
                    "Most segments of a light path, camera and light side together, as Mitsuba's max_depth "
                    "and Tungsten's max_bounces count them: 1 = emitters seen directly, 2 = direct light and "
                    "single scattering; 0 = uncapped")
        ->check(nonNegativeInteger())
        ->capture_default_str();
}

void addRegionOption(CLI::App* cmd, CommonOptions& o) {
    cmd->add_option("--region", o.region,
                    "Render region X Y W H in pixels (top-left origin): only those pixels are traced and splatted, "
                    "the others stay 0; they equal the whole image's at the same seed and passes (default: the "
                    "whole image)")
        ->expected(4)
        ->allow_extra_args(false);
}

void addSimdOption(CLI::App* cmd, CommonOptions& o) {
    addOnOffOption(cmd, "--simd", o.settings.simd,
                   "on|off: the CPU beam splat's SIMD kernel; off runs the scalar estimator (its definition)");
}

void finishOptions(CommonOptions& o) {
    std::smatch m;
    static const std::regex kSize(R"(^\s*(\d{1,6})\s*[xX]\s*(\d{1,6})\s*$)");
    if (!std::regex_match(o.size, m, kSize)) throw Error("--size: expected WxH such as 512x512, got '" + o.size + "'");
    o.settings.width = std::stoi(m[1]);
    o.settings.height = std::stoi(m[2]);
    if (!(o.exposure > 0) || !std::isfinite(o.exposure)) throw Error("--exposure must be a positive number");
    if (!o.region.empty()) {
        const std::vector<int>& r = o.region;
        if (r.size() != 4 || r[0] < 0 || r[1] < 0 || r[2] < 1 || r[3] < 1)
            throw Error("--region: expected X Y W H in pixels, X and Y >= 0, W and H >= 1 (got " +
                        [&] {
                            std::string got;
                            for (int v : r) got += (got.empty() ? "" : " ") + std::to_string(v);
                            return got;
                        }() +
                        ")");
        o.settings.region = PixelRegion{r[0], r[1], r[2], r[3]};
    }
    // The region is checked against the image size in loadScene: the scene's render block may set it.
    RenderSettings unsized = o.settings;
    unsized.region = PixelRegion{};
    validateOptions(unsized);
}

namespace {
/// The render settings given explicitly on the command line, as RenderSettings JSON keys.
nlohmann::json explicitSettings(const CommonOptions& o) {
    nlohmann::json all = o.settings.toJson(), given = nlohmann::json::object();
    auto isGiven = [&](const char* name) {
        const CLI::Option* opt = o.command ? o.command->get_option_no_throw(name) : nullptr;
        return opt && opt->count() > 0;
    };
    for (const auto& [option, key] : kOptionKeys)
        if (isGiven(option)) given[key] = all[key];
    if (isGiven("--size")) given["width"] = all["width"], given["height"] = all["height"];
    if (isGiven("--passes") || isGiven("--time")) given["passes"] = all["passes"], given["time"] = all["time"];
    return given;
}
}  // namespace

Scene loadScene(CommonOptions& o, std::vector<std::string>* cameraNames, std::vector<Camera>* cameras) {
    SceneFile file;
    if (o.scene.empty()) {
        file.scene = makeDefaultScene();
        if (!o.camera.empty() && o.camera != "0" && o.camera != "default")
            throw Error("--camera " + o.camera + ": the built-in default scene has one camera, 0 'default'");
        file.scene.validate();
        file.render = defaultSceneRender();
        file.renderWhere = "default scene";
        file.cameras = {"default"};
        file.cameraViews = {file.scene.camera};
        if (!o.environment.empty()) {
            WarnOnce warn(nullptr);
            LoadBudget budget(loadMemoryBytes(o));
            file.scene.environment = loadEnvironmentImage(o.environment, "--environment", warn, &budget);
        }
    } else {
        SceneLoadOptions options;
        options.camera = o.camera;
        options.environment = o.environment;
        options.loadMemoryBytes = loadMemoryBytes(o);
        file = loadSceneFile(o.scene, options);
    }
    // The command's own defaults (bench's photon count), then the scene's render block, then the
    // options given.
    RenderSettings fromScene = RenderSettings::fromJson(file.render, file.renderWhere, o.settings);
    o.settings = RenderSettings::fromJson(explicitSettings(o), "command line", fromScene);
    validateOptions(o.settings);
    if (cameraNames) *cameraNames = file.cameras;
    if (cameras) *cameras = file.cameraViews;
    return std::move(file.scene);
}

uint64_t loadMemoryBytes(const CommonOptions& o) {
    const CLI::Option* given = o.command ? o.command->get_option_no_throw("--load-memory") : nullptr;
    return given && given->count() > 0 ? std::min(o.loadMemoryMiB, uint64_t(1) << 40) << 20 : defaultLoadMemoryBytes();
}

void checkOutputWritable(const std::string& path) {
    checkImageExtension(path);
    namespace fs = std::filesystem;
    fs::path p(path);
    fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw Error("output '" + path + "': directory '" + dir.string() + "' does not exist");
    bool existed = fs::exists(p, ec);
    {
        std::ofstream probe(path, std::ios::app);
        if (!probe) throw Error("output '" + path + "': cannot be written (permissions?)");
    }
    if (!existed) fs::remove(p, ec);
}

void addTwinOption(CLI::App* cmd, TwinRegion& region) {
    static const std::map<std::string, TwinRegion> regions = {{"support", TwinRegion::Support},
                                                              {"domain", TwinRegion::Domain}};
    cmd->add_option("--twin", region,
                    "Where the homogeneous twin's medium sits: support (a box around the grid's voxels, at the "
                    "grid's mean over that box; clear air outside) or domain (all space the grid's medium fills, at "
                    "its mean over its active voxels) (default: support)")
        ->transform(CLI::CheckedTransformer(regions))
        ->default_str("support");
}

ThreadLimit::ThreadLimit(int threads) {
    if (threads > 0) m_control = new tbb::global_control(tbb::global_control::max_allowed_parallelism, size_t(threads));
}
ThreadLimit::~ThreadLimit() {
    delete static_cast<tbb::global_control*>(m_control);
}

}  // namespace tyndall::app
