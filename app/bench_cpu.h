#pragma once
// Measurements behind `tyndall bench` for the CPU renderer. Each returns rates measured in the
// caller's run so they can be printed as ratios against a baseline from the same run.
#include <cstdint>

#include "cpu/pass_renderer.h"

namespace tyndall::app {

/// Embree's raw incoherent closest-hit throughput on `rt`: `count` rays with origins uniform in the
/// scene bounds and uniform random directions, rtcIntersect1 in parallel. Rays per second.
double measureRawRayRate(const EmbreeScene& rt, uint64_t count);

/// Embree's raw closest-hit throughput on the photon tracer's own rays: the origins and directions
/// of the beams of `passes` photon passes (in a fog-filled scene nearly every photon ray starts a
/// beam), replayed through rtcIntersect1 in parallel. Rays per second.
double measureReplayedPhotonRayRate(const PassRenderer& renderer, int passes);

struct PhotonRate {
    double pathsPerSecond = 0, beamsPerSecond = 0, raysPerSecond = 0;
};
PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes);

struct GatherRate {
    double queriesPerSecond = 0, hitsPerSecond = 0, buildSeconds = 0;
};
/// Gathers the beams of one pass along `count` of that pass's primary segments, through a BeamBvh
/// of the given kind.
GatherRate measureBeamGather(const PassRenderer& renderer, BeamBvh::Kind kind, uint64_t count);

struct PassRate {
    double passesPerSecond = 0;
    PassStats totals;  ///< summed over the measured passes
    int passes = 0;
};
PassRate measurePasses(const PassRenderer& renderer, int passes);

}  // namespace tyndall::app
