#pragma once
// The boundary's pre-check (cpu/surface_boundary.h): a lower bound on the distance from a point to
// the nearest feature half-edge, from a uniform grid, so that a gather point farther than its
// kernel radius from every edge (most of them: the coverage there is exactly 1) skips the Embree
// point query.
//
// Each cell stores k, the Chebyshev distance in cells (capped at 255) to the nearest cell that a
// segment touches; every point of a cell k cells away is at least (k - 1) cell widths from every
// segment along some axis, so (k - 1) x cell width, less a slack for the float arithmetic, is a
// lower bound on its Euclidean distance. Segments are marked piecewise (pieces at most a cell
// long, each piece's box dilated by 1% of a cell), so a long diagonal edge marks the cells along
// it, not its whole bounding box. The grid covers the box the gather points lie in (the
// photon-holding triangles); outside it the bound is 0 (no skip), so the test is conservative
// everywhere and the coverage, hence the image, is bit for bit the same as without it.
//
// The cells are cubes, at most 96 across the box's longest side and 2^22 in all (4 MiB);
// building is linear in the cells plus the segments' lengths in cells.
#include <cstdint>
#include <vector>

#include "core/math.h"

namespace tyndall {

class EdgeClearanceGrid {
public:
    EdgeClearanceGrid() = default;
    /// Segments (a[i], b[i]); queries are answered inside `domain` (dilated by a cell).
    EdgeClearanceGrid(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Bounds3& domain);

    /// A lower bound on min_i distance(x, segment i); 0 outside the grid (or with no grid),
    /// infinity with no segments.
    float clearance(const Vec3& x) const {
        if (m_noSegments) return kInfinity;
        if (m_cells.empty()) return 0.0f;
        int idx[3];
        for (int k = 0; k < 3; ++k) {
            const float c = (x[k] - m_origin[k]) * m_invCell;
            if (!(c >= 0.0f) || !(c < float(m_dims[k]))) return 0.0f;  // NaN too
            idx[k] = int(c);
        }
        return m_clearanceOf[m_cells[(size_t(idx[2]) * m_dims[1] + idx[1]) * m_dims[0] + idx[0]]];
    }

    /// The cell holding x (false outside the grid): its index, and the centre and radius of a
    /// sphere holding every point the index can be computed for (the cell, plus the float slack).
    bool cellOf(const Vec3& x, size_t* index, Vec3* centre, float* radius) const {
        if (m_cells.empty()) return false;
        int idx[3];
        for (int k = 0; k < 3; ++k) {
            const float c = (x[k] - m_origin[k]) * m_invCell;
            if (!(c >= 0.0f) || !(c < float(m_dims[k]))) return false;
            idx[k] = int(c);
        }
        *index = (size_t(idx[2]) * m_dims[1] + idx[1]) * m_dims[0] + idx[0];
        *centre = m_origin + Vec3(float(idx[0]) + 0.5f, float(idx[1]) + 0.5f, float(idx[2]) + 0.5f) * m_cell;
        *radius = 0.8660254f * m_cell + m_slack;
        return true;
    }

    float cellSize() const { return m_cell; }
    size_t cellCount() const { return m_cells.size(); }
    size_t memoryBytes() const { return m_cells.capacity(); }

private:
    std::vector<uint8_t> m_cells;  ///< Chebyshev distance in cells to the nearest touched cell
    float m_clearanceOf[256] = {};  ///< lower bound on the distance, per cell value
    Vec3 m_origin;
    float m_cell = 0, m_invCell = 0, m_slack = 0;
    int m_dims[3] = {0, 0, 0};
    bool m_noSegments = false;
};

}  // namespace tyndall
