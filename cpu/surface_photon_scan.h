#pragma once
// The surface-photon lookup's candidate scan (SurfacePhotonGrid::forEachNear) with Google Highway,
// 16 (AVX-512), 8 (AVX2) or 4 candidates at a time, runtime dispatch. It performs the scalar
// test's float operations in the same order with no fused multiply-adds (compiled with
// -ffp-contract=off), so it accepts exactly the photons the scalar test accepts, with the same d2
// bits (SurfacePhotonScan.SimdAcceptsExactlyWhatTheScalarTestAccepts in
// tests/cpu/surface_photon_grid_test.cpp).
#include <cstddef>
#include <cstdint>

#include "core/math.h"

namespace tyndall {

/// Lanes the scan may read past `count` in its arrays and write past it in its outputs.
constexpr size_t kPhotonScanPadding = 16;

/// The scalar definition, candidate by candidate: with d = c_i - p (c_i = (x[i], y[i], z[i])),
/// d2 = (d.x d.x + d.y d.y) + d.z d.z, candidate i is accepted unless d2 >= r_i^2 or
/// |(d.x n.x + d.y n.y) + d.z n.z| > 0.25 r_i (a NaN is accepted, as the scalar test's `continue`s
/// let it through). Writes the accepted i ascending to `accepted` and their d2 to `d2`; returns how
/// many.
size_t scanPhotonCandidatesScalar(const float* x, const float* y, const float* z, const float* radius, size_t count,
                                  const Vec3& p, const Vec3& n, uint32_t* accepted, float* d2);

/// The same with the widest SIMD the CPU has. x, y, z and radius must be readable up to
/// count + kPhotonScanPadding floats, `accepted` and `d2` writable as far.
size_t scanPhotonCandidates(const float* x, const float* y, const float* z, const float* radius, size_t count,
                            const Vec3& p, const Vec3& n, uint32_t* accepted, float* d2);

}  // namespace tyndall
