#pragma once
// The stage studies behind build/bench/tyndall_stages: each stage against a baseline measured in
// the same run (Embree alone on the same rays, the other BVH kind, the scalar splat), so the
// figures can be printed as ratios that the machine's load affects alike.
#include <cstdint>
#include <vector>

#include "app/stage_rates.h"
#include "cpu/pass_renderer.h"

namespace tyndall::bench {

using app::PassRate;
using app::PhotonRate;
using app::measurePasses;

/// Embree's raw incoherent closest-hit throughput on `rt`: `count` rays with origins uniform in the
/// scene bounds and uniform random directions, rtcIntersect1 in parallel. Rays per second.
double measureRawRayRate(const EmbreeScene& rt, uint64_t count);

/// The photon stage against Embree alone on the same rays.
struct PhotonStageRate {
    PhotonRate tracing;                  ///< PhotonTracer::trace(pass), pass after pass as renderPass calls it
    double replayRaysPerSecond = 0;      ///< every ray those passes cast, through rtcIntersect1 alone
    double beamReplayRaysPerSecond = 0;  ///< only the rays that start a beam (the earlier baseline)
    uint64_t rays = 0, beamRays = 0;     ///< per round
};
/// Traces passes 0 .. passes-1 (the renderer's own pass size, app::measurePhotonTracing) and
/// replays every ray they cast (origin, direction, t range; the tracer's own ray setup) through
/// rtcIntersect1 in blocks of 1024, in parallel at the same thread count. Rounds alternate tracing
/// and replay; each rate is its best round (the machine's noise only ever slows a round down).
PhotonStageRate measurePhotonStage(const PassRenderer& renderer, int passes, int rounds);

struct GatherRate {
    double queriesPerSecond = 0, hitsPerSecond = 0, buildSeconds = 0;
};
/// Gathers the beams of one pass along `count` of that pass's primary segments, through a BeamBvh
/// of each given kind: `rounds` rounds alternating between the kinds (count / rounds queries and
/// one build each), the best round of each kind kept, so load on the machine hits all alike.
std::vector<GatherRate> measureBeamGather(const PassRenderer& renderer, const std::vector<BeamBvh::Kind>& kinds,
                                          uint64_t count, int rounds = 3);

/// Passes 1..passes of two renderers of the same scene (e.g. --simd on and off), alternating pass
/// by pass after one warm-up pass each, so the machine's load falls on both alike.
void measurePassesAlternating(const PassRenderer& a, const PassRenderer& b, int passes, PassRate* rateA,
                              PassRate* rateB);

struct SplatRate {
    double scalarEvalsPerSecond = 0, simdEvalsPerSecond = 0;
    uint64_t evalsPerRound = 0;
};
/// The primary splat with the scalar and the SIMD kernel on the same beams and pixels (passes
/// 1..passes of `renderer`, traced once), rounds alternating the two; best round of each.
SplatRate measureSplatKernels(const PassRenderer& renderer, int passes, int rounds);

/// Embree alone on exactly the primary camera rays of pass `pass` (same jitter, rtcIntersect1 in
/// parallel rows as the camera stage casts them), best of `rounds`: rays per second.
double measurePrimaryRayReplay(const PassRenderer& renderer, uint64_t pass, int rounds);

}  // namespace tyndall::bench
