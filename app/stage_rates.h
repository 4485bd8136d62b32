#pragma once
// The CPU figures of `tyndall bench`: whole passes with the time of each stage, and the photon
// stage alone. Rates are measured in the caller's run on the caller's renderer, so they describe
// this machine with these settings.
#include <cstdint>
#include <string>

#include "core/timing.h"
#include "cpu/pass_renderer.h"

namespace tyndall::app {

/// CPU time of the whole process (every thread: TBB's, the GL thread, a software rasterizer's).
double processCpuSeconds();

struct PassRate {
    double passesPerSecond = 0;
    PassStats totals;  ///< summed over the measured passes (time per stage, beams, gathers, splat evaluations)
    int passes = 0;
    double cpuSeconds = 0;  ///< process CPU time of the measured passes (every thread; 0 = not measured)
};
/// Passes 1..passes of `renderer` after one warm-up pass (page-ins, caches).
PassRate measurePasses(const PassRenderer& renderer, int passes);

/// One row of a bench table: "  <what> <value> <unit> <note>", columns aligned.
void printRate(const char* what, double value, const char* unit, const std::string& note = "");
/// A row's note comparing `value` with `base`: "= <value / base>x <baseName>".
std::string ratio(double value, double base, const char* baseName);
/// The rows of whole passes measured on `settings`: passes/s (noted `passesNote`), camera paths,
/// gather queries and splat evaluations per second, each stage's time per pass and its share of
/// a pass, the process CPU time per pass (when measured: what a loaded machine does not
/// stretch, so two scenes' passes compare on it), beams per pass.
void printPassRate(const PassRate& pr, const RenderSettings& settings, const std::string& passesNote = "");

struct PhotonRate {
    double pathsPerSecond = 0, beamsPerSecond = 0, raysPerSecond = 0;
    /// What the paths store, the same in every round: what a pass's splat and gathers work on.
    double beamsPerPath = 0, meanBeamLength = 0;
};
/// The photon stage alone: passes 0..passes-1 traced as renderPass traces them (the renderer's own
/// pass size), `rounds` times; the fastest round (the machine's noise only ever slows one down).
PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes, int rounds);

}  // namespace tyndall::app
