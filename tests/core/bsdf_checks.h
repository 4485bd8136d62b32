#pragma once
// Shared checks of BSDF models (core/microfacet.h, core/coated_diffuse.h): directions by angle,
// albedo by quadrature of eval, chi-square of a sampler against its pdf.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/math.h"

namespace tyndall {

inline Vec3 dirOf(float cosTheta, float phi) {
    float s = safeSqrt(1.0f - cosTheta * cosTheta);
    return {s * std::cos(phi), s * std::sin(phi), cosTheta};
}

/// Directional albedo by quadrature of eval (independent of the sampling routine).
template <class F>
inline double albedoByQuadrature(F f, int n = 400) {
    double sum = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            float c = -1.0f + 2.0f * (i + 0.5f) / n, phi = 2.0f * kPi * (j + 0.5f) / n;
            sum += f(dirOf(c, phi)) * std::abs(c);
        }
    return sum * (2.0 / n) * (2.0 * kPi / n);
}

/// Chi-square of sampled directions against the pdf integrated over (cos theta, phi) bins.
template <class Sampler, class Pdf>
inline void chiSquare(Sampler sample, Pdf pdf, const char* what) {
    const int nc = 24, np = 48, sub = 6, n = 400000;
    std::vector<double> observed(nc * np, 0), expected(nc * np, 0);
    std::mt19937 gen(1234);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int k = 0; k < n; ++k) {
        Vec3 wi;
        if (!sample(gen, u, &wi)) continue;
        float phi = std::atan2(wi.y, wi.x);
        if (phi < 0) phi += 2.0f * kPi;
        int ic = std::min(nc - 1, int((clampValue(wi.z, -1.0f, 1.0f) + 1.0f) * 0.5f * nc));
        int ip = std::min(np - 1, int(phi / (2.0f * kPi) * np));
        observed[size_t(ic * np + ip)] += 1;
    }
    for (int ic = 0; ic < nc; ++ic)
        for (int ip = 0; ip < np; ++ip) {
            double s = 0;
            for (int a = 0; a < sub; ++a)
                for (int b = 0; b < sub; ++b) {
                    float c = -1.0f + 2.0f * (ic + (a + 0.5f) / sub) / nc;
                    float phi = 2.0f * kPi * (ip + (b + 0.5f) / sub) / np;
                    s += pdf(dirOf(c, phi));
                }
            expected[size_t(ic * np + ip)] = s / (sub * sub) * (2.0 / nc) * (2.0 * kPi / np) * n;
        }
    // Pool bins with small expectations (the usual >= 5 rule).
    double chi2 = 0, pooledO = 0, pooledE = 0;
    int dof = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5) {
            pooledO += observed[i];
            pooledE += expected[i];
            continue;
        }
        chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++dof;
    }
    if (pooledE > 5) {
        chi2 += (pooledO - pooledE) * (pooledO - pooledE) / pooledE;
        ++dof;
    }
    // Wilson-Hilferty: chi2/dof ~ normal; 5 sigma keeps a fixed seed far from flaky yet catches
    // a wrong sampler (a planted alpha^2 instead of alpha in the visible-normal warp fails by ~100 sigma).
    double z = (std::cbrt(chi2 / (dof - 1)) - (1 - 2.0 / (9 * (dof - 1)))) / std::sqrt(2.0 / (9 * (dof - 1)));
    EXPECT_LT(z, 5.0) << what << ": chi2 " << chi2 << " over " << dof - 1 << " dof";
}

}  // namespace tyndall
