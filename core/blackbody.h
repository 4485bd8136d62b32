#pragma once
// Blackbody emission colour (fire and explosions: a medium's temperature grid, core/medium.h).
//
// The spectrum is Planck's law B(lambda, T) divided by its own peak value B(lambda_max, T) (Wien:
// lambda_max = 2.8978e-3 m K / T), as pbrt-v4's BlackbodySpectrum: at every temperature the
// spectrum's maximum is 1, so a hotter body is brighter in the visible only as its peak moves in.
// XYZ = sum over 380..780 nm (5 nm) of spectrum x CIE 1931 2-degree matching functions, divided by
// the same sum of y-bar: a flat spectrum of 1 has Y = 1 (pbrt-v4's normalisation). RGB is linear
// Rec.709 (sRGB primaries, D65 white, no chromatic adaptation); out-of-gamut components (below
// ~1900 K the locus leaves the gamut past the red-green edge) are clamped to 0.
// Luminance Y: 1000 K 9e-6, 1500 K 0.0034, 2000 K 0.048, 3000 K 0.42, 6500 K 0.89, 10000 K 0.44
// (the peak leaves the visible both ways): temperature sets brightness as well as colour.
#include "core/math.h"

namespace tyndall {

/// XYZ of the peak-normalised blackbody spectrum at `kelvin` (0 for T <= 0 or non-finite).
Vec3 blackbodyXyz(float kelvin);
/// Linear Rec.709 RGB of that spectrum, negative components clamped to 0. Exact (81 Planck
/// evaluations): use blackbodyRgb in render loops.
Rgb blackbodyRgbExact(float kelvin);
/// blackbodyRgbExact interpolated from a table every 4 K up to 16380 K (relative error < 1e-3
/// above 1000 K), exact beyond; 0 for T <= 0 or NaN. Thread-safe.
Rgb blackbodyRgb(float kelvin);

}  // namespace tyndall
