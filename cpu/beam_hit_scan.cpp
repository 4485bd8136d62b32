// Highway kernel of cpu/beam_hit_scan.h. This file is compiled once per instruction set
// (hwy/foreach_target.h re-includes it); HWY_DYNAMIC_DISPATCH picks one at run time. Every formula
// mirrors intersectBeamRay (core/beam_estimator.h) operation by operation: keep the two in step.
#include "cpu/beam_hit_scan.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cpu/beam_hit_scan.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/highway.h>

#include "cpu/simd_mask_bits-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tyndall {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void ScanBeamHits(const BeamCandidates& c, const Vec3& o, const Vec3& wc, float sMax,
                  std::vector<BeamHitRecord>& hits) {
    const hn::ScalableTag<float> d;
    using V = hn::Vec<decltype(d)>;
    static_assert(hn::MaxLanes(d) <= BeamCandidates::kPadding, "padding too small for the widest vectors");
    HWY_ALIGN float lane[5][BeamCandidates::kPadding];
    const size_t lanes = hn::Lanes(d), count = c.size();
    const V ox = hn::Set(d, o.x), oy = hn::Set(d, o.y), oz = hn::Set(d, o.z);
    const V cx = hn::Set(d, wc.x), cy = hn::Set(d, wc.y), cz = hn::Set(d, wc.z);
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f), s1 = hn::Set(d, sMax);
    const V minSin = hn::Set(d, kMinSinTheta), tiny = hn::Set(d, 1e-12f);
    // dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z, as core/math.h forms it.
    auto dot = [](V ax, V ay, V az, V bx, V by, V bz) {
        return hn::Add(hn::Add(hn::Mul(ax, bx), hn::Mul(ay, by)), hn::Mul(az, bz));
    };
    for (size_t i = 0; i < count; i += lanes) {
        const V bx = hn::LoadU(d, c.dx.data() + i), by = hn::LoadU(d, c.dy.data() + i), bz = hn::LoadU(d, c.dz.data() + i);
        // w0 = xc - beam.origin
        const V w0x = hn::Sub(ox, hn::LoadU(d, c.ox.data() + i)), w0y = hn::Sub(oy, hn::LoadU(d, c.oy.data() + i)),
                w0z = hn::Sub(oz, hn::LoadU(d, c.oz.data() + i));
        const V b = dot(cx, cy, cz, bx, by, bz);
        const V sin2 = hn::Sub(one, hn::Mul(b, b));
        const V dd = dot(cx, cy, cz, w0x, w0y, w0z), e = dot(bx, by, bz, w0x, w0y, w0z);
        const V s = hn::Div(hn::Sub(hn::Mul(b, e), dd), sin2);
        const V t = hn::Div(hn::Sub(e, hn::Mul(b, dd)), sin2);
        // between = (w0 + wc s) - w_b t
        const V ex = hn::Sub(hn::Add(w0x, hn::Mul(cx, s)), hn::Mul(bx, t));
        const V ey = hn::Sub(hn::Add(w0y, hn::Mul(cy, s)), hn::Mul(by, t));
        const V ez = hn::Sub(hn::Add(w0z, hn::Mul(cz, s)), hn::Mul(bz, t));
        const V u2 = dot(ex, ey, ez, ex, ey, ez);
        // The scalar test's rejections, each false for a NaN as there.
        auto reject = hn::Or(hn::Lt(sin2, tiny), hn::Or(hn::Lt(s, zero), hn::Gt(s, s1)));
        reject = hn::Or(reject, hn::Or(hn::Lt(t, zero), hn::Gt(t, hn::LoadU(d, c.tMax.data() + i))));
        reject = hn::Or(reject, hn::Ge(u2, hn::LoadU(d, c.r2.data() + i)));
        const auto keep = hn::AndNot(reject, hn::FirstN(d, count - i));
        uint64_t bits = MaskBits(d, keep);
        if (!bits) continue;
        // std::max(sqrt(sin2), kMinSinTheta): sqrt(sin2) unless it is below the bound.
        const V sinTheta = hn::Sqrt(sin2);
        const V clamped = hn::IfThenElse(hn::Lt(sinTheta, minSin), minSin, sinTheta);
        hn::Store(hn::Sqrt(u2), d, lane[0]);
        hn::Store(s, d, lane[1]);
        hn::Store(t, d, lane[2]);
        hn::Store(b, d, lane[3]);
        hn::Store(hn::Div(one, clamped), d, lane[4]);
        do {
            const int j = __builtin_ctzll(bits);
            BeamHitRecord& h = hits.emplace_back();
            h.beam = c.beam[i + size_t(j)];
            h.hit.u = lane[0][j];
            h.hit.s = lane[1][j];
            h.hit.t = lane[2][j];
            h.hit.cosTheta = lane[3][j];
            h.hit.invSinTheta = lane[4][j];
            bits &= bits - 1;
        } while (bits);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace tyndall
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tyndall {

HWY_EXPORT(ScanBeamHits);

void BeamCandidates::assign(const std::vector<PhotonBeam>& beams, const std::vector<uint32_t>& indices) {
    beam = indices;
    const size_t n = indices.size() + kPadding;
    for (std::vector<float>* v : {&ox, &oy, &oz, &dx, &dy, &dz, &tMax, &r2}) v->resize(n);
    for (size_t k = 0; k < indices.size(); ++k) {
        const PhotonBeam& b = beams[indices[k]];
        ox[k] = b.origin.x, oy[k] = b.origin.y, oz[k] = b.origin.z;
        dx[k] = b.dir.x, dy[k] = b.dir.y, dz[k] = b.dir.z;
        tMax[k] = b.tMax;
        r2[k] = b.radius * b.radius;
    }
    // Padding lanes: never read into a hit (masked), kept finite.
    for (size_t k = indices.size(); k < n; ++k) ox[k] = oy[k] = oz[k] = dx[k] = dy[k] = dz[k] = tMax[k] = r2[k] = 0.0f;
}

void scanBeamHits(const BeamCandidates& candidates, const Vec3& o, const Vec3& d, float sMax,
                  std::vector<BeamHitRecord>& hits) {
    HWY_DYNAMIC_DISPATCH(ScanBeamHits)(candidates, o, d, sMax, hits);
}

void scanBeamHitsScalar(const BeamCandidates& candidates, const std::vector<PhotonBeam>& beams, const Vec3& o,
                        const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) {
    for (uint32_t b : candidates.beam) {
        BeamRayHit h;
        if (intersectBeamRay(o, d, sMax, beams[b], &h)) hits.push_back({b, h});
    }
}

}  // namespace tyndall
#endif  // HWY_ONCE
