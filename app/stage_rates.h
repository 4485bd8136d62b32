#pragma once
// The CPU figures of `tyndall bench`: whole passes with the time of each stage, and the photon
// stage alone. Rates are measured in the caller's run on the caller's renderer, so they describe
// this machine with these settings.
#include <chrono>
#include <cstdint>

#include "cpu/pass_renderer.h"

namespace tyndall::app {

/// Wall seconds since `t0` on the steady clock.
double secondsSince(std::chrono::steady_clock::time_point t0);
/// CPU time of the whole process (every thread: TBB's, the GL thread, a software rasterizer's).
double processCpuSeconds();

struct PassRate {
    double passesPerSecond = 0;
    PassStats totals;  ///< summed over the measured passes (time per stage, beams, gathers, splat evaluations)
    int passes = 0;
};
/// Passes 1..passes of `renderer` after one warm-up pass (page-ins, caches).
PassRate measurePasses(const PassRenderer& renderer, int passes);

struct PhotonRate {
    double pathsPerSecond = 0, beamsPerSecond = 0, raysPerSecond = 0;
};
/// The photon stage alone: passes 0..passes-1 traced as renderPass traces them (the renderer's own
/// pass size), `rounds` times; the fastest round (the machine's noise only ever slows one down).
PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes, int rounds);

}  // namespace tyndall::app
