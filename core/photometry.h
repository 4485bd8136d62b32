#pragma once
// Photometric -> radiometric conversion for glTF lights. Tyndall renders radiometric RGB
// (W/sr, W/m^2, W m^-2 sr^-1); glTF's KHR_lights_punctual gives point and spot intensity in
// candela (lm/sr) and directional illuminance in lux (lm/m^2). The convention (docs/scene-format.md):
// one watt is 683 lumens for every RGB channel (the luminous efficacy of 555 nm light), so
//     W/sr  = colour * candela / 683        (point, spot)
//     W/m^2 = colour * lux / 683            (directional)
// glTF does not give emissive materials a unit; Tyndall reads emissiveFactor * emissiveStrength
// directly as radiance in W m^-2 sr^-1 (no 683), the convention of the Khronos sample models
// (the Cornell box's Ke = (17, 12, 4)) and of Blender's exporter.
#include "core/math.h"

namespace tyndall {

constexpr float kLumensPerWatt = 683.0f;

/// glTF point/spot light: colour (linear RGB) x intensity (cd) -> radiant intensity (W/sr).
inline Rgb radiantIntensityFromCandela(const Rgb& color, float candela) {
    return color * (candela / kLumensPerWatt);
}
/// glTF directional light: colour x illuminance (lux) -> irradiance (W/m^2).
inline Rgb irradianceFromLux(const Rgb& color, float lux) {
    return color * (lux / kLumensPerWatt);
}

}  // namespace tyndall
