#pragma once
// The homogeneous twin of a scene with density-grid media, for `tyndall compare`, the viewer's
// --compare and the benchmark: the same scene with each grid medium made homogeneous (same albedo
// and g, coefficients x one density), rendered next to the original.
//
// Where the twin's medium sits (TwinRegion):
// - Support (default): the scene's global grid medium becomes a homogeneous medium inside one
//   axis-aligned box, clear air (vacuum) outside. The box is the world bounding box of the grid's
//   support (the positive voxels plus the one voxel the trilinear stencil reaches), grown to hold
//   whole every transmissive or emissive mesh that sits in the medium and crosses it (so each such
//   mesh lies wholly inside or wholly outside), then clipped to the scene's bounds widened by
//   1e-4 of their diagonal (no face coplanar with a wall). The box is an invisible Interface mesh
//   "homogeneous twin hull". Its density is the grid's mean over the box: the integral of the
//   density over the box / the box's volume (DensityGrid::integratedDensity when the box holds the
//   whole support, integrateDensity otherwise), so the twin holds the same total amount of medium
//   in the same place, spread evenly.
// - Domain: the global medium stays global (the twin fills all space the grid's medium filled,
//   e.g. a whole room) at the grid's mean over its active voxels.
// A grid medium that fills a closed mesh (a mesh's interior medium) keeps filling that mesh in
// both modes, at the grid's mean over its active voxels. An explicit `density` >= 0 replaces the
// mean in every case.
//
// Emission: the twin's constant Le is the grid's Le weighted by density over the grid's support
// (clipped to the box in Support mode): Le_twin = integral of d Le / integral of d, the first by
// stratified sampling (one jittered point in each of 96^3 cells over the density's bounds, a fixed
// seed: unbiased, where a midpoint lattice of that size missed 3% of the campfire's power, whose
// blackbody peaks are narrower than its cells), the second the twin's own mass (Le without the
// medium's emissionScale, which the twin keeps: one scale drives both). Since the twin's sigma_a is sigma_a x its mean density, its
// source sigma_a Le_twin integrated over its region is the grid's integral of sigma_a d Le, the
// same emitted power 4 pi sigma_a d Le (Support mode with the mean density; in Domain mode or with
// an explicit density the power scales with the twin's mass as its extinction does). A grid
// medium with a constant `emission` keeps it.
#include <string>
#include <vector>

#include "core/scene.h"

namespace tyndall {

enum class TwinRegion { Support, Domain };

/// "support" / "domain"; parseTwinRegion throws Error naming the accepted words.
const char* twinRegionName(TwinRegion region);
TwinRegion parseTwinRegion(const std::string& text);

/// One converted medium of a twin: its index in Scene::media, the density used, and the box it
/// was confined to (empty when it fills its old domain).
struct TwinMedium {
    MediumId medium = kVacuum;
    float density = 0;
    Rgb emission{0.0f};  ///< the twin's Le (before emissionScale)
    Bounds3 box;
};

/// The twin of a finalized `scene` (see above). `used`, when given, receives the density used for
/// each converted medium in Scene::media order; `converted` the details. Throws Error when the
/// scene has no density-grid medium.
Scene makeHomogeneousTwin(const Scene& scene, float density = -1.0f, std::vector<float>* used = nullptr,
                          TwinRegion region = TwinRegion::Support, std::vector<TwinMedium>* converted = nullptr);

}  // namespace tyndall
