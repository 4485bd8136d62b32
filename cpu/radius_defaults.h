#pragma once
// The automatic photon radii: the settings left at "automatic" (radius 0, surface radius 0,
// radius offset kAutoRadiusOffset) resolved into plain numbers from the camera's pixel footprint
// where the media and surfaces are (cpu/pixel_footprint.h) and the planned photon-path count.
// The model and the measurements behind the constants: docs/algorithm.md ("Where the radius
// sits") and docs/performance.md ("Image quality at equal time").
//
//   beam radius at the end of the plan    = kBeamEndFootprints    x media footprint
//   surface radius at the end of the plan = kSurfaceEndFootprints x surface footprint, at most
//                                           kSurfaceEndMaxDiagonal x the scene's diagonal
//   first beam radius                     = kStartOverEnd x the end radius (auto radius)
//   offset                                = the one whose schedule shrinks the first radius to the
//                                           end radius over the planned paths (auto offset)
// With an explicit offset, automatic radii start at kStartOverEnd x their end footprints (surface:
// sqrt of it, the 2D kernel's rate). An explicit radius with an automatic offset is shrunk to the
// end radius by the plan (kept constant when it is already smaller). Explicit values are never
// changed. The result is a plain RenderSettings: rendering with it reproduces the image bit for bit.
#include <cstdint>

#include "core/settings.h"
#include "cpu/embree_scene.h"

namespace tyndall {

struct RadiusDefaults {
    static constexpr double kBeamEndFootprints = 0.5;
    static constexpr double kSurfaceEndFootprints = 3.0;
    static constexpr double kStartOverEnd = 4.0;
    /// The surface radius's ceiling at the end of a plan, as a fraction of the scene's diagonal
    /// (so it starts at most at twice the 2% of the scene-relative defaults). A kernel loses the light of
    /// photons near a surface's edges, a loss set by the radius against the scene's objects, not the
    /// pixel: in coarse images (tens of pixels) 3 footprints are several percent of the scene and
    /// lose that much of the lit surfaces' light (docs/algorithm.md, "Where the radius sits").
    static constexpr double kSurfaceEndMaxDiagonal = 0.02;
    /// The scene-relative radii of earlier versions (withSceneRelativeRadii), which also stand in
    /// where no footprint can be measured: the first beam radius and the surface radius as
    /// fractions of the scene's diagonal, and the radius offset.
    static constexpr double kSceneRelativeBeam = 0.005;
    static constexpr double kSceneRelativeSurface = 0.02;
    static constexpr uint64_t kSceneRelativeOffset = 1000;
    /// Horizon of an open-ended render (no pass count, time not yet measured): photon paths per
    /// image pixel, about a minute of a 2-core machine at 256x256 (docs/performance.md).
    static constexpr uint64_t kOpenEndedPathsPerPixel = 100;
    /// Photon cone angle at the end of a plan of P paths: kConeAngleScale x P^(-1/5) radians
    /// (photonConeAngle; the model in docs/algorithm.md, "The photon cone").
    static constexpr double kConeAngleScale = 3.3;
    /// The automatic cone is on only where the first beam radius of the plan (kStartOverEnd end
    /// radii) exceeds this many pixel footprints at the light's depth (pointLightNearTheImage's
    /// `wider`): the early passes' blur of the light's glow stays in the mean of the whole render
    /// (docs/algorithm.md, "The photon cone").
    static constexpr double kConeMinLightFootprints = 1.0;
};

/// The photon cone's angle (radians) at the end of a plan of `plannedPaths` photon paths.
double photonConeAngle(uint64_t plannedPaths);

/// True when a point or spot light lies in the camera's image or within `reach` (scene units) of
/// the frustum's sides at its depth, or within `reach` of the eye: where the automatic photon
/// cone is turned on (elsewhere it would only split beams no camera ray passes close to the light).
/// With `wider` > 0 a light counts only where `wider` exceeds the pixel footprint at the light's
/// depth (its path length, for pointLightSeenInAMirror): a kernel no wider than the light's own pixel
/// blurs its glow no more than the pixel does, and the cone would only add beams and variance.
bool pointLightNearTheImage(const Scene& scene, int width, int height, double reach, double wider = 0);

/// True when a point or spot light is seen in a smooth mirror: a grid of camera rays (at most 64 x 64,
/// pinhole), reflected by smooth mirrors up to 4 times (passing through index-matched Interfaces),
/// passes after a reflection within `reach` of the light plus the grid's spacing at that path length
/// (the light's reflection can fall between two rays; exact for flat mirrors, curved ones spread the
/// rays and can hide a light between them). pointLightNearTheImage sees the light itself, not its
/// mirror image; a light seen in a mirror has a glow in view all the same.
bool pointLightSeenInAMirror(const EmbreeScene& rt, int width, int height, double reach, double wider = 0);

/// True when any radius setting (radii, offset, photon cone angle) is left automatic.
bool hasAutomaticRadii(const RenderSettings& s);

/// The photon-path count the automatic radii plan for: settings.plannedPaths when set, else
/// passes x photons without a time budget, else (time budget, or a pass count too large to plan
/// for such as the viewer's "until stopped") the open-ended horizon for the image size.
uint64_t plannedPhotonPaths(const RenderSettings& s);

/// `s` with the scene-relative radii Tyndall used before the automatic ones
/// (RadiusDefaults::kSceneRelative*: the first beam radius 0.5% and the surface radius 2% of the
/// scene's diagonal, offset 1000; the photon cone angle is left as it is). build/bench/
/// tyndall_quality's LEGACY row, and tests whose bounds were measured with these radii rather
/// than with the defaults of the day.
RenderSettings withSceneRelativeRadii(RenderSettings s, const Scene& scene);

/// `s` with every automatic radius setting replaced by its value for `rt`'s scene and camera
/// (and plannedPaths filled in when anything was automatic); `s` unchanged when nothing is.
RenderSettings resolveRadiusDefaults(const RenderSettings& s, const EmbreeScene& rt);

}  // namespace tyndall
