#pragma once
// A coarse grid of density upper bounds for delta and ratio tracking (the "majorant grid"): a
// ray walks it with a 3D DDA (Amanatides & Woo 1987) and sees a piecewise-constant majorant that
// hugs the density, so thin and empty regions cost few tentative collisions.
//
// The grid has its own cell space, an affine image of world space: cell (i, j, k) is the box
// [i, i+1] x [j, j+1] x [k, k+1], and worldToCell maps world points there. Contract for whoever
// fills it (loading/vdb_grid.cpp, the analytic test grids): at(i, j, k) bounds the density at every
// world point whose cell coordinates lie in that closed box, with margin for float rounding at the
// faces; the density is zero outside [0, nx] x [0, ny] x [0, nz]. Read-only after construction,
// so any number of threads may walk it at once.
#include <vector>

#include "core/affine3.h"
#include "core/math.h"

namespace tyndall {

class MajorantGrid {
public:
    MajorantGrid() = default;
    /// All cells zero; fill with at() and then call finish().
    MajorantGrid(const Affine3& worldToCell, int nx, int ny, int nz);

    float& at(int i, int j, int k) { return m_cells[(size_t(k) * m_res[1] + j) * m_res[0] + i]; }
    float at(int i, int j, int k) const { return m_cells[(size_t(k) * m_res[1] + j) * m_res[0] + i]; }
    /// Computes maxValue() once the cells are filled.
    void finish();

    int resolution(int axis) const { return m_res[axis]; }
    size_t cellCount() const { return m_cells.size(); }
    float maxValue() const { return m_max; }
    const Affine3& worldToCell() const { return m_worldToCell; }

    /// The segments of ray.o + t ray.d, t in [tMin, tMax], inside the grid, in increasing t, each
    /// with its cell's majorant. Parts of the ray outside the grid are skipped (density 0 there).
    class Walk {
    public:
        /// Next segment [*t0, *t1] with majorant *majorant; false when the ray has left the grid.
        bool next(float* t0, float* t1, float* majorant);

    private:
        friend class MajorantGrid;
        const MajorantGrid* m_grid = nullptr;
        int m_cell[3] = {0, 0, 0};
        int m_step[3] = {0, 0, 0};
        float m_tNext[3] = {0, 0, 0};
        float m_tDelta[3] = {0, 0, 0};
        float m_t = 0, m_tEnd = -1;
    };
    Walk walk(const Ray& ray, float tMin, float tMax) const;

    /// Maximum majorant along the segment (a single bound for the whole segment).
    float maxAlong(const Ray& ray, float tMin, float tMax) const;

private:
    Affine3 m_worldToCell;
    int m_res[3] = {0, 0, 0};
    std::vector<float> m_cells;
    float m_max = 0;
};

inline bool MajorantGrid::Walk::next(float* t0, float* t1, float* majorant) {
    if (!(m_t < m_tEnd)) return false;
    int axis = m_tNext[0] < m_tNext[1] ? (m_tNext[0] < m_tNext[2] ? 0 : 2) : (m_tNext[1] < m_tNext[2] ? 1 : 2);
    float exit = std::min(std::max(m_tNext[axis], m_t), m_tEnd);
    *t0 = m_t;
    *t1 = exit;
    *majorant = m_grid->at(m_cell[0], m_cell[1], m_cell[2]);
    m_t = exit;
    m_cell[axis] += m_step[axis];
    m_tNext[axis] += m_tDelta[axis];
    if (m_cell[axis] < 0 || m_cell[axis] >= m_grid->m_res[axis]) m_tEnd = m_t;  // left the grid
    return true;
}

}  // namespace tyndall
