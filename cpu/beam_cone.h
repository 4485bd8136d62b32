#pragma once
// The photon cone: near its light a photon path's beams are thinner than the global radius.
//
// n photon paths leave a point light about sqrt(4 pi / n) radians apart, so at path distance s
// from the light (the length of the path so far, over every segment) neighbouring beams are
// ~ s sqrt(4 pi / n) apart: a radius that is fine far away blurs the light's own glow, whose
// radiance falls as 1/distance (the photon differentials' beam widths of Jarosz et al. 2011 grow
// the same way). A beam's radius at path distance s is therefore
//     r(s) = min(R_j, angle_j * s),      angle_j = photonAngle * R_j / R_0 = R_j / reach,
// R_j the schedule's radius of path j: the cone reaches the full radius at the path distance
// `reach` = radius / photonAngle, the same for every path, and both shrink at the schedule's rate
// (so the estimator stays consistent). The cone is applied as a step function: the part of a
// beam inside the reach is stored as separate beams over the intervals [reach q^-k, reach q^(1-k)),
// k = 1..kConePieces-1, and [0, reach q^(1-kConePieces)), q = kConeRatio, with radius R_j q^(1/2-k)
// (the interval's geometric middle): with q = 4 and 2 pieces, R_j/2 on [reach/4, reach) and R_j/8
// below reach/4. Every piece is an ordinary beam (origin, power
// times the transmittance up to its start, its own radius), so the splat, the gather and the GLSL
// twin are unchanged, and the estimate at each point along a beam is still a normalised kernel.
// Path distance only grows along a path, so a path gains at most kConePieces extra beams.
// Area lights start their paths at the emitter's equivalent radius sqrt(area / 4 pi); directional
// lights at infinity (no cone).
//
// Surface photons get the same cone (surfaceConeScale): a photon stored at path distance s carries
// the radius r_s,j x min(1, s / reach), floored at the innermost beam piece's 1/8. The irradiance of
// a point light on a surface at distance s falls as 1/s^2, and the photons' spacing there grows as
// s, so a radius proportional to s keeps both the kernel's relative bias (~ (r/s)^2) and the photon
// count within it independent of s. Without it a small surface next to a light (the end cap of a
// flashlight's handle, 1 cm from the lamp) has its photons spread over a kernel many times its own
// size, where no camera ray sees them: their light is lost (docs/algorithm.md, "The photon cone").
// A photon sits at one path distance, so the scale is continuous, not stepped.
#include <vector>

#include "core/medium.h"
#include "core/photon_beam.h"

namespace tyndall {

/// Pieces inside the reach, and the ratio of their path-distance intervals.
constexpr int kConePieces = 2;
constexpr double kConeRatio = 4.0;

/// The factor on a surface photon's radius at path distance `s` from its light: s / reach clamped to
/// [kConeRatio^(1/2 - kConePieces), 1] (the innermost beam piece's radius factor); 1 when reach <= 0.
double surfaceConeScale(double s, double reach);

/// Appends `beam` to `beams`, split at the cone's dyadic path distances when its start lies
/// within `reach` (beam.radius is the full radius R_j); its path distance at t = 0 is `s0`.
/// reach <= 0 (off) or s0 >= reach stores it unchanged. `freeFlights`/`n` (n > 0: grid media)
/// are the beam's stored distances, appended once per piece, shifted to the piece's origin;
/// homogeneous pieces carry the analytic transmittance to their start in their power.
void appendConeBeam(const PhotonBeam& beam, double s0, double reach, const Medium& medium, const float* freeFlights,
                    int n, std::vector<PhotonBeam>& beams, std::vector<float>& outFreeFlights);

}  // namespace tyndall
