#pragma once
// The camera's pixel footprint where the image's media and surfaces are: what the default photon
// radii are measured in (docs/algorithm.md, "Where the radius sits"). A pixel at depth z (along the
// view direction) spans z * 2 tan(yFov / 2) / height scene units, so a radius given in footprints
// is independent of the scene's scale and of the image's size.
//
// Measured by a fixed grid of pinhole rays through the film (no randomness: a pure function of
// scene, camera and image size). Along each ray, up to its first surface (or the scene bounds),
// points at regular spacing that lie in a scattering medium vote, weighted by the ray length they
// stand for, for the footprint at their depth; the medium footprint is the weighted median. The
// surface footprint is the median over the rays' first hits. Thin-lens blur and the media seen
// through mirrors and glass are not counted (the primary rays dominate the image).
#include "core/camera.h"
#include "cpu/embree_scene.h"

namespace tyndall {

struct PixelFootprint {
    double media = 0;    ///< scene units per pixel at the media's median depth; 0 = no medium seen
    double surface = 0;  ///< scene units per pixel at the surfaces' median depth; 0 = nothing hit
    double mediaFraction = 0;  ///< share of the grid's rays that cross a scattering medium

    /// The footprint the beam radius is measured in: media's, else the surfaces', else `fallback`.
    double beam(double fallback) const { return media > 0 ? media : (surface > 0 ? surface : fallback); }
    /// The footprint the surface-photon radius is measured in: surfaces', else media's, else `fallback`.
    double surfaces(double fallback) const { return surface > 0 ? surface : (media > 0 ? media : fallback); }
};

/// Footprints for `camera` on a width x height film, from a grid of at most `gridSize`^2 rays.
PixelFootprint measurePixelFootprint(const EmbreeScene& rt, const Camera& camera, int width, int height,
                                     int gridSize = 24);

}  // namespace tyndall
