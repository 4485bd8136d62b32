#pragma once
// The built-in heterogeneous scene: the default caustic box (loading/default_scene.h) with its fog
// replaced by the procedural OpenVDB smoke plume (loading/procedural_media.h), which the glass
// sphere's focused spot beam cuts through. Used by `tyndall compare` without a scene and by the
// benchmark's heterogeneous case. Needs no files.
#include <vector>

#include "core/scene.h"

namespace tyndall {

Scene makeDefaultSmokeScene();

/// The homogeneous twin of `scene` for side-by-side comparison: every density-grid medium
/// becomes homogeneous with the same albedo and g and coefficients scaled by `density` (< 0 = the
/// grid's mean over its active region). `used`, when given, receives the density used for each
/// converted medium, in Scene::media order. Throws Error when the scene has no density-grid medium.
Scene makeHomogeneousTwin(const Scene& scene, float density = -1.0f, std::vector<float>* used = nullptr);

}  // namespace tyndall
