#include "gpu/media_table.h"

#include "core/error.h"

namespace tyndall {

GlMediaTable buildMediaTable(const Scene& scene, size_t maxVoxels) {
    GlMediaTable table;
    for (const Medium& m : scene.media) {
        GlMedium g{};
        Rgb st = m.sigmaT();
        for (int c = 0; c < 3; ++c) {
            g.sigmaS[c] = m.sigmaS[c];
            g.sigmaT[c] = st[c];
        }
        g.g = m.g;
        g.volume = -1;
        if (!m.homogeneous()) {
            DensityVolume dense;
            size_t left = maxVoxels - table.voxels.size();
            if (!m.density->denseVolume(&dense, left))
                throw Error("medium '" + m.name + "': its density grid has no dense voxel form of at most " +
                            std::to_string(left) + " voxels for the GL splatter");
            if (dense.voxelCount() != dense.voxels.size() || dense.voxelCount() > left)
                throw Error("medium '" + m.name + "': dense density volume has " + std::to_string(dense.voxels.size()) +
                            " voxels, expected " + std::to_string(dense.voxelCount()) + " (at most " +
                            std::to_string(left) + ")");
            GlVolume v{};
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c) v.worldToIndex[r][c] = dense.worldToIndex[r][c];
            v.size[0] = dense.nx;
            v.size[1] = dense.ny;
            v.size[2] = dense.nz;
            v.offset = uint32_t(table.voxels.size());
            table.voxels.insert(table.voxels.end(), dense.voxels.begin(), dense.voxels.end());
            g.volume = int32_t(table.volumes.size());
            table.volumes.push_back(v);
        }
        table.media.push_back(g);
    }
    return table;
}

}  // namespace tyndall
