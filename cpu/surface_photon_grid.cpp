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
    // Cells as wide as the largest photon diameter, but never so small that a cell index along the
    // photons' extent passes 2^20 (relative, so a scene in millimetres or kilometres hashes alike).
    const Vec3 extent = b.hi - b.lo;
    const float span = std::max(extent.x, std::max(extent.y, extent.z));
    m_cellSize = std::max(2.0f * m_maxRadius, span * 0x1p-20f);
    if (!(m_cellSize > 0)) m_cellSize = 1.0f;  // one photon, radius 0: any cell size will do
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
    for (size_t i = 0; i < m_sorted.size(); ++i)
        m_candidates[i] = {m_sorted[i].position, m_sorted[i].radius * m_sorted[i].radius};
}

uint32_t SurfacePhotonGrid::cellHash(int x, int y, int z) const {
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u;
    return h & (m_buckets - 1);
}

Rgb SurfacePhotonGrid::density(const Vec3& x, const Vec3& n) const {
    Rgb sum;
    if (m_photons.empty()) return sum;
    // Cells are 2 r_max wide, so the 2x2x2 block nearest to x covers the query ball.
    Vec3 c = (x - m_origin) / m_cellSize;
    int x0 = int(std::floor(c.x - 0.5f)), y0 = int(std::floor(c.y - 0.5f)), z0 = int(std::floor(c.z - 0.5f));
    uint32_t visited[8];
    int nVisited = 0;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                uint32_t h = cellHash(x0 + dx, y0 + dy, z0 + dz);
                if (std::find(visited, visited + nVisited, h) != visited + nVisited) continue;
                visited[nVisited++] = h;
                for (uint32_t k = m_cellStart[h]; k < m_cellStart[h + 1]; ++k) {
                    const Candidate& c = m_candidates[k];
                    Vec3 diff = c.position - x;
                    float d2 = dot(diff, diff);
                    if (d2 >= c.radius2) continue;
                    const SurfacePhoton& p = m_sorted[k];
                    // Same side of the surface, and close to its plane (no leaks round corners).
                    if (dot(p.normal, n) < 0.7f) continue;
                    if (std::abs(dot(diff, n)) > 0.25f * p.radius) continue;
                    sum += p.power * kernel(d2, p.radius);
                }
            }
    return sum;
}

}  // namespace tyndall
