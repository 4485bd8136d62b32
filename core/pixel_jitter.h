#pragma once
// Where in its pixel the camera ray of pass i starts (the film jitter). A progressive render
// averages one camera ray per pixel per pass, so the jitter over the passes is the quadrature of
// the pixel's area: independent uniform jitter leaves the pixel integral's own noise at
// 1/sqrt(passes), largest where the pixel holds an edge, a highlight or a light's glow in fog
// (where the in-scattered radiance grows as 1/distance to the light and one pixel decides an
// image's error). Here pass i of pixel p uses the R2 sequence (Roberts 2018: the 2-D Kronecker
// sequence of the plastic number, frac(i a)), rotated by a random offset per pixel
// (Cranley-Patterson): every prefix of passes covers the pixel evenly, so that integral converges
// nearly as 1/passes, while neighbouring pixels stay uncorrelated. A pure function of (seed, pass,
// pixel): any split of the passes, any thread count, CPU or GL give the same rays.
#include <cmath>
#include <cstdint>

#include "core/rng.h"
#include "core/sampling.h"

namespace tyndall {

/// The film jitter in [0, 1)^2 of `pixel` in pass `pass`.
inline Vec2 pixelJitter(uint64_t seed, uint64_t pass, uint64_t pixel) {
    constexpr double a1 = 0.7548776662466927;  // 1 / g, g the plastic number (x^3 = x + 1)
    constexpr double a2 = 0.5698402909980532;  // 1 / g^2
    Rng rotation = Rng::forKey(seed, 0, pixel, StreamPurpose::PixelJitterRotation);
    const double u0 = rotation.uniform(), v0 = rotation.uniform();
    // pass mod 2^32: the sequence's index stays exact in a double's fraction.
    const double n = double((pass & 0xffffffffull) + 1);
    const double u = u0 + n * a1, v = v0 + n * a2;
    constexpr float below1 = 0.99999994f;
    return Vec2{std::min(float(u - std::floor(u)), below1), std::min(float(v - std::floor(v)), below1)};
}

/// The uniform that chooses the light of `pixel`'s first shadow ray in pass `pass` (PPB's direct
/// light, docs/algorithm.md "Direct light by shadow rays"): the golden-ratio Kronecker sequence
/// frac(o + (pass + 1) / phi), rotated by a random offset per pixel as the film jitter is. Each pass's
/// value is uniform (the offset is), so the choice stays unbiased; over any run of passes a light of
/// probability p is chosen in a share within about 1/passes of p, where independent choices scatter
/// by sqrt(p (1 - p) / passes): where two lights of different colours light a surface, that
/// scatter was the surface's noise. 1/phi is independent over the rationals of the film jitter's
/// 1/g and 1/g^2 (g cubic, phi quadratic), so the choice does not follow the jitter's position.
inline float lightChoiceUniform(uint64_t seed, uint64_t pass, uint64_t pixel) {
    constexpr double a = 0.6180339887498949;  // 1 / phi
    Rng rotation = Rng::forKey(seed, 0, pixel, StreamPurpose::LightChoiceRotation);
    const double n = double((pass & 0xffffffffull) + 1), u = rotation.uniform() + n * a;
    return std::min(float(u - std::floor(u)), 0.99999994f);
}

}  // namespace tyndall
