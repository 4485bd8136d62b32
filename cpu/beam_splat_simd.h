#pragma once
// The SIMD kernels of the CPU beam rasterizer: the beam x ray estimator of core/beam_estimator.h
// for one beam against a run of consecutive pixels, 8 (AVX2) or 16 (AVX-512) pixels per
// instruction, with Google Highway and runtime dispatch to the best instruction set the CPU has;
// and a footprint's pixel columns on a band's rows, a row per lane.
//
// The scalar evaluator in cpu/beam_rasterizer.cpp stays the definition. These kernels do the same
// float operations in the same order, without fused multiply-adds (the file is built with
// -ffp-contract=off), so coverage (which pixels a beam reaches) and every intermediate value are
// bit for bit the scalar ones; the only difference is Highway's vectorised exp (1 ulp) in place of
// std::exp, so a homogeneous pixel agrees with the scalar splat to ~1e-7 relative and a
// heterogeneous one exactly (tests/cpu/beam_splat_simd_test.cpp). Per-pixel sums still add the
// beams in index order, so the result does not depend on the thread count; it may differ by an ulp
// between machines whose dispatch picks different instruction sets (exp's last bit).
//
// Pixels are passed as a structure of arrays (SplatBlock): one band of rows of the image, copied
// from PrimarySegments by the rasterizer. Called from the rasterizer's band tasks; the kernels keep
// no state and are thread-safe on distinct blocks.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/medium.h"
#include "cpu/beam_rasterizer.h"

namespace tyndall {

/// A block of pixels' primary rays (structure of arrays) and their radiance sums. Every array holds
/// `capacity` entries; entries a kernel reads past the pixels of a span are padding it never adds
/// to. `freeFlights` holds `freeFlightsPerRay` arrays of `capacity` distances each (array k is the
/// k-th stored distance of every pixel), for grid media.
struct SplatBlock {
    static constexpr size_t kPadding = 64;  ///< >= the widest vector in floats
    size_t capacity = 0;
    std::vector<float> ox, oy, oz, dx, dy, dz, tMax;
    std::vector<int32_t> medium;
    std::vector<float> freeFlights;
    int freeFlightsPerRay = 0;
    std::vector<float> sumR, sumG, sumB;

    /// Room for `pixels` pixels plus padding; sums zeroed, rays of the padding in no medium (the
    /// pixels' rays are left for the caller to fill).
    void reset(size_t pixels, int freeFlightsPerRay);
};

/// One beam's constants, hoisted as the scalar evaluator hoists them.
struct SplatBeam {
    Vec3 origin, dir;
    float tMax = 0, radius = 0, r2 = 0, kernelScale = 0;
    float hgA = 0, hgB = 0, hgC = 0;  ///< HG phase: hgA / ((hgB + hgC b) sqrt(...)), b = dot(w_c, w_b)
    float g = 0;                      ///< HG asymmetry (the heterogeneous kernel uses hgPhase's own form)
    Rgb sigmaT, scaledPower;          ///< extinction; Phi_b sigma_s (homogeneous media)
    bool grey = false;                ///< sigmaT equal in all channels: one exp per pixel
    MediumId medium = kVacuum;
    const float* freeFlights = nullptr;  ///< the beam's stored distances (grid media)
    int freeFlightsPerBeam = 0;
};

/// The pixel columns one footprint covers on each row of a band of at most kMaxRows rows: row i
/// (block row i) holds the pixels [x0[i], x1[i]], none when x0[i] > x1[i].
struct SplatRows {
    static constexpr int kMaxRows = 8;
    int rows = 0;
    int32_t x0[kMaxRows] = {}, x1[kMaxRows] = {};
};

/// The rows [rowBegin, rowEnd) of the band starting at image row y0 (rowEnd - y0 <= kMaxRows; the
/// band's rows before rowBegin stay empty): on each, the pixels whose centre x + 0.5 lies in
/// footprintRowSpan's interval at y + 0.5 and in the columns [colMin, colMax]. The rows are
/// computed together, each with footprintRowSpan's float operations, so the columns are exactly
/// the ones a row at a time gives (tests/cpu/beam_splat_simd_test.cpp). Returns the number of pixels.
size_t footprintBandColumns(const BeamFootprint& fp, const FootprintSides& sides, int y0, int rowBegin, int rowEnd,
                            int colMin, int colMax, int width, SplatRows* rows);

/// Homogeneous medium: adds the estimator of `beam` to the sums of the block pixels of `rows`
/// (block row i starts at block pixel i * rowStride).
void splatRowsHomogeneous(const SplatBeam& beam, SplatBlock& block, size_t rowStride, const SplatRows& rows);

/// What the heterogeneous kernel leaves for the caller: the pixels of a span that the beam reaches
/// with non-zero stored transmittances on both sides, with s_w and the estimator's factors except
/// sigma_s(x_w) (a density lookup, done per pixel by the caller).
struct SplatHits {
    std::vector<uint32_t> pixel;  ///< block index
    std::vector<float> s, trCam, trBeam, weight;  ///< weight = k_r(u) p(theta) / sin(theta)
    size_t count = 0;
};

/// Grid medium: finds the contributing pixels of [first, first + count) and their factors, in
/// pixel order, into `hits` (overwritten; sized by the kernel).
void splatSpanHeterogeneous(const SplatBeam& beam, const SplatBlock& block, size_t first, size_t count,
                            SplatHits* hits);

/// The instruction set the dispatch chose on this CPU (for the bench), e.g. "AVX3" or "AVX2".
const char* splatSimdTarget();

}  // namespace tyndall
