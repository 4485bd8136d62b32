#include "cpu/beam_cone.h"

#include <algorithm>
#include <cmath>

namespace tyndall {

namespace {
/// Cone piece of path distance s (< reach): the smallest k in 1..kConePieces with s >= reach 2^-k
/// (the last piece reaches down to 0).
int pieceOf(double s, double reach) {
    int k = 1;
    double lower = reach / kConeRatio;
    while (k < kConePieces && s < lower) {
        lower /= kConeRatio;
        ++k;
    }
    return k;
}
}  // namespace

double surfaceConeScale(double s, double reach) {
    if (!(reach > 0) || !(s < reach)) return 1.0;
    static const double floor = std::pow(kConeRatio, 0.5 - kConePieces);
    return std::max(floor, s / reach);
}

void appendConeBeam(const PhotonBeam& beam, double s0, double reach, const Medium& medium, const float* freeFlights,
                    int n, std::vector<PhotonBeam>& beams, std::vector<float>& outFreeFlights) {
    auto appendFreeFlights = [&](float shift) {
        for (int i = 0; i < n; ++i) outFreeFlights.push_back(freeFlights[i] - shift);
    };
    if (!(reach > 0) || s0 >= reach) {
        beams.push_back(beam);
        if (n > 0) appendFreeFlights(0.0f);
        return;
    }
    const double sEnd = s0 + double(beam.tMax);
    double s = s0;
    for (int k = pieceOf(s0, reach); k >= 0; --k) {
        const double upper = k == 0 ? sEnd : std::min(sEnd, reach * std::pow(kConeRatio, 1 - k));
        if (upper > s) {
            const float t = float(s - s0);
            PhotonBeam& piece = beams.emplace_back(beam);
            piece.origin = beam.origin + beam.dir * t;
            piece.tMax = float(upper - s);
            piece.radius = k == 0 ? beam.radius : float(double(beam.radius) * std::pow(kConeRatio, 0.5 - k));
            if (n > 0) appendFreeFlights(t);
            // Grid media keep the stored distances (shifted); homogeneous beams are analytic.
            if (medium.homogeneous() && t > 0) piece.power = beam.power * medium.transmittance(t);
            s = upper;
        }
        if (s >= sEnd) break;
    }
}

}  // namespace tyndall
