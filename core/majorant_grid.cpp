#include "core/majorant_grid.h"

#include <cmath>

namespace tyndall {

MajorantGrid::MajorantGrid(const Affine3& worldToCell, int nx, int ny, int nz)
    : m_worldToCell(worldToCell), m_res{nx, ny, nz}, m_cells(size_t(nx) * ny * nz, 0.0f) {}

void MajorantGrid::finish() {
    m_max = 0;
    for (float v : m_cells) m_max = std::max(m_max, v);
}

MajorantGrid::Walk MajorantGrid::walk(const Ray& ray, float tMin, float tMax) const {
    Walk w;
    w.m_grid = this;
    if (m_cells.empty() || !(tMin < tMax)) return w;
    const Vec3 o = m_worldToCell.point(ray.o), d = m_worldToCell.vector(ray.d);
    // Clip to the grid box [0, res] (slabs); a component of d that is 0 keeps the whole slab or none.
    float lo = tMin, hi = tMax;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0f) {
            if (o[a] < 0.0f || o[a] > float(m_res[a])) return w;
            continue;
        }
        float inv = 1.0f / d[a];
        float tn = (0.0f - o[a]) * inv, tf = (float(m_res[a]) - o[a]) * inv;
        if (tn > tf) std::swap(tn, tf);
        lo = std::max(lo, tn);
        hi = std::min(hi, tf);
    }
    if (!(lo < hi)) return w;
    const Vec3 p = o + d * lo;
    for (int a = 0; a < 3; ++a) {
        int c = int(std::floor(p[a]));
        c = clampValue(c, 0, m_res[a] - 1);
        w.m_cell[a] = c;
        if (d[a] > 0.0f) {
            w.m_step[a] = 1;
            w.m_tDelta[a] = 1.0f / d[a];
            w.m_tNext[a] = lo + (float(c + 1) - p[a]) / d[a];
        } else if (d[a] < 0.0f) {
            w.m_step[a] = -1;
            w.m_tDelta[a] = -1.0f / d[a];
            w.m_tNext[a] = lo + (float(c) - p[a]) / d[a];
        } else {
            w.m_step[a] = 0;
            w.m_tDelta[a] = kInfinity;
            w.m_tNext[a] = kInfinity;
        }
    }
    w.m_t = lo;
    w.m_tEnd = hi;
    return w;
}

float MajorantGrid::maxAlong(const Ray& ray, float tMin, float tMax) const {
    Walk w = walk(ray, tMin, tMax);
    float t0, t1, m, best = 0;
    while (w.next(&t0, &t1, &m)) best = std::max(best, m);
    return best;
}

}  // namespace tyndall
