#pragma once
// Fixed-radius lookup of surface photons (progressive surface photon mapping): a hashed uniform
// grid with cells as wide as the largest photon diameter, photons stored in bucket order.
// The density estimate at a diffuse point x with normal n and albedo rho is
//   L = rho/pi * sum_p Phi_p K_2D(|x - x_p|, r_p)
// over photons on the same side of the surface (normal agreement) and near its plane, with the
// normalised 2D Epanechnikov kernel K(d, r) = 2/(pi r^2) (1 - d^2/r^2), each photon with its own
// (scheduled) radius.
//
// A lookup scans the 2x2x2 block of cells nearest to x (it covers the ball of radius r_max).
//
// Neighbouring camera paths look up nearly the same point, so each thread keeps the candidates of
// its last few regions (a box r_max wide round a lookup point: the photons within their own radius
// of the box, ascending) and a lookup inside such a box scans only those, without hashing, with
// Highway (cpu/surface_photon_scan.h: the scalar test's operations, 4-16 candidates at a time).
// Both ways visit the same photons in the same (ascending) order, so the sums are bit for bit the
// same whatever the cache held. The cache is one per thread (thread_local), keyed by the grid it
// holds regions of: a lookup in another grid starts it afresh.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/photon_beam.h"
#include "cpu/surface_photon_scan.h"

namespace tyndall {

class SurfacePhotonGrid {
public:
    /// Keeps a reference to `photons`: they must outlive the grid.
    explicit SurfacePhotonGrid(const std::vector<SurfacePhoton>& photons);

    /// sum_p Phi_p K_2D(|x - x_p|, r_p) for photons whose normal agrees with `n` (the side the
    /// query looks from); multiply by the BRDF (rho/pi) to get outgoing radiance. Bit for bit
    /// gatherFacing with a weight of exactly 1 for every photon (1 x Phi is Phi), from the photons'
    /// normals, powers and kernel factors kept apart (SoA) so that the loop reads no photon record.
    Rgb density(const Vec3& x, const Vec3& n) const;

    /// The largest photon radius (0 with no photons).
    float maxRadius() const { return m_maxRadius; }

    /// sum_p weight(p) Phi_p K_2D(|x - x_p|, r_p) over photons near the plane through x with normal
    /// n, from either side (|n_p . n| >= kSurfaceNormalAgreement): a glossy vertex evaluates its
    /// BSDF per photon (weight = f(wo, p.wi)), transmission included.
    template <class Weight>
    Rgb gather(const Vec3& x, const Vec3& n, const Weight& weight) const {
        return gatherOver<false>(x, n, weight);
    }
    /// gather over the photons on the side `n` faces alone (n_p . n >= kSurfaceNormalAgreement), as
    /// a diffuse end gathers: the same sum, bit for bit, as gather with a weight that returns 0
    /// where n_p . n < kSurfaceNormalAgreement, one dot product a photon instead of two.
    template <class Weight>
    Rgb gatherFacing(const Vec3& x, const Vec3& n, const Weight& weight) const {
        return gatherOver<true>(x, n, weight);
    }

    /// Calls visit(photon, d2) once for every photon within its own radius of x (d2 = |x - x_p|^2
    /// < r_p^2) and near the plane through x with unit normal n (|(x_p - x).n| <= r_p / 4), in
    /// an order fixed by the photons and x alone (ascending photon order). The query density()
    /// uses and gather() writes out. `visit` must not query a grid (it scans the thread's cached region).
    template <class Visit>
    void forEachNear(const Vec3& x, const Vec3& n, const Visit& visit) const;
    /// forEachNear without the per-thread cache (the definition the cache must reproduce).
    template <class Visit>
    void forEachNearUncached(const Vec3& x, const Vec3& n, const Visit& visit) const;

    static float kernel(float d2, float r) {
        float r2 = r * r;
        return d2 < r2 ? 2.0f / (kPi * r2) * (1.0f - d2 / r2) : 0.0f;
    }

private:
    /// gather (kFacing false) and gatherFacing (true). forEachNear's loop written out, its sum a
    /// local the compiler keeps in registers (a visitor's sum by reference was stored and the
    /// weight's captures reloaded at every photon); the same photons in the same order.
    template <bool kFacing, class Weight>
    Rgb gatherOver(const Vec3& x, const Vec3& n, const Weight& weight) const;

    static bool isZeroWeight(float w) { return w == 0.0f; }
    static bool isZeroWeight(const Rgb& w) { return w.isBlack(); }

    // The candidates of one box [lo, hi], structure of arrays (the scan reads four floats each),
    // padded by kPhotonScanPadding for the SIMD scan, and where the scan writes what it accepts.
    struct Region {
        Vec3 lo, hi;
        std::vector<float> x, y, z, radius;
        size_t count = 0;  // the candidates; the arrays are longer (kept between fills, padded)
        std::vector<uint32_t> index;  // into m_sorted, ascending
        std::vector<uint32_t> accepted;  // positions in the arrays above (scan output)
        std::vector<float> acceptedD2;
    };
    struct RegionCache {
        static constexpr int kRegions = 4;
        uint64_t owner = 0;  ///< the SurfacePhotonGrid::m_id the regions belong to
        Region regions[kRegions];
        int used = 0, next = 0;
    };
    /// The cached region holding x, or a new one round x (nullptr when x is outside the grid).
    Region* regionFor(const Vec3& x) const;
    void fillRegion(Region& r) const;

    uint32_t cellHash(int x, int y, int z) const;
    /// The distinct non-empty hash buckets of the cells that can hold a photon forEachNear(x, n)
    /// accepts; returns how many (<= 8).
    int bucketsNear(const Vec3& x, const Vec3& n, uint32_t* buckets) const;

    const std::vector<SurfacePhoton>& m_photons;
    // The photons in bucket order (a copy: a lookup streams through a bucket's photons instead of
    // chasing indices). Within a bucket, index order.
    std::vector<SurfacePhoton> m_sorted;
    // Position and radius of m_sorted[i], 16 bytes each: the scan that rejects most visited
    // photons reads only these, touching the full photon only for the few it accepts.
    struct Candidate {
        Vec3 position;
        float radius;
    };
    std::vector<Candidate> m_candidates;
    // What density() reads of m_sorted[i]: its normal, radius, power and kernel()'s factor
    // 2 / (pi r^2), computed once as kernel() computes it.
    struct Shading {
        Vec3 normal;
        float radius;
        Rgb power;
        float kernelScale;
    };
    std::vector<Shading> m_shading;
    std::vector<uint32_t> m_cellStart;  // per hash bucket: start in m_sorted (size buckets + 1)
    float m_cellSize = 1;
    float m_maxRadius = 0;
    Vec3 m_origin;
    Vec3 m_extentCells;  // the photons' bounds in cells, from m_origin
    uint32_t m_buckets = 1;
    uint64_t m_id;  ///< unique per grid: keys the per-thread region cache
};

template <class Visit>
void SurfacePhotonGrid::forEachNear(const Vec3& x, const Vec3& n, const Visit& visit) const {
    if (m_photons.empty()) return;
    Region* r = regionFor(x);
    if (!r) return;
    const size_t found = scanPhotonCandidates(r->x.data(), r->y.data(), r->z.data(), r->radius.data(),
                                              r->count, x, n, r->accepted.data(), r->acceptedD2.data());
    for (size_t k = 0; k < found; ++k) visit(m_sorted[r->index[r->accepted[k]]], r->acceptedD2[k]);
}

template <class Visit>
void SurfacePhotonGrid::forEachNearUncached(const Vec3& x, const Vec3& n, const Visit& visit) const {
    if (m_photons.empty()) return;
    uint32_t buckets[8];
    const int count = bucketsNear(x, n, buckets);
    for (int b = 0; b < count; ++b) {
        const uint32_t h = buckets[b];
        for (uint32_t k = m_cellStart[h]; k < m_cellStart[h + 1]; ++k) {
            const Candidate& c = m_candidates[k];
            const Vec3 diff = c.position - x;
            const float d2 = dot(diff, diff);
            if (d2 >= c.radius * c.radius) continue;
            if (std::abs(dot(diff, n)) > 0.25f * c.radius) continue;
            visit(m_sorted[k], d2);
        }
    }
}

template <bool kFacing, class Weight>
Rgb SurfacePhotonGrid::gatherOver(const Vec3& x, const Vec3& n, const Weight& weight) const {
    Rgb sum;
    if (m_photons.empty()) return sum;
    Region* r = regionFor(x);
    if (!r) return sum;
    const size_t found = scanPhotonCandidates(r->x.data(), r->y.data(), r->z.data(), r->radius.data(),
                                              r->count, x, n, r->accepted.data(), r->acceptedD2.data());
    const Vec3 normal = n;
    for (size_t k = 0; k < found; ++k) {
        const uint32_t index = r->index[r->accepted[k]];
        const SurfacePhoton& p = m_sorted[index];
        const float cosine = dot(p.normal, normal);
        // Either side (gather) or n's side (gatherFacing; NaN passes both tests, as it did).
        if (kFacing ? cosine < kSurfaceNormalAgreement : std::abs(cosine) < kSurfaceNormalAgreement) continue;
        const auto w = weight(p);
        // A zero weight adds +-0 (finite powers and kernels): the sum's bits stay as they are.
        if (isZeroWeight(w)) continue;
        // kernel(d2, r) with its 2 / (pi r^2) kept per photon (the same float operations).
        const float r2 = p.radius * p.radius, d2 = r->acceptedD2[k];
        sum += w * p.power * (d2 < r2 ? m_shading[index].kernelScale * (1.0f - d2 / r2) : 0.0f);
    }
    return sum;
}

}  // namespace tyndall
