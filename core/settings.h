#pragma once
// Render settings: a plain struct that reads and writes the same JSON (the scene file's
// "render" block, the EXR metadata). Every field has the default listed by `tyndall --help`.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "core/error.h"
#include "core/pixel_region.h"

namespace tyndall {

/// Where the primary media are splatted: Off never touches GL; On needs the GL splatter (an error
/// otherwise); Auto uses it when a hardware GL context exists and the scene's media can be
/// splatted, else the CPU twin (hybrid/pass_scheduler.h).
enum class GpuMode { Auto, On, Off };

/// The text forms of the typed settings, used only where settings meet text (the command line, a
/// scene's "render" block, EXR metadata, checkpoints, view files): "auto" | "on" | "off", and
/// "on" | "off" for the switches. The readers return nullopt for any other text.
const char* gpuModeText(GpuMode mode);
std::optional<GpuMode> gpuModeFromText(std::string_view text);
const char* onOffText(bool on);
std::optional<bool> onOffFromText(std::string_view text);

/// A render setting out of range, thrown by RenderSettings::validate(). `key` is the setting's
/// JSON name ("alpha", or "size" for width and height); what() reads "render setting 'alpha'
/// <problem>", and a command line reports the option instead ("--alpha <problem>").
class SettingError : public Error {
public:
    SettingError(std::string key, std::string problem);
    std::string key;
    std::string problem;  ///< "must lie strictly between 0 and 1 (got 1.5)"
};

struct RenderSettings {
    int width = 512;
    int height = 512;
    /// The render region: only these pixels are traced and splatted, the others stay 0; their
    /// values are those of the whole image's render bit for bit (same passes: the region changes
    /// no random stream, radius or photon). No region (the default) = the whole image. JSON
    /// "region": [x, y, width, height], written only when set.
    PixelRegion region;
    uint64_t passes = 64;            ///< stop after this many passes (when timeBudget == 0)
    double timeBudget = 0.0;         ///< seconds; > 0 renders passes until the budget is spent
    uint32_t photonsPerPass = 4000;  ///< photon paths emitted per pass (the bench uses 1000)
    double alpha = 0.5;              ///< radius reduction, in (0, 1): low = less noise, more bias
    /// Beam radius of the first photon path, scene units; 0 = automatic: chosen from the pixel
    /// footprint where the media are and the planned path count (cpu/radius_defaults.h). Later
    /// paths shrink by RadiusSchedule::beamFactor.
    float radius = 0.0f;
    /// Surface-photon radius of the first photon path; 0 = automatic (footprint on the surfaces).
    float surfaceRadius = 0.0f;
    /// RadiusSchedule offset n0 - 1 (see radius_schedule.h); kAutoRadiusOffset = chosen so the
    /// radius ends the planned budget near the pixel footprint.
    uint64_t radiusOffset = kAutoRadiusOffset;
    /// Photon paths the automatic radii plan for; 0 = passes x photons without a time budget, an
    /// open-ended horizon (RadiusDefaults::kOpenEndedPathsPerPixel per pixel, cpu/radius_defaults.h)
    /// with one until the rate is measured.
    uint64_t plannedPaths = 0;
    static constexpr uint64_t kAutoRadiusOffset = ~uint64_t(0);
    /// Photon cone angle of the first photon path, radians (cpu/beam_cone.h): at path distance s
    /// from its light a beam's radius is at most photonAngle x s (times the schedule's factor), so
    /// beams stay thinner than the photons' own spacing near a light. 0 = off (radius alone);
    /// kAutoPhotonAngle = chosen with the automatic radii (off when `radius` is explicit).
    float photonAngle = kAutoPhotonAngle;
    static constexpr float kAutoPhotonAngle = -1.0f;
    uint64_t seed = 1;
    int threads = 0;                 ///< 0 = all hardware threads
    int maxPhotonBounces = 32;       ///< photon path vertices before termination
    int maxCameraBounces = 16;       ///< specular camera-path vertices before termination
    /// Most segments of a light path, camera side and light side together (Mitsuba's max_depth,
    /// Tungsten's max_bounces): 1 = emitters seen directly, 2 = direct light and single scattering.
    /// Crossing an index-matched Interface starts no segment. 0 = uncapped. docs/algorithm.md.
    int maxPathLength = 0;
    int freeFlightSamples = 4;       ///< stored free-flight distances per beam/ray (heterogeneous)
    GpuMode gpu = GpuMode::Auto;
    /// Working-memory budget of the pass loop, MiB: image buffers plus the photon batches a pass
    /// is traced in (cpu/memory_plan.h). Sets the batch size, never the image.
    uint64_t memoryMiB = 2048;
    /// The CPU beam rasterizer's SIMD kernel (false = the scalar definition; the two agree to ~1e-7
    /// relative per pixel, docs/performance.md)
    bool simd = true;
    /// Direct light on diffuse surfaces by shadow rays (next-event estimation,
    /// cpu/direct_light.h) instead of the surface photons that arrive straight from a light, which
    /// are then not stored (docs/algorithm.md, "Direct light by shadow rays"). off = photons only.
    bool directLight = true;
    /// The surface photon kernel divided by the part of its disc that lies on surface
    /// that can hold those photons (cpu/surface_boundary.h), which removes the estimate's loss at
    /// the edges and corners of surfaces (docs/algorithm.md, "The surface kernel at edges").
    /// false = the plain kernel.
    bool surfaceBoundary = true;
    /// Single scattering from point, spot, area and directional lights along every camera segment in
    /// a medium by equiangular sampling (directional lights: distance sampling; cpu/equiangular.h)
    /// instead of those lights' unscattered first beams,
    /// which are then not stored (docs/algorithm.md, "Single scattering by equiangular sampling").
    /// false = beams only (docs/performance.md: on is better or level at equal time on every scene).
    bool equiangular = true;
    /// Equiangular distances per camera segment in a medium, shared by its lights (each drawn for
    /// one light, chosen by its estimated share of the segment's light: cpu/equiangular.h), in
    /// (0, 64]; a fraction f over floor(N) is one more distance on a share f of the segments (the
    /// sum divided by N). kAutoEquiangularSamples = autoEquiangularSamples(), resolved before
    /// rendering (resolveEquiangularSamples) and recorded as a number.
    double equiangularSamples = kAutoEquiangularSamples;
    static constexpr double kAutoEquiangularSamples = 0;
    static constexpr double kMaxEquiangularSamples = 64;
    /// With `equiangular` on: a pixel within a pixel of the image of a point or spot light inside a
    /// medium traces one more camera ray a pass, its film position drawn towards that image
    /// (density falling as 1 / distance from it), for that light's single scattering alone,
    /// combined with the uniform ray's by the balance heuristic (core/film_light_sampler.h;
    /// docs/algorithm.md, "Camera rays near a light's image"): the light's single scattering,
    /// growing as 1 / distance from the light, then has finite variance in that pixel, and the
    /// rest of the pixel keeps its uniform film position. false = the uniform ray alone.
    bool filmLightSampling = true;
    /// Photon planes (core/photon_plane.h) in homogeneous media: every beam there is joined with a
    /// sampled next direction into a plane that every camera segment in a medium gathers without a
    /// kernel, and the beams that start at a scattering in a homogeneous medium (which the planes
    /// stand for) are not stored (docs/algorithm.md, "Photon planes"). false = beams only.
    bool photonPlanes = false;
    /// Beams that start at a scattering in a homogeneous medium (not a light's first beams, nor those
    /// leaving a surface, whose edges are sharp, nor those after a scattering in a grid medium) get
    /// a kernel radius of at least this many of the medium's mean free paths (1 / the largest
    /// channel of sigma_t) at the end of the plan, and shrink by the same schedule as every beam, so
    /// they stay consistent: their radius is the automatic one times max(1, C mfp / the plan's end
    /// radius), at most kMaxScatteredBeamScale times (docs/algorithm.md, "Beams after a
    /// scattering"). 0 = off: every beam the schedule's radius.
    double scatteredBeamMfp = 0.05;
    static constexpr double kMaxScatteredBeamMfp = 10;
    static constexpr double kMaxScatteredBeamScale = 8;
    /// Photon points in dense media (docs/algorithm.md, "Photon points in dense media"): a beam that
    /// starts at a scattering in a homogeneous medium whose mean free path (1 / the largest channel
    /// of sigma_t) is short against the beam radius, C mfp <= kMaxMediumPointScale x the plan's end
    /// radius, is not stored; the photon's next scattering on it is stored instead as a point, which
    /// the camera segments in that medium gather with a 2D kernel of the schedule's radius times
    /// max(1, C mfp / the plan's end radius) (the beam radiance estimate). 0 = off: beams only.
    double mediumPointMfp = 0;
    static constexpr double kMaxMediumPointMfp = 10;
    /// Surface photons whose light scattered diffusely since it left the light (at a diffuse or
    /// glossy surface, in a medium, or an emissive medium's) and came from there along a path of
    /// length l (mirrors, glass and Interfaces on the way count in l) get a kernel radius of at
    /// least C l at the end of the plan, and shrink by the same schedule as every surface photon, so
    /// they stay consistent: their radius is the automatic one times clamp(C l / the plan's end
    /// surface radius, 1, kMaxIndirectPhotonScale), rounded down to a quarter octave. Caustic
    /// photons (a light's through mirrors and glass alone) keep the automatic radius
    /// (docs/algorithm.md, "Indirect surface photons"). 0 = off: every photon the schedule's radius.
    double indirectPhotonSpread = 0;
    static constexpr double kMaxIndirectPhotonSpread = 1;
    static constexpr double kMaxIndirectPhotonScale = 8;
    static constexpr double kMaxMediumPointScale = 16;
    /// Points per beam they stand for: the photon's own free flight and this many minus one more.
    static constexpr int kMediumPointsPerBeam = 4;
    /// Transparent film (render block "transparent", `tyndall render --transparent`): camera paths
    /// that reach the environment straight, through index-matched Interfaces alone, do not see it
    /// (it still lights the scene), and the output gets an alpha channel, the pixel's coverage: 1
    /// minus the share of its camera paths' throughput that reached the background, so fog in
    /// front of an empty background composites by its transmittance (Cycles' transparent film).
    bool transparentFilm = false;

    /// Throws SettingError naming the setting when a value is out of range.
    void validate() const;
    /// The typed settings as their text forms ("gpu": "auto", "simd": "on", ...).
    nlohmann::json toJson() const;
    /// Reads the keys present in `j` over the defaults; unknown keys and wrong types throw Error
    /// naming `where` (a file and JSON path) and the key. The switches read "on"/"off" or a JSON
    /// true/false.
    static RenderSettings fromJson(const nlohmann::json& j, const std::string& where, RenderSettings base);
    static RenderSettings fromJson(const nlohmann::json& j, const std::string& where);

    /// What equiangularSamples "auto" stands for at this image size and photon count: falls as
    /// sqrt(pixels / photon paths per pass) from 4 at the quality bench's 64x64 with 4000 paths,
    /// within bounds (settings.cpp; docs/algorithm.md, "How many samples, and which light"). The
    /// whole image's size counts, not the region's (a region renders its pixels as the whole
    /// image does).
    static double autoEquiangularSamples(int width, int height, uint32_t photonsPerPass);
    /// equiangularSamples, "auto" resolved.
    double resolvedEquiangularSamples() const;
};

/// `s` with equiangularSamples "auto" replaced by its number (a pure function of the settings).
RenderSettings resolveEquiangularSamples(RenderSettings s);

}  // namespace tyndall
