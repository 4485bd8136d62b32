#pragma once
// The scene's media as the GL splatter reads them (gpu/gl_layout.h): one GlMedium per
// Scene::media entry, and for each grid medium its dense density volume (core/density_volume.h)
// appended to one voxel array. Built on the CPU, uploaded by GlBeamSplatter.
#include <vector>

#include "core/scene.h"
#include "gpu/gl_layout.h"

namespace tyndall {

struct GlMediaTable {
    std::vector<GlMedium> media;
    std::vector<GlVolume> volumes;
    std::vector<float> voxels;
};

/// Throws Error naming the medium when a grid medium has no dense form of at most `maxVoxels`
/// voxels in all (DensityGrid::denseVolume).
GlMediaTable buildMediaTable(const Scene& scene, size_t maxVoxels);

}  // namespace tyndall
