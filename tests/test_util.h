#pragma once
// Helpers shared by the test suites: statistics, paths, image evidence on failure.
#include <cmath>
#include <string>
#include <vector>

#include "core/image.h"

namespace tyndall::test {

inline std::string assetsDir() { return TYNDALL_ASSETS_DIR; }
inline std::string outputDir() { return TYNDALL_TEST_OUTPUT_DIR; }

struct MeanVar {
    double mean = 0, var = 0;  ///< sample mean and unbiased sample variance
    size_t n = 0;
};

inline MeanVar meanVar(const std::vector<double>& xs) {
    MeanVar r;
    r.n = xs.size();
    for (double x : xs) r.mean += x;
    r.mean /= double(xs.size());
    for (double x : xs) r.var += (x - r.mean) * (x - r.mean);
    r.var /= double(xs.size() > 1 ? xs.size() - 1 : 1);
    return r;
}

/// Bit-for-bit equality of two images (determinism tests).
inline bool identicalImages(const Image& a, const Image& b) {
    if (a.pixels.size() != b.pixels.size()) return false;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (a.pixels[i][c] != b.pixels[i][c]) return false;
    return true;
}

/// Least-squares slope of y against x.
inline double slope(const std::vector<double>& x, const std::vector<double>& y) {
    double mx = 0, my = 0;
    for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
    mx /= double(x.size());
    my /= double(y.size());
    double sxy = 0, sxx = 0;
    for (size_t i = 0; i < x.size(); ++i) sxy += (x[i] - mx) * (y[i] - my), sxx += (x[i] - mx) * (x[i] - mx);
    return sxy / sxx;
}

}  // namespace tyndall::test
