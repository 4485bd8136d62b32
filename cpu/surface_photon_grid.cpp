#include "cpu/surface_photon_grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace tyndall {

SurfacePhotonGrid::SurfacePhotonGrid(const std::vector<SurfacePhoton>& photons) : m_photons(photons) {
    static std::atomic<uint64_t> grids{0};
    m_id = ++grids;
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
    m_shading.resize(photons.size());
    for (size_t i = 0; i < m_sorted.size(); ++i) {
        const SurfacePhoton& p = m_sorted[i];
        m_candidates[i] = {p.position, p.radius};
        const float r2 = p.radius * p.radius;
        m_shading[i] = {p.normal, p.radius, p.power, 2.0f / (kPi * r2)};
    }
}

uint32_t SurfacePhotonGrid::cellHash(int x, int y, int z) const {
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u ^ uint32_t(z) * 83492791u;
    return h & (m_buckets - 1);
}

int SurfacePhotonGrid::bucketsNear(const Vec3& x, const Vec3& n, uint32_t* buckets) const {
    (void)n;  // pruning cells by the slab round the plane was measured to pay nothing (photons lie
              // on surfaces: the cells it drops are empty anyway)
    // In cell units (cells [i, i+1], 2 r_max wide): the 2x2x2 block nearest to x covers the ball
    // of radius r_max (half a cell) round it.
    const Vec3 c = (x - m_origin) / m_cellSize;
    // Farther than a cell outside the photons' bounds, or not a number: nothing near (and no
    // float-to-int overflow below).
    if (!(c.x >= -1.0f && c.y >= -1.0f && c.z >= -1.0f && c.x <= m_extentCells.x + 1.0f &&
          c.y <= m_extentCells.y + 1.0f && c.z <= m_extentCells.z + 1.0f))
        return 0;
    const int x0 = int(std::floor(c.x - 0.5f)), y0 = int(std::floor(c.y - 0.5f)), z0 = int(std::floor(c.z - 0.5f));
    int count = 0;
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const uint32_t h = cellHash(x0 + dx, y0 + dy, z0 + dz);
                if (m_cellStart[h] == m_cellStart[h + 1]) continue;                     // empty
                if (std::find(buckets, buckets + count, h) != buckets + count) continue;  // a hash collision
                buckets[count++] = h;
            }
    std::sort(buckets, buckets + count);  // ascending photon order, like the cached regions
    return count;
}

SurfacePhotonGrid::Region* SurfacePhotonGrid::regionFor(const Vec3& x) const {
    thread_local RegionCache cache;
    if (cache.owner != m_id) cache.owner = m_id, cache.used = 0, cache.next = 0;
    for (int i = 0; i < cache.used; ++i) {
        Region& r = cache.regions[i];
        if (x.x >= r.lo.x && x.y >= r.lo.y && x.z >= r.lo.z && x.x <= r.hi.x && x.y <= r.hi.y && x.z <= r.hi.z)
            return &r;
    }
    // Same bounds check as bucketsNear: nothing near, and no float-to-int overflow.
    const Vec3 c = (x - m_origin) / m_cellSize;
    if (!(c.x >= -1.0f && c.y >= -1.0f && c.z >= -1.0f && c.x <= m_extentCells.x + 1.0f &&
          c.y <= m_extentCells.y + 1.0f && c.z <= m_extentCells.z + 1.0f))
        return nullptr;
    Region& r = cache.regions[cache.next];
    cache.next = (cache.next + 1) % RegionCache::kRegions;
    cache.used = std::min(cache.used + 1, RegionCache::kRegions);
    const Vec3 half(0.5f * m_maxRadius);
    r.lo = x - half;
    r.hi = x + half;
    fillRegion(r);
    return &r;
}

void SurfacePhotonGrid::fillRegion(Region& r) const {
    // The cells (2 r_max wide) overlapping the box grown by r_max: every photon within its radius
    // of the box lies in one of them.
    const Vec3 lo = (r.lo - Vec3(m_maxRadius) - m_origin) / m_cellSize;
    const Vec3 hi = (r.hi + Vec3(m_maxRadius) - m_origin) / m_cellSize;
    const int x0 = int(std::floor(lo.x)), y0 = int(std::floor(lo.y)), z0 = int(std::floor(lo.z));
    const int x1 = int(std::floor(hi.x)), y1 = int(std::floor(hi.y)), z1 = int(std::floor(hi.z));
    uint32_t buckets[64];
    int count = 0;
    size_t bound = 0;  // the buckets' photons: at most that many candidates
    for (int z = z0; z <= z1; ++z)
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const uint32_t h = cellHash(x, y, z);
                if (m_cellStart[h] == m_cellStart[h + 1]) continue;
                if (std::find(buckets, buckets + count, h) != buckets + count) continue;
                buckets[count++] = h;
                bound += m_cellStart[h + 1] - m_cellStart[h];
            }
    std::sort(buckets, buckets + count);
    // Room for every candidate and the padding the SIMD scan may read and write (never counted:
    // the scan masks lanes past `count`, whatever an earlier fill left there).
    const size_t room = bound + kPhotonScanPadding;
    if (r.index.size() < room) {
        for (std::vector<float>* v : {&r.x, &r.y, &r.z, &r.radius, &r.acceptedD2}) v->resize(room, 0.0f);
        r.index.resize(room), r.accepted.resize(room);
    }
    float *px = r.x.data(), *py = r.y.data(), *pz = r.z.data(), *pr = r.radius.data();
    uint32_t* index = r.index.data();
    size_t n = 0;
    for (int b = 0; b < count; ++b)
        for (uint32_t k = m_cellStart[buckets[b]]; k < m_cellStart[buckets[b] + 1]; ++k) {
            const Candidate& c = m_candidates[k];
            const Vec3 out = vmax(vmax(r.lo - c.position, c.position - r.hi), Vec3(0.0f));
            // A margin over the exact box distance: the scan applies the exact test.
            if (dot(out, out) > 1.0001f * c.radius * c.radius) continue;
            px[n] = c.position.x, py[n] = c.position.y, pz[n] = c.position.z, pr[n] = c.radius;
            index[n++] = k;
        }
    r.count = n;
}

Rgb SurfacePhotonGrid::density(const Vec3& x, const Vec3& n) const {
    // forEachNear's photons in its order, each as kernel() and gatherOver<true> weigh it.
    Rgb sum;
    if (m_photons.empty()) return sum;
    Region* r = regionFor(x);
    if (!r) return sum;
    const size_t found = scanPhotonCandidates(r->x.data(), r->y.data(), r->z.data(), r->radius.data(),
                                              r->count, x, n, r->accepted.data(), r->acceptedD2.data());
    const Vec3 normal = n;
    const uint32_t* index = r->index.data();
    const uint32_t* accepted = r->accepted.data();
    const float* acceptedD2 = r->acceptedD2.data();
    for (size_t k = 0; k < found; ++k) {
        const Shading& p = m_shading[index[accepted[k]]];
        // Same side of the surface (a NaN passes, as it does in gatherOver).
        if (dot(p.normal, normal) < kSurfaceNormalAgreement) continue;
        const float r2 = p.radius * p.radius, d2 = acceptedD2[k];
        sum += p.power * (d2 < r2 ? p.kernelScale * (1.0f - d2 / r2) : 0.0f);
    }
    return sum;
}

}  // namespace tyndall
