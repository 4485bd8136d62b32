// Highway kernel of cpu/surface_photon_scan.h. This file is compiled once per instruction set
// (hwy/foreach_target.h re-includes it); HWY_DYNAMIC_DISPATCH picks one at run time. The tests
// mirror SurfacePhotonGrid::forEachNearUncached's operation by operation: keep the two in step.
#include "cpu/surface_photon_scan.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cpu/surface_photon_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "cpu/simd_mask_bits-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tyndall {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

size_t ScanPhotonCandidates(const float* x, const float* y, const float* z, const float* radius, size_t count,
                            const Vec3& p, const Vec3& n, uint32_t* accepted, float* d2) {
    const hn::ScalableTag<float> d;
    HWY_ALIGN float lane[kPhotonScanPadding];
    static_assert(hn::MaxLanes(d) <= kPhotonScanPadding, "padding too small for the widest vectors");
    const size_t lanes = hn::Lanes(d);
    const auto px = hn::Set(d, p.x), py = hn::Set(d, p.y), pz = hn::Set(d, p.z);
    const auto nx = hn::Set(d, n.x), ny = hn::Set(d, n.y), nz = hn::Set(d, n.z);
    const auto quarter = hn::Set(d, 0.25f);
    size_t out = 0;
    for (size_t i = 0; i < count; i += lanes) {
        const auto dx = hn::Sub(hn::LoadU(d, x + i), px), dy = hn::Sub(hn::LoadU(d, y + i), py),
                   dz = hn::Sub(hn::LoadU(d, z + i), pz);
        const auto r = hn::LoadU(d, radius + i);
        // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z, as core/math.h forms it.
        const auto dd = hn::Add(hn::Add(hn::Mul(dx, dx), hn::Mul(dy, dy)), hn::Mul(dz, dz));
        const auto dn = hn::Add(hn::Add(hn::Mul(dx, nx), hn::Mul(dy, ny)), hn::Mul(dz, nz));
        const auto reject = hn::Or(hn::Ge(dd, hn::Mul(r, r)), hn::Gt(hn::Abs(dn), hn::Mul(quarter, r)));
        const auto keep = hn::AndNot(reject, hn::FirstN(d, count - i));
        // Few lanes pass (~a quarter): walk the mask's bits rather than compress (which AVX2
        // emulates with table lookups).
        uint64_t bits = MaskBits(d, keep);
        if (!bits) continue;
        hn::Store(dd, d, lane);
        do {
            const int j = __builtin_ctzll(bits);
            accepted[out] = uint32_t(i) + uint32_t(j);
            d2[out++] = lane[j];
            bits &= bits - 1;
        } while (bits);
    }
    return out;
}

}  // namespace HWY_NAMESPACE
}  // namespace tyndall
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <cmath>

namespace tyndall {

HWY_EXPORT(ScanPhotonCandidates);

size_t scanPhotonCandidates(const float* x, const float* y, const float* z, const float* radius, size_t count,
                            const Vec3& p, const Vec3& n, uint32_t* accepted, float* d2) {
    return HWY_DYNAMIC_DISPATCH(ScanPhotonCandidates)(x, y, z, radius, count, p, n, accepted, d2);
}

size_t scanPhotonCandidatesScalar(const float* x, const float* y, const float* z, const float* radius, size_t count,
                                  const Vec3& p, const Vec3& n, uint32_t* accepted, float* d2) {
    size_t out = 0;
    for (size_t i = 0; i < count; ++i) {
        const Vec3 diff(x[i] - p.x, y[i] - p.y, z[i] - p.z);
        const float dd = dot(diff, diff);
        if (dd >= radius[i] * radius[i]) continue;
        if (std::abs(dot(diff, n)) > 0.25f * radius[i]) continue;
        accepted[out] = uint32_t(i);
        d2[out++] = dd;
    }
    return out;
}

}  // namespace tyndall
#endif  // HWY_ONCE
