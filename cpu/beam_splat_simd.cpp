// Highway kernels of cpu/beam_splat_simd.h. This file is compiled once per instruction set
// (hwy/foreach_target.h re-includes it); HWY_DYNAMIC_DISPATCH picks one at run time.
// Every formula mirrors BeamPixelEvaluator in cpu/beam_rasterizer.cpp operation by operation: keep
// the two in step (the tests compare them bit for bit where exp is not involved).
#include "cpu/beam_splat_simd.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "cpu/beam_splat_simd.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include "core/beam_estimator.h"

HWY_BEFORE_NAMESPACE();
namespace tyndall {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {
using D = hn::ScalableTag<float>;
using DI = hn::RebindToSigned<D>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// The closest approach of every lane's primary ray to the beam, as intersectBeamRay and the
/// scalar evaluator form it; `active` = contributes (same medium, not parallel, closest points
/// inside both segments, u < r).
struct Approach {
    V b, sin2, s, t, u2;
    M active;
};

HWY_INLINE Approach approach(D d, const SplatBeam& beam, const SplatBlock& blk, size_t i, size_t remaining) {
    const DI di;
    M active = hn::FirstN(d, remaining);
    active = hn::And(active, hn::RebindMask(d, hn::Eq(hn::LoadU(di, blk.medium.data() + i), hn::Set(di, beam.medium))));
    const V ox = hn::LoadU(d, blk.ox.data() + i), oy = hn::LoadU(d, blk.oy.data() + i),
            oz = hn::LoadU(d, blk.oz.data() + i);
    const V dx = hn::LoadU(d, blk.dx.data() + i), dy = hn::LoadU(d, blk.dy.data() + i),
            dz = hn::LoadU(d, blk.dz.data() + i);
    const V bx = hn::Set(d, beam.dir.x), by = hn::Set(d, beam.dir.y), bz = hn::Set(d, beam.dir.z);
    // w0 = ray.origin - beam.origin; dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
    const V w0x = hn::Sub(ox, hn::Set(d, beam.origin.x)), w0y = hn::Sub(oy, hn::Set(d, beam.origin.y)),
            w0z = hn::Sub(oz, hn::Set(d, beam.origin.z));
    auto dot = [](V ax, V ay, V az, V cx, V cy, V cz) {
        return hn::Add(hn::Add(hn::Mul(ax, cx), hn::Mul(ay, cy)), hn::Mul(az, cz));
    };
    Approach a;
    a.b = dot(dx, dy, dz, bx, by, bz);
    a.sin2 = hn::Sub(hn::Set(d, 1.0f), hn::Mul(a.b, a.b));
    active = hn::AndNot(hn::Lt(a.sin2, hn::Set(d, 1e-12f)), active);
    const V dd = dot(dx, dy, dz, w0x, w0y, w0z), e = dot(bx, by, bz, w0x, w0y, w0z);
    a.s = hn::Div(hn::Sub(hn::Mul(a.b, e), dd), a.sin2);
    a.t = hn::Div(hn::Sub(e, hn::Mul(a.b, dd)), a.sin2);
    const V zero = hn::Zero(d);
    active = hn::AndNot(hn::Or(hn::Lt(a.s, zero), hn::Gt(a.s, hn::LoadU(d, blk.tMax.data() + i))), active);
    active = hn::AndNot(hn::Or(hn::Lt(a.t, zero), hn::Gt(a.t, hn::Set(d, beam.tMax))), active);
    // between = (w0 + w_c s) - w_b t
    const V ex = hn::Sub(hn::Add(w0x, hn::Mul(dx, a.s)), hn::Mul(bx, a.t));
    const V ey = hn::Sub(hn::Add(w0y, hn::Mul(dy, a.s)), hn::Mul(by, a.t));
    const V ez = hn::Sub(hn::Add(w0z, hn::Mul(dz, a.s)), hn::Mul(bz, a.t));
    a.u2 = dot(ex, ey, ez, ex, ey, ez);
    a.active = hn::AndNot(hn::Ge(a.u2, hn::Set(d, beam.r2)), active);
    return a;
}

HWY_INLINE V invSinTheta(D d, V sin2) {
    return hn::Div(hn::Set(d, 1.0f), hn::Max(hn::Sqrt(sin2), hn::Set(d, kMinSinTheta)));
}
}  // namespace

void SplatSpanHomogeneous(const SplatBeam& beam, SplatBlock& blk, size_t first, size_t count) {
    const D d;
    const size_t n = hn::Lanes(d);
    const V one = hn::Set(d, 1.0f);
    for (size_t k = 0; k < count; k += n) {
        const size_t i = first + k;
        Approach a = approach(d, beam, blk, i, count - k);
        if (hn::AllFalse(d, a.active)) continue;
        // The kernel exactly as beamKernel() forms it, so coverage at the rim matches.
        const V x = hn::Div(hn::Sqrt(a.u2), hn::Set(d, beam.radius));
        const V ka = hn::Sub(one, hn::Mul(x, x));
        const M active = hn::And(a.active, hn::Gt(ka, hn::Zero(d)));
        const V denom = hn::Add(hn::Set(d, beam.hgB), hn::Mul(hn::Set(d, beam.hgC), a.b));
        const V phase =
            hn::Div(hn::Set(d, beam.hgA), hn::Mul(denom, hn::Sqrt(hn::Max(denom, hn::Set(d, 1e-12f)))));
        const V weight = hn::Div(hn::Mul(hn::Mul(hn::Mul(hn::Set(d, beam.kernelScale), ka), ka), phase),
                                 hn::Max(hn::Sqrt(a.sin2), hn::Set(d, kMinSinTheta)));
        const V l = hn::Add(a.s, a.t);
        V r, g, b;
        if (beam.grey) {
            const V we = hn::Mul(weight, hn::Exp(d, hn::Mul(hn::Set(d, -beam.sigmaT.r), l)));
            r = hn::Mul(hn::Set(d, beam.scaledPower.r), we);
            g = hn::Mul(hn::Set(d, beam.scaledPower.g), we);
            b = hn::Mul(hn::Set(d, beam.scaledPower.b), we);
        } else {
            r = hn::Mul(hn::Mul(hn::Set(d, beam.scaledPower.r), hn::Exp(d, hn::Mul(hn::Set(d, -beam.sigmaT.r), l))),
                        weight);
            g = hn::Mul(hn::Mul(hn::Set(d, beam.scaledPower.g), hn::Exp(d, hn::Mul(hn::Set(d, -beam.sigmaT.g), l))),
                        weight);
            b = hn::Mul(hn::Mul(hn::Set(d, beam.scaledPower.b), hn::Exp(d, hn::Mul(hn::Set(d, -beam.sigmaT.b), l))),
                        weight);
        }
        // Inactive lanes add exactly +0, as the scalar evaluator's Rgb() does.
        hn::StoreU(hn::Add(hn::LoadU(d, blk.sumR.data() + i), hn::IfThenElseZero(active, r)), d, blk.sumR.data() + i);
        hn::StoreU(hn::Add(hn::LoadU(d, blk.sumG.data() + i), hn::IfThenElseZero(active, g)), d, blk.sumG.data() + i);
        hn::StoreU(hn::Add(hn::LoadU(d, blk.sumB.data() + i), hn::IfThenElseZero(active, b)), d, blk.sumB.data() + i);
    }
}

void SplatSpanHeterogeneous(const SplatBeam& beam, const SplatBlock& blk, size_t first, size_t count,
                            SplatHits* hits) {
    const D d;
    const size_t n = hn::Lanes(d);
    const V one = hn::Set(d, 1.0f), zero = hn::Zero(d);
    hits->count = 0;
    for (std::vector<float>* v : {&hits->s, &hits->trCam, &hits->trBeam, &hits->weight})
        if (v->size() < count + n) v->resize(count + n);
    if (hits->pixel.size() < count + n) hits->pixel.resize(count + n);
    HWY_ALIGN float lane[5][64];
    for (size_t k = 0; k < count; k += n) {
        const size_t i = first + k;
        Approach a = approach(d, beam, blk, i, count - k);
        if (hn::AllFalse(d, a.active)) continue;
        // beamKernel(u, r) * hgPhase(-cos, g) * invSinTheta, as intersectBeamRay + beamRadiance.
        const V rv = hn::Set(d, beam.radius);
        const V x = hn::Div(hn::Sqrt(a.u2), rv);
        const V ka = hn::Sub(one, hn::Mul(x, x));
        const V kernel =
            hn::IfThenElseZero(hn::Gt(ka, zero), hn::Div(hn::Mul(hn::Mul(hn::Set(d, 15.0f / 16.0f), ka), ka), rv));
        const V denom = hn::Add(hn::Set(d, beam.hgB), hn::Mul(hn::Set(d, beam.hgC), a.b));
        const V phase =
            hn::Div(hn::Set(d, beam.hgA), hn::Mul(denom, hn::Sqrt(hn::Max(denom, hn::Set(d, 1e-12f)))));
        const V weight = hn::Mul(hn::Mul(kernel, phase), invSinTheta(d, a.sin2));
        // storedTransmittance: the fraction of stored distances beyond s (camera) and t (beam).
        V cam = zero, bm = zero;
        for (int j = 0; j < blk.freeFlightsPerRay; ++j)
            cam = hn::Add(cam, hn::IfThenElseZero(hn::Gt(hn::LoadU(d, blk.freeFlights.data() + j * blk.capacity + i), a.s), one));
        for (int j = 0; j < beam.freeFlightsPerBeam; ++j)
            bm = hn::Add(bm, hn::IfThenElseZero(hn::Gt(hn::Set(d, beam.freeFlights[j]), a.t), one));
        cam = hn::Div(cam, hn::Set(d, float(blk.freeFlightsPerRay)));
        bm = hn::Div(bm, hn::Set(d, float(beam.freeFlightsPerBeam)));
        const M active = hn::And(a.active, hn::And(hn::Gt(cam, zero), hn::Gt(bm, zero)));
        if (hn::AllFalse(d, active)) continue;
        hn::Store(hn::IfThenElseZero(active, one), d, lane[0]);
        hn::Store(a.s, d, lane[1]);
        hn::Store(cam, d, lane[2]);
        hn::Store(bm, d, lane[3]);
        hn::Store(weight, d, lane[4]);
        for (size_t j = 0; j < n && k + j < count; ++j) {
            if (lane[0][j] == 0.0f) continue;
            const size_t h = hits->count++;
            hits->pixel[h] = uint32_t(i + j);
            hits->s[h] = lane[1][j];
            hits->trCam[h] = lane[2][j];
            hits->trBeam[h] = lane[3][j];
            hits->weight[h] = lane[4][j];
        }
    }
}

const char* SplatTargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace tyndall
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tyndall {

HWY_EXPORT(SplatSpanHomogeneous);
HWY_EXPORT(SplatSpanHeterogeneous);
HWY_EXPORT(SplatTargetName);

void SplatBlock::reset(size_t pixels, int ffPerRay) {
    capacity = pixels + kPadding;
    for (std::vector<float>* v : {&ox, &oy, &oz, &dx, &dy, &dz, &tMax, &sumR, &sumG, &sumB}) v->assign(capacity, 0.0f);
    medium.assign(capacity, kVacuum);
    freeFlightsPerRay = ffPerRay;
    freeFlights.assign(capacity * size_t(ffPerRay), 0.0f);
}

void splatSpanHomogeneous(const SplatBeam& beam, SplatBlock& block, size_t first, size_t count) {
    HWY_DYNAMIC_DISPATCH(SplatSpanHomogeneous)(beam, block, first, count);
}

void splatSpanHeterogeneous(const SplatBeam& beam, const SplatBlock& block, size_t first, size_t count,
                            SplatHits* hits) {
    HWY_DYNAMIC_DISPATCH(SplatSpanHeterogeneous)(beam, block, first, count, hits);
}

const char* splatSimdTarget() { return HWY_DYNAMIC_DISPATCH(SplatTargetName)(); }

}  // namespace tyndall
#endif  // HWY_ONCE
