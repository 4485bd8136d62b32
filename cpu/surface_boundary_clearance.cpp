#include "cpu/surface_boundary_clearance.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace tyndall {

namespace {
constexpr int kMaxCellsPerSide = 96;
constexpr size_t kMaxCells = size_t(1) << 22;
constexpr int kFar = 255;

/// p[0..n+1] = the row src[0..n-1] + 1 (255 stays 255), with a far cell on either side.
void plusOnePadded(const uint8_t* __restrict src, uint8_t* __restrict p, int n) {
    p[0] = p[n + 1] = uint8_t(kFar);
    for (int x = 0; x < n; ++x) p[x + 1] = uint8_t(src[x] + (src[x] != kFar));
}

/// v[x] = min(v[x], the 12 p_k[x .. x+2]): the neighbours of x in four padded rows.
void minOfRows(uint8_t* __restrict v, const uint8_t* __restrict p0, const uint8_t* __restrict p1,
               const uint8_t* __restrict p2, const uint8_t* __restrict p3, int n) {
    for (int x = 0; x < n; ++x) {
        uint8_t m = v[x];
        m = std::min(m, std::min(std::min(p0[x], p0[x + 1]), p0[x + 2]));
        m = std::min(m, std::min(std::min(p1[x], p1[x + 1]), p1[x + 2]));
        m = std::min(m, std::min(std::min(p2[x], p2[x + 1]), p2[x + 2]));
        m = std::min(m, std::min(std::min(p3[x], p3[x + 1]), p3[x + 2]));
        v[x] = m;
    }
}
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
    m_slack = slack;
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
    // (exact for the chessboard metric). Each sweep takes, per row, the minimum over the 12
    // neighbours in rows already swept (all x at once: the compiler vectorises it), then runs
    // along the row for the 13th (x - 1, or x + 1 backward), the same as the plain raster order.
    std::vector<uint8_t> far(size_t(nx) + 2, uint8_t(kFar));
    auto row = [&](int y, int z) -> const uint8_t* {  // with a far cell on either side
        return y < 0 || z < 0 || y >= ny || z >= nz ? far.data() + 1 : m_cells.data() + (size_t(z) * ny + y) * nx;
    };
    std::vector<uint8_t> padded[4];
    for (std::vector<uint8_t>& p : padded) p.resize(size_t(nx) + 2);
    auto sweep = [&](int s) {  // s = -1: forward (neighbours before), +1: backward
        for (int zi = 0; zi < nz; ++zi) {
            const int z = s < 0 ? zi : nz - 1 - zi;
            for (int yi = 0; yi < ny; ++yi) {
                const int y = s < 0 ? yi : ny - 1 - yi;
                uint8_t* v = m_cells.data() + (size_t(z) * ny + y) * nx;
                // The 12 neighbour rows: (y + dy, z + s) for dy in -1..1, and (y + s, z), each read
                // at x - 1, x, x + 1 through a copy padded with far cells.
                const uint8_t* rows[4] = {row(y - 1, z + s), row(y, z + s), row(y + 1, z + s), row(y + s, z)};
                for (int k = 0; k < 4; ++k) plusOnePadded(rows[k], padded[k].data(), nx);
                minOfRows(v, padded[0].data(), padded[1].data(), padded[2].data(), padded[3].data(), nx);
                if (s < 0) {
                    for (int x = 1; x < nx; ++x) v[x] = uint8_t(std::min(int(v[x]), v[x - 1] + 1));
                } else {
                    for (int x = nx - 2; x >= 0; --x) v[x] = uint8_t(std::min(int(v[x]), v[x + 1] + 1));
                }
            }
        }
    };
    sweep(-1);
    sweep(+1);
}

}  // namespace tyndall
