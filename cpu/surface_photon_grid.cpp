#include "cpu/surface_photon_grid.h"

#include <algorithm>
#include <cmath>

namespace tyndall {

SurfacePhotonGrid::SurfacePhotonGrid(const std::vector<SurfacePhoton>& photons) : m_photons(photons) {
    if (photons.empty()) {
        m_cellStart.assign(2, 0);
        return;
    }
    Bounds3 b;
    for (const SurfacePhoton& p : photons) {
        b.extend(p.position);
        m_maxRadius = std::max(m_maxRadius, p.radius);
    }
    m_origin = b.lo;
    // Cells as wide as the largest photon radius, but never so small that a cell index along the
    // photons' extent passes 2^20 (relative, so a scene in millimetres or kilometres hashes alike).
    const Vec3 extent = b.hi - b.lo;
    const float span = std::max(extent.x, std::max(extent.y, extent.z));
    m_cellSize = std::max(m_maxRadius, span * 0x1p-20f);
    if (!(m_cellSize > 0)) m_cellSize = 1.0f;  // one photon, radius 0: any cell size will do
    m_extentCells = extent / m_cellSize;
    m_buckets = 1;
    while (m_buckets < 2 * photons.size()) m_buckets <<= 1;
    std::vector<uint32_t> counts(m_buckets + 1, 0);
    std::vector<uint32_t> bucketOf(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) {
        Vec3 c = (photons[i].position - m_origin) / m_cellSize;
        bucketOf[i] = cellHash(int(std::floor(c.x)), int(std::floor(c.y)), int(std::floor(c.z)));
        counts[bucketOf[i] + 1]++;
    }
    for (uint32_t i = 0; i < m_buckets; ++i) counts[i + 1] += counts[i];
    m_cellStart = counts;
    m_sorted.resize(photons.size());
    for (size_t i = 0; i < photons.size(); ++i) m_sorted[counts[bucketOf[i]]++] = photons[i];
    m_candidates.resize(photons.size());
    for (size_t i = 0; i < m_sorted.size(); ++i) m_candidates[i] = {m_sorted[i].position, m_sorted[i].radius};
}

uint32_t SurfacePhotonGrid::cellHash(int x, int y, int z) const {
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u;
    return h & (m_buckets - 1);
}

int SurfacePhotonGrid::bucketsNear(const Vec3& x, const Vec3& n, uint32_t* buckets) const {
    // In cell units (cells [i, i+1]); the reach is r_max (<= 1 cell), padded so that float
    // rounding of a photon's cell index can never drop a cell that holds an accepted photon: a
    // few ulps of the cell coordinate (< 0.5 cell, as indices stay below 2^20), so <= 5 cells a side.
    const Vec3 c = (x - m_origin) / m_cellSize;
    // Farther than a cell (> r_max) outside the photons' bounds, or not a number: nothing near.
    if (!(c.x >= -2.0f && c.y >= -2.0f && c.z >= -2.0f && c.x <= m_extentCells.x + 2.0f &&
          c.y <= m_extentCells.y + 2.0f && c.z <= m_extentCells.z + 2.0f))
        return 0;
    const float reach = std::min(1.0f, m_maxRadius / m_cellSize);
    const float pad = 1e-3f + 4e-7f * std::max(std::abs(c.x), std::max(std::abs(c.y), std::abs(c.z)));
    const float ballReach = reach + pad, slabReach = 0.25f * reach + pad;
    const float cellHalfWidth = 0.5f * (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));  // along n
    const int x0 = int(std::floor(c.x - ballReach)), x1 = int(std::floor(c.x + ballReach));
    const int y0 = int(std::floor(c.y - ballReach)), y1 = int(std::floor(c.y + ballReach));
    const int z0 = int(std::floor(c.z - ballReach)), z1 = int(std::floor(c.z + ballReach));
    auto gap = [](float lo, float v) { return std::max(0.0f, std::max(lo - v, v - (lo + 1.0f))); };
    int count = 0;
    for (int iz = z0; iz <= z1; ++iz)
        for (int iy = y0; iy <= y1; ++iy)
            for (int ix = x0; ix <= x1; ++ix) {
                // The cell must meet the ball round x ...
                const float gx = gap(float(ix), c.x), gy = gap(float(iy), c.y), gz = gap(float(iz), c.z);
                if (gx * gx + gy * gy + gz * gz > ballReach * ballReach) continue;
                // ... and the slab round the plane through x.
                const Vec3 centre(float(ix) + 0.5f - c.x, float(iy) + 0.5f - c.y, float(iz) + 0.5f - c.z);
                if (std::abs(dot(centre, n)) - cellHalfWidth > slabReach) continue;
                const uint32_t h = cellHash(ix, iy, iz);
                if (std::find(buckets, buckets + count, h) != buckets + count) continue;  // a hash collision
                buckets[count++] = h;
            }
    return count;
}

Rgb SurfacePhotonGrid::density(const Vec3& x, const Vec3& n) const {
    Rgb sum;
    forEachNear(x, n, [&](const SurfacePhoton& p, float d2) {
        if (dot(p.normal, n) < 0.7f) return;  // same side of the surface
        sum += p.power * kernel(d2, p.radius);
    });
    return sum;
}

}  // namespace tyndall
