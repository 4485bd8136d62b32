#include "cpu/surface_boundary_clearance.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace tyndall {

namespace {
constexpr int kMaxCellsPerSide = 128;
constexpr size_t kMaxCells = size_t(1) << 22;
constexpr int kFar = 255;
}  // namespace

EdgeClearanceGrid::EdgeClearanceGrid(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Bounds3& domain) {
    if (a.empty()) {
        m_noSegments = true;
        return;
    }
    if (domain.empty()) return;
    const Vec3 ext = domain.diagonal();
    const float longest = std::max({ext.x, ext.y, ext.z});
    if (!(longest > 0) || !std::isfinite(longest)) return;
    // Cubic cells, the domain dilated by one cell on every side.
    float cell = longest / float(kMaxCellsPerSide - 2);
    size_t total = 0;
    for (;;) {
        total = 1;
        for (int k = 0; k < 3; ++k) {
            m_dims[k] = int(std::ceil(ext[k] / cell)) + 2;
            total *= size_t(m_dims[k]);
        }
        if (total <= kMaxCells) break;
        cell *= 1.25f;
    }
    m_cell = cell;
    m_invCell = 1.0f / cell;
    m_origin = domain.lo - Vec3(cell);

    // Float slack: the cell index of a query point and the distance test in coverage() are both
    // rounded; 5% of a cell plus a few ulps of the largest coordinate covers either.
    float maxAbs = 0;
    for (int k = 0; k < 3; ++k)
        maxAbs = std::max({maxAbs, std::abs(m_origin[k]), std::abs(m_origin[k] + cell * float(m_dims[k]))});
    const float slack = 0.05f * cell + 16.0f * FLT_EPSILON * maxAbs;
    for (int k = 1; k <= kFar; ++k) m_clearanceOf[k] = std::max(0.0f, float(k - 1) * cell - slack);

    m_cells.assign(total, uint8_t(kFar));
    const int nx = m_dims[0], ny = m_dims[1], nz = m_dims[2];
    auto cellIndex = [&](float v, int axis) {
        const float c = std::floor((v - m_origin[axis]) * m_invCell);
        // Clamped into the grid: a point outside is marked in the nearest border cell, which is
        // nearer every query point inside than the point itself.
        return int(std::clamp(c, 0.0f, float(m_dims[axis] - 1)));
    };
    for (size_t i = 0; i < a.size(); ++i) {
        const Vec3 d = b[i] - a[i];
        const int pieces = std::max(1, int(std::min(1e6f, std::ceil(length(d) * m_invCell))));
        for (int p = 0; p < pieces; ++p) {
            const Vec3 p0 = a[i] + d * (float(p) / float(pieces)), p1 = p == pieces - 1 ? b[i] : a[i] + d * (float(p + 1) / float(pieces));
            const Vec3 lo = vmin(p0, p1) - Vec3(0.01f * cell), hi = vmax(p0, p1) + Vec3(0.01f * cell);
            const int x0 = cellIndex(lo.x, 0), x1 = cellIndex(hi.x, 0), y0 = cellIndex(lo.y, 1), y1 = cellIndex(hi.y, 1);
            const int z0 = cellIndex(lo.z, 2), z1 = cellIndex(hi.z, 2);
            for (int z = z0; z <= z1; ++z)
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x) m_cells[(size_t(z) * ny + y) * nx + x] = 0;
        }
    }

    // Chebyshev distance transform: two raster sweeps with the 26-neighbourhood, unit steps
    // (exact for the chessboard metric).
    auto sweep = [&](int s) {  // s = -1: forward (neighbours before), +1: backward
        const int zb = s < 0 ? 0 : nz - 1, yb = s < 0 ? 0 : ny - 1, xb = s < 0 ? 0 : nx - 1;
        for (int zi = 0; zi < nz; ++zi) {
            const int z = s < 0 ? zi : zb - zi;
            for (int yi = 0; yi < ny; ++yi) {
                const int y = s < 0 ? yi : yb - yi;
                for (int xi = 0; xi < nx; ++xi) {
                    const int x = s < 0 ? xi : xb - xi;
                    uint8_t& v = m_cells[(size_t(z) * ny + y) * nx + x];
                    if (v == 0) continue;
                    int best = v;
                    auto take = [&](int dx, int dy, int dz) {
                        const int X = x + dx, Y = y + dy, Z = z + dz;
                        if (X < 0 || Y < 0 || Z < 0 || X >= nx || Y >= ny || Z >= nz) return;
                        best = std::min(best, int(m_cells[(size_t(Z) * ny + Y) * nx + X]) + 1);
                    };
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) take(dx, dy, s);  // the slab already swept
                    for (int dx = -1; dx <= 1; ++dx) take(dx, s, 0);
                    take(s, 0, 0);
                    v = uint8_t(std::min(best, kFar));
                }
            }
        }
    };
    sweep(-1);
    sweep(+1);
}

}  // namespace tyndall
