#pragma once
// Which quantity a path carries, for the BSDFs that are not symmetric (refraction, shading normals).

namespace tyndall {

/// Importance: photons, which carry power (no 1/eta^2 at a refraction; Veach's adjoint for shading
/// normals). Radiance: camera paths, scaled by (eta_i / eta_t)^2 when crossing into another index.
enum class TransportMode { Importance, Radiance };

}  // namespace tyndall
