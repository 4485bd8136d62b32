#pragma once
// Estimates against a closed-form image, pixels grouped by h, the distance of the pixel-centre
// ray to the light (analytic_sphere_test.cpp, emitter_in_medium_test.cpp). Per group the ratio
// sum(estimate) / sum(closed form) over its pixels and channels must be within 4 standard errors
// plus a stated bias allowance of 1, and the standard error below a stated bound (so that the
// check can fail).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/image.h"
#include "cpu/reference_tracer.h"
#include "tests/test_util.h"

namespace tyndall::test {

/// The closed form per pixel and each pixel's h (< 0 or outside every bin: left out).
struct ClosedFormImage {
    Image radiance;
    std::vector<double> h;
};

/// Pixels with h in [hLo, hHi).
struct HBin {
    double hLo, hHi;
};

struct BinTolerance {
    double maxStdErr;  ///< the standard error must stay below this
    double bias;       ///< allowed on top of 4 standard errors
};

/// The path tracer's image: its standard error from the per-pixel variance (pixels independent;
/// the channels of one pixel share paths, so (sum of their standard deviations)^2 bounds the
/// variance of their sum, Cauchy-Schwarz).
inline void expectReferenceMatches(const char* what, const ReferenceImage& ref, const ClosedFormImage& e,
                                   const std::vector<HBin>& bins, BinTolerance tol) {
    for (const HBin& bin : bins) {
        double num = 0, den = 0, var = 0;
        for (size_t p = 0; p < ref.mean.pixels.size(); ++p) {
            if (e.h[p] < bin.hLo || e.h[p] >= bin.hHi) continue;
            double sd = 0;
            for (int c = 0; c < 3; ++c) {
                num += ref.mean.pixels[p][c];
                den += e.radiance.pixels[p][c];
                sd += std::sqrt(double(ref.varianceOfMean.pixels[p][c]));
            }
            var += sd * sd;
        }
        const double ratio = num / den, stdErr = std::sqrt(var) / den;
        std::printf("%s path tracer, h in [%.2f, %.2f): ratio %.4f +- %.4f\n", what, bin.hLo, bin.hHi, ratio, stdErr);
        EXPECT_LT(stdErr, tol.maxStdErr) << what << ": too noisy to test";
        EXPECT_NEAR(ratio, 1.0, 4.0 * stdErr + tol.bias)
            << what << " path tracer, h in [" << bin.hLo << ", " << bin.hHi << ")";
    }
}

/// PPB as independent batches (each the mean of some passes): the standard error from their spread.
inline void expectPpbMatches(const char* what, const std::vector<Image>& batches, const ClosedFormImage& e,
                             const std::vector<HBin>& bins, BinTolerance tol) {
    for (const HBin& bin : bins) {
        std::vector<double> ratios;
        for (const Image& img : batches) {
            double num = 0, den = 0;
            for (size_t p = 0; p < img.pixels.size(); ++p) {
                if (e.h[p] < bin.hLo || e.h[p] >= bin.hHi) continue;
                for (int c = 0; c < 3; ++c) num += img.pixels[p][c], den += e.radiance.pixels[p][c];
            }
            ratios.push_back(num / den);
        }
        const MeanVar r = meanVar(ratios);
        const double stdErr = std::sqrt(r.var / double(r.n));
        std::printf("%s PPB, h in [%.2f, %.2f): ratio %.4f +- %.4f\n", what, bin.hLo, bin.hHi, r.mean, stdErr);
        EXPECT_LT(stdErr, tol.maxStdErr) << what << ": too noisy to test";
        EXPECT_NEAR(r.mean, 1.0, 4.0 * stdErr + tol.bias)
            << what << " PPB, h in [" << bin.hLo << ", " << bin.hHi << ")";
    }
}

}  // namespace tyndall::test
