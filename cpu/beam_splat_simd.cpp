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

/// One beam's constants in every lane, set up once per call rather than once per vector.
struct BeamLanes {
    V ox, oy, oz, bx, by, bz, tMax, r2;
    hn::Vec<DI> medium;
};

HWY_INLINE BeamLanes beamLanes(D d, const SplatBeam& beam) {
    const DI di;
    return BeamLanes{hn::Set(d, beam.origin.x), hn::Set(d, beam.origin.y), hn::Set(d, beam.origin.z),
                     hn::Set(d, beam.dir.x),    hn::Set(d, beam.dir.y),    hn::Set(d, beam.dir.z),
                     hn::Set(d, beam.tMax),     hn::Set(d, beam.r2),       hn::Set(di, beam.medium)};
}

/// The block's ray arrays, read once per call (stores to the sums could otherwise make every
/// vector reload them).
struct RayArrays {
    const float *ox, *oy, *oz, *dx, *dy, *dz, *tMax;
    const int32_t* medium;
};

HWY_INLINE RayArrays rayArrays(const SplatBlock& blk) {
    return RayArrays{blk.ox.data(), blk.oy.data(), blk.oz.data(),   blk.dx.data(),
                     blk.dy.data(), blk.dz.data(), blk.tMax.data(), blk.medium.data()};
}

struct SumArrays {
    float *r, *g, *b;
};

/// The closest approach of every lane's primary ray to the beam, as intersectBeamRay and the
/// scalar evaluator form it; `active` = contributes (same medium, not parallel, closest points
/// inside both segments, u < r).
struct Approach {
    V b, sin2, s, t, u2;
    M active;
};

HWY_INLINE Approach approach(D d, const BeamLanes& beam, const RayArrays& blk, size_t i, size_t remaining) {
    const DI di;
    M active = hn::FirstN(d, remaining);
    active = hn::And(active, hn::RebindMask(d, hn::Eq(hn::LoadU(di, blk.medium + i), beam.medium)));
    const V ox = hn::LoadU(d, blk.ox + i), oy = hn::LoadU(d, blk.oy + i), oz = hn::LoadU(d, blk.oz + i);
    const V dx = hn::LoadU(d, blk.dx + i), dy = hn::LoadU(d, blk.dy + i), dz = hn::LoadU(d, blk.dz + i);
    const V bx = beam.bx, by = beam.by, bz = beam.bz;
    // w0 = ray.origin - beam.origin; dot(a, b) = (a.x b.x + a.y b.y) + a.z b.z.
    const V w0x = hn::Sub(ox, beam.ox), w0y = hn::Sub(oy, beam.oy), w0z = hn::Sub(oz, beam.oz);
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
    active = hn::AndNot(hn::Or(hn::Lt(a.s, zero), hn::Gt(a.s, hn::LoadU(d, blk.tMax + i))), active);
    active = hn::AndNot(hn::Or(hn::Lt(a.t, zero), hn::Gt(a.t, beam.tMax)), active);
    // between = (w0 + w_c s) - w_b t
    const V ex = hn::Sub(hn::Add(w0x, hn::Mul(dx, a.s)), hn::Mul(bx, a.t));
    const V ey = hn::Sub(hn::Add(w0y, hn::Mul(dy, a.s)), hn::Mul(by, a.t));
    const V ez = hn::Sub(hn::Add(w0z, hn::Mul(dz, a.s)), hn::Mul(bz, a.t));
    a.u2 = dot(ex, ey, ez, ex, ey, ez);
    a.active = hn::AndNot(hn::Ge(a.u2, beam.r2), active);
    return a;
}

HWY_INLINE V invSinTheta(D d, V sin2) {
    return hn::Div(hn::Set(d, 1.0f), hn::Max(hn::Sqrt(sin2), hn::Set(d, kMinSinTheta)));
}

/// The homogeneous estimator's per-beam factors in every lane.
struct HomogeneousLanes {
    V radius, kernelScale, hgA, hgB, hgC, negSigmaR, negSigmaG, negSigmaB, powerR, powerG, powerB;
};

HWY_INLINE HomogeneousLanes homogeneousLanes(D d, const SplatBeam& beam) {
    return HomogeneousLanes{hn::Set(d, beam.radius),        hn::Set(d, beam.kernelScale),   hn::Set(d, beam.hgA),
                            hn::Set(d, beam.hgB),           hn::Set(d, beam.hgC),           hn::Set(d, -beam.sigmaT.r),
                            hn::Set(d, -beam.sigmaT.g),     hn::Set(d, -beam.sigmaT.b),     hn::Set(d, beam.scaledPower.r),
                            hn::Set(d, beam.scaledPower.g), hn::Set(d, beam.scaledPower.b)};
}

/// Adds the homogeneous estimator to block pixels [first, first + count).
HWY_INLINE void splatSpan(D d, const BeamLanes& beam, const HomogeneousLanes& h, bool grey, const RayArrays& rays,
                          const SumArrays& sums, size_t first, size_t count) {
    const size_t n = hn::Lanes(d);
    const V one = hn::Set(d, 1.0f);
    for (size_t k = 0; k < count; k += n) {
        const size_t i = first + k;
        Approach a = approach(d, beam, rays, i, count - k);
        if (hn::AllFalse(d, a.active)) continue;
        // The kernel exactly as beamKernel() forms it, so coverage at the rim matches.
        const V x = hn::Div(hn::Sqrt(a.u2), h.radius);
        const V ka = hn::Sub(one, hn::Mul(x, x));
        const M active = hn::And(a.active, hn::Gt(ka, hn::Zero(d)));
        const V denom = hn::Add(h.hgB, hn::Mul(h.hgC, a.b));
        const V phase = hn::Div(h.hgA, hn::Mul(denom, hn::Sqrt(hn::Max(denom, hn::Set(d, 1e-12f)))));
        const V weight = hn::Div(hn::Mul(hn::Mul(hn::Mul(h.kernelScale, ka), ka), phase),
                                 hn::Max(hn::Sqrt(a.sin2), hn::Set(d, kMinSinTheta)));
        const V l = hn::Add(a.s, a.t);
        V r, g, b;
        if (grey) {
            const V we = hn::Mul(weight, hn::Exp(d, hn::Mul(h.negSigmaR, l)));
            r = hn::Mul(h.powerR, we);
            g = hn::Mul(h.powerG, we);
            b = hn::Mul(h.powerB, we);
        } else {
            r = hn::Mul(hn::Mul(h.powerR, hn::Exp(d, hn::Mul(h.negSigmaR, l))), weight);
            g = hn::Mul(hn::Mul(h.powerG, hn::Exp(d, hn::Mul(h.negSigmaG, l))), weight);
            b = hn::Mul(hn::Mul(h.powerB, hn::Exp(d, hn::Mul(h.negSigmaB, l))), weight);
        }
        // Inactive lanes add exactly +0, as the scalar evaluator's Rgb() does.
        hn::StoreU(hn::Add(hn::LoadU(d, sums.r + i), hn::IfThenElseZero(active, r)), d, sums.r + i);
        hn::StoreU(hn::Add(hn::LoadU(d, sums.g + i), hn::IfThenElseZero(active, g)), d, sums.g + i);
        hn::StoreU(hn::Add(hn::LoadU(d, sums.b + i), hn::IfThenElseZero(active, b)), d, sums.b + i);
    }
}
}  // namespace

void SplatRowsHomogeneous(const SplatBeam& beam, SplatBlock& blk, size_t rowStride, const SplatRows& rows) {
    const D d;
    const BeamLanes lanes = beamLanes(d, beam);
    const HomogeneousLanes h = homogeneousLanes(d, beam);
    const RayArrays rays = rayArrays(blk);
    const SumArrays sums{blk.sumR.data(), blk.sumG.data(), blk.sumB.data()};
    for (int y = 0; y < rows.rows; ++y)
        if (rows.x0[y] <= rows.x1[y])
            splatSpan(d, lanes, h, beam.grey, rays, sums, size_t(y) * rowStride + size_t(rows.x0[y]),
                      size_t(rows.x1[y] - rows.x0[y] + 1));
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
    const BeamLanes lanes = beamLanes(d, beam);
    const RayArrays rays = rayArrays(blk);
    for (size_t k = 0; k < count; k += n) {
        const size_t i = first + k;
        Approach a = approach(d, lanes, rays, i, count - k);
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

// footprintRowSpan (cpu/beam_rasterizer.cpp) with one row per lane: the same float operations per
// row, so the same columns; min and max differ from std::min and std::max only in the sign of a
// zero, which the columns' rounding (x - 0.5, then ceil or floor) does not see.
size_t FootprintBandColumns(const BeamFootprint& fp, const FootprintSides& sides, int y0, int rowBegin, int rowEnd,
                            int colMin, int colMax, int width, SplatRows* out) {
    using DR = hn::CappedTag<float, SplatRows::kMaxRows>;
    const DR d;
    const hn::RebindToSigned<DR> di;
    using VR = hn::Vec<DR>;
    using MR = hn::Mask<DR>;
    const int n = int(hn::Lanes(d));
    out->rows = rowEnd - y0;
    auto pixels = hn::Zero(di);
    for (int i0 = 0; i0 < out->rows; i0 += n) {
        const auto row = hn::Add(hn::Iota(di, 0), hn::Set(di, y0 + i0));
        const VR y = hn::Add(hn::ConvertTo(d, row), hn::Set(d, 0.5f));  // float(y) + 0.5f
        const VR inf = hn::Set(d, kInfinity);
        VR lo = fp.fullScreen ? hn::Neg(inf) : inf, hi = fp.fullScreen ? inf : hn::Neg(inf);
        auto add = [&](MR m, VR x) {
            lo = hn::IfThenElse(m, hn::Min(lo, x), lo);
            hi = hn::IfThenElse(m, hn::Max(hi, x), hi);
        };
        auto disc = [&](float cx, float cy, float r) {
            const VR dy = hn::Sub(y, hn::Set(d, cy));
            const VR h2 = hn::Sub(hn::Set(d, r * r), hn::Mul(dy, dy));
            const MR m = hn::Not(hn::Lt(h2, hn::Zero(d)));
            const VR h = hn::Sqrt(hn::Max(h2, hn::Zero(d)));  // the max only keeps missed rows' lanes finite
            lo = hn::IfThenElse(m, hn::Min(lo, hn::Sub(hn::Set(d, cx), h)), lo);
            hi = hn::IfThenElse(m, hn::Max(hi, hn::Add(hn::Set(d, cx), h)), hi);
        };
        if (!fp.fullScreen) {
            disc(fp.ax, fp.ay, fp.ra);
            disc(fp.bx, fp.by, fp.rb);
        }
        if (!fp.fullScreen && sides.present) {
            for (int e = 0; e < 4; ++e) {
                const float* p = sides.quad[e];
                const float* q = sides.quad[(e + 1) % 4];
                const MR crosses = hn::Not(
                    hn::Gt(hn::Mul(hn::Sub(hn::Set(d, p[1]), y), hn::Sub(hn::Set(d, q[1]), y)), hn::Zero(d)));
                if (p[1] == q[1]) {
                    add(crosses, hn::Set(d, p[0]));
                    add(crosses, hn::Set(d, q[0]));
                    continue;
                }
                add(crosses, hn::Add(hn::Set(d, p[0]), hn::Div(hn::Mul(hn::Set(d, q[0] - p[0]), hn::Sub(y, hn::Set(d, p[1]))),
                                                            hn::Set(d, q[1] - p[1]))));
            }
        }
        // As the rasterizer rounds a row's span: the pixels whose centre x + 0.5 lies in [lo, hi].
        const VR half = hn::Set(d, 0.5f);
        const VR x0 = hn::Max(hn::Set(d, float(colMin)), hn::Ceil(hn::Sub(hn::Max(lo, hn::Set(d, -1.0f)), half)));
        const VR x1 =
            hn::Min(hn::Set(d, float(colMax)), hn::Floor(hn::Sub(hn::Min(hi, hn::Set(d, float(width) + 1.0f)), half)));
        const MR inRows = hn::RebindMask(d, hn::And(hn::Not(hn::Lt(row, hn::Set(di, rowBegin))), hn::Lt(row, hn::Set(di, rowEnd))));
        const MR keep = hn::And(hn::And(hn::Le(lo, hi), hn::Le(x0, x1)), inRows);
        const auto c0 = hn::ConvertTo(di, hn::IfThenElseZero(keep, x0));
        const auto c1 = hn::ConvertTo(di, hn::IfThenElse(keep, x1, hn::Set(d, -1.0f)));
        hn::StoreU(c0, di, out->x0 + i0);
        hn::StoreU(c1, di, out->x1 + i0);
        pixels = hn::Add(pixels, hn::Add(hn::Sub(c1, c0), hn::Set(di, 1)));
    }
    return size_t(hn::GetLane(hn::SumOfLanes(di, pixels)));
}

const char* SplatTargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace tyndall
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tyndall {

HWY_EXPORT(SplatSpanHeterogeneous);
HWY_EXPORT(SplatRowsHomogeneous);
HWY_EXPORT(FootprintBandColumns);
HWY_EXPORT(SplatTargetName);

void SplatBlock::reset(size_t pixels, int ffPerRay) {
    // The rays' entries are all overwritten (fillBlock), so only the padding's are set here.
    const size_t old = capacity;
    capacity = pixels + kPadding;
    for (std::vector<float>* v : {&ox, &oy, &oz, &dx, &dy, &dz, &tMax}) {
        if (old != capacity) v->resize(capacity);
        std::fill(v->begin() + pixels, v->end(), 0.0f);
    }
    if (old != capacity) medium.resize(capacity);
    std::fill(medium.begin() + pixels, medium.end(), kVacuum);
    for (std::vector<float>* v : {&sumR, &sumG, &sumB}) v->assign(capacity, 0.0f);
    freeFlightsPerRay = ffPerRay;
    freeFlights.assign(capacity * size_t(ffPerRay), 0.0f);
}

void splatRowsHomogeneous(const SplatBeam& beam, SplatBlock& block, size_t rowStride, const SplatRows& rows) {
    HWY_DYNAMIC_DISPATCH(SplatRowsHomogeneous)(beam, block, rowStride, rows);
}

size_t footprintBandColumns(const BeamFootprint& fp, const FootprintSides& sides, int y0, int rowBegin, int rowEnd,
                            int colMin, int colMax, int width, SplatRows* rows) {
    return HWY_DYNAMIC_DISPATCH(FootprintBandColumns)(fp, sides, y0, rowBegin, rowEnd, colMin, colMax, width, rows);
}

void splatSpanHeterogeneous(const SplatBeam& beam, const SplatBlock& block, size_t first, size_t count,
                            SplatHits* hits) {
    HWY_DYNAMIC_DISPATCH(SplatSpanHeterogeneous)(beam, block, first, count, hits);
}

const char* splatSimdTarget() { return HWY_DYNAMIC_DISPATCH(SplatTargetName)(); }

}  // namespace tyndall
#endif  // HWY_ONCE
