#include "gpu/media_table.h"

#include "core/error.h"

namespace tyndall {

GlMediaTable buildMediaTable(const Scene& scene, size_t maxVoxels) {
    GlMediaTable table;
    for (const Medium& m : scene.media) {
        GlMedium g{};
        Rgb st = m.sigmaT();
        g.sigmaS = {m.sigmaS.r, m.sigmaS.g, m.sigmaS.b};
        g.sigmaT = {st.r, st.g, st.b};
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
            for (int r = 0; r < 3; ++r) {
                const auto& row = dense.worldToIndex[r];
                v.worldToIndex[r] = {row[0], row[1], row[2], row[3]};
            }
            v.size = {dense.nx, dense.ny, dense.nz};
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
