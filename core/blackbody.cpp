#include "core/blackbody.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace tyndall {

namespace {
// CIE 1931 2-degree colour-matching functions x, y, z at 380, 385, ..., 780 nm (CIE 15, Table T.4).
constexpr int kCieSamples = 81;
constexpr float kCieFirstNm = 380.0f, kCieStepNm = 5.0f;
constexpr float kCie1931[kCieSamples][3] = {
    {0.001368f, 0.000039f, 0.006450f},  // 380 nm
    {0.002236f, 0.000064f, 0.010550f},  // 385 nm
    {0.004243f, 0.000120f, 0.020050f},  // 390 nm
    {0.007650f, 0.000217f, 0.036210f},  // 395 nm
    {0.014310f, 0.000396f, 0.067850f},  // 400 nm
    {0.023190f, 0.000640f, 0.110200f},  // 405 nm
    {0.043510f, 0.001210f, 0.207400f},  // 410 nm
    {0.077630f, 0.002180f, 0.371300f},  // 415 nm
    {0.134380f, 0.004000f, 0.645600f},  // 420 nm
    {0.214770f, 0.007300f, 1.039050f},  // 425 nm
    {0.283900f, 0.011600f, 1.385600f},  // 430 nm
    {0.328500f, 0.016840f, 1.622960f},  // 435 nm
    {0.348280f, 0.023000f, 1.747060f},  // 440 nm
    {0.348060f, 0.029800f, 1.782600f},  // 445 nm
    {0.336200f, 0.038000f, 1.772110f},  // 450 nm
    {0.318700f, 0.048000f, 1.744100f},  // 455 nm
    {0.290800f, 0.060000f, 1.669200f},  // 460 nm
    {0.251100f, 0.073900f, 1.528100f},  // 465 nm
    {0.195360f, 0.090980f, 1.287640f},  // 470 nm
    {0.142100f, 0.112600f, 1.041900f},  // 475 nm
    {0.095640f, 0.139020f, 0.812950f},  // 480 nm
    {0.058010f, 0.169300f, 0.616200f},  // 485 nm
    {0.032010f, 0.208020f, 0.465180f},  // 490 nm
    {0.014700f, 0.258600f, 0.353300f},  // 495 nm
    {0.004900f, 0.323000f, 0.272000f},  // 500 nm
    {0.002400f, 0.407300f, 0.212300f},  // 505 nm
    {0.009300f, 0.503000f, 0.158200f},  // 510 nm
    {0.029100f, 0.608200f, 0.111700f},  // 515 nm
    {0.063270f, 0.710000f, 0.078250f},  // 520 nm
    {0.109600f, 0.793200f, 0.057250f},  // 525 nm
    {0.165500f, 0.862000f, 0.042160f},  // 530 nm
    {0.225750f, 0.914850f, 0.029840f},  // 535 nm
    {0.290400f, 0.954000f, 0.020300f},  // 540 nm
    {0.359700f, 0.980300f, 0.013400f},  // 545 nm
    {0.433450f, 0.994950f, 0.008750f},  // 550 nm
    {0.512050f, 1.000000f, 0.005750f},  // 555 nm
    {0.594500f, 0.995000f, 0.003900f},  // 560 nm
    {0.678400f, 0.978600f, 0.002750f},  // 565 nm
    {0.762100f, 0.952000f, 0.002100f},  // 570 nm
    {0.842500f, 0.915400f, 0.001800f},  // 575 nm
    {0.916300f, 0.870000f, 0.001650f},  // 580 nm
    {0.978600f, 0.816300f, 0.001400f},  // 585 nm
    {1.026300f, 0.757000f, 0.001100f},  // 590 nm
    {1.056700f, 0.694900f, 0.001000f},  // 595 nm
    {1.062200f, 0.631000f, 0.000800f},  // 600 nm
    {1.045600f, 0.566800f, 0.000600f},  // 605 nm
    {1.002600f, 0.503000f, 0.000340f},  // 610 nm
    {0.938400f, 0.441200f, 0.000240f},  // 615 nm
    {0.854450f, 0.381000f, 0.000190f},  // 620 nm
    {0.751400f, 0.321000f, 0.000100f},  // 625 nm
    {0.642400f, 0.265000f, 0.000050f},  // 630 nm
    {0.541900f, 0.217000f, 0.000030f},  // 635 nm
    {0.447900f, 0.175000f, 0.000020f},  // 640 nm
    {0.360800f, 0.138200f, 0.000010f},  // 645 nm
    {0.283500f, 0.107000f, 0.000000f},  // 650 nm
    {0.218700f, 0.081600f, 0.000000f},  // 655 nm
    {0.164900f, 0.061000f, 0.000000f},  // 660 nm
    {0.121200f, 0.044580f, 0.000000f},  // 665 nm
    {0.087400f, 0.032000f, 0.000000f},  // 670 nm
    {0.063600f, 0.023200f, 0.000000f},  // 675 nm
    {0.046770f, 0.017000f, 0.000000f},  // 680 nm
    {0.032900f, 0.011920f, 0.000000f},  // 685 nm
    {0.022700f, 0.008210f, 0.000000f},  // 690 nm
    {0.015840f, 0.005723f, 0.000000f},  // 695 nm
    {0.011359f, 0.004102f, 0.000000f},  // 700 nm
    {0.008111f, 0.002929f, 0.000000f},  // 705 nm
    {0.005790f, 0.002091f, 0.000000f},  // 710 nm
    {0.004109f, 0.001484f, 0.000000f},  // 715 nm
    {0.002899f, 0.001047f, 0.000000f},  // 720 nm
    {0.002049f, 0.000740f, 0.000000f},  // 725 nm
    {0.001440f, 0.000520f, 0.000000f},  // 730 nm
    {0.001000f, 0.000361f, 0.000000f},  // 735 nm
    {0.000690f, 0.000249f, 0.000000f},  // 740 nm
    {0.000476f, 0.000172f, 0.000000f},  // 745 nm
    {0.000332f, 0.000120f, 0.000000f},  // 750 nm
    {0.000235f, 0.000085f, 0.000000f},  // 755 nm
    {0.000166f, 0.000060f, 0.000000f},  // 760 nm
    {0.000117f, 0.000042f, 0.000000f},  // 765 nm
    {0.000083f, 0.000030f, 0.000000f},  // 770 nm
    {0.000059f, 0.000021f, 0.000000f},  // 775 nm
    {0.000042f, 0.000015f, 0.000000f},  // 780 nm
};

/// Planck's law over wavelength (nm), divided by its value at the peak (Wien's law), as
/// pbrt-v4's BlackbodySpectrum.
double planckNormalised(double nm, double kelvin) {
    constexpr double c = 299792458.0, h = 6.62607015e-34, kb = 1.380649e-23;
    auto planck = [&](double metres) {
        return 2.0 * h * c * c / (std::pow(metres, 5) * (std::exp(h * c / (metres * kb * kelvin)) - 1.0));
    };
    const double peak = 2.897771955e-3 / kelvin;
    return planck(nm * 1e-9) / planck(peak);
}

// Rec.709 / sRGB primaries, D65 white: linear RGB from XYZ.
Rgb xyzToRec709(const Vec3& c) {
    return {3.2404542f * c.x - 1.5371385f * c.y - 0.4985314f * c.z,
            -0.9692660f * c.x + 1.8760108f * c.y + 0.0415560f * c.z,
            0.0556434f * c.x - 0.2040259f * c.y + 1.0572252f * c.z};
}

// rgb(T) tabulated every kTableStep kelvin up to kTableMax (linear interpolation; beyond, exact).
constexpr float kTableStep = 4.0f;
constexpr int kTableSize = 4096;
constexpr float kTableMax = kTableStep * float(kTableSize - 1);

const std::array<Rgb, kTableSize>& rgbTable() {
    static const std::array<Rgb, kTableSize> table = [] {
        std::array<Rgb, kTableSize> t;
        for (int i = 0; i < kTableSize; ++i) t[size_t(i)] = blackbodyRgbExact(float(i) * kTableStep);
        return t;
    }();
    return table;
}
}  // namespace

Vec3 blackbodyXyz(float kelvin) {
    if (!(kelvin > 0) || !std::isfinite(kelvin)) return Vec3(0.0f);
    double xyz[3] = {0, 0, 0}, yIntegral = 0;
    for (int i = 0; i < kCieSamples; ++i) {
        const double s = planckNormalised(kCieFirstNm + kCieStepNm * float(i), kelvin);
        for (int k = 0; k < 3; ++k) xyz[k] += s * kCie1931[i][k];
        yIntegral += kCie1931[i][1];
    }
    return Vec3(float(xyz[0] / yIntegral), float(xyz[1] / yIntegral), float(xyz[2] / yIntegral));
}

Rgb blackbodyRgbExact(float kelvin) {
    Rgb c = xyzToRec709(blackbodyXyz(kelvin));
    return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)};
}

Rgb blackbodyRgb(float kelvin) {
    if (!(kelvin > 0)) return Rgb(0.0f);  // NaN too
    if (kelvin >= kTableMax) return blackbodyRgbExact(kelvin);
    const std::array<Rgb, kTableSize>& t = rgbTable();
    const float x = kelvin / kTableStep;
    const int i = int(x);
    const float f = x - float(i);
    return t[size_t(i)] * (1.0f - f) + t[size_t(i) + 1] * f;
}

}  // namespace tyndall
