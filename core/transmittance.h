#pragma once
// Transmittance estimates shared by all gather stages (CPU gather, CPU rasterizer, GLSL twin).
//
// Homogeneous media: analytic exp(-sigma_t t).
// Heterogeneous media: the paper's unbiased, cacheable step estimate. A ray or beam stores n
// free-flight distances d_1..d_n sampled by delta tracking; Tr(t) ~= #{k : d_k > t} / n. Fresh
// distances every pass keep it unbiased (single passes look like swiss cheese).
#include "core/math.h"

namespace tyndall {

/// Fraction of the `n` stored free-flight distances that lie beyond `t`.
inline float storedTransmittance(const float* distances, int n, float t) {
    int beyond = 0;
    for (int k = 0; k < n; ++k) beyond += distances[k] > t ? 1 : 0;
    return float(beyond) / float(n);
}

}  // namespace tyndall
