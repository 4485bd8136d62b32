#pragma once
// The hybrid split of `tyndall bench`: passes/s of the hybrid loop (GL splat on its own thread,
// overlapped with the CPU passes) against the CPU-only loop, both through PassScheduler in the
// same run; each side's time per pass measured alone; the overlap efficiency; and the GL splat's
// own rates (fragments/s, time per beam), plus process CPU time per pass, which shows where a
// software rasterizer's time comes from (it shares the cores with the CPU passes).
#include <string>

#include "cpu/pass_renderer.h"

namespace tyndall::app {

struct HybridSplit {
    int passes = 0;
    std::string gl;  ///< the GL context's description
    double cpuOnlyPassesPerSecond = 0, hybridPassesPerSecond = 0;
    double cpuOnlyCpuSecondsPerPass = 0, hybridCpuSecondsPerPass = 0;  ///< process CPU time (all threads)
    // Alone (nothing else running), seconds per pass.
    double cpuStageSeconds = 0;     ///< photons + camera paths (the CPU side of the hybrid loop)
    double glSplatSeconds = 0;      ///< the GL splat, wall
    double glSplatCpuSeconds = 0;   ///< the GL splat, process CPU time
    double cpuSplatSeconds = 0;     ///< the CPU twin (BeamRasterizer), wall
    double cpuSplatCpuSeconds = 0;  ///< the CPU twin, process CPU time
    // Inside the hybrid loop, seconds per pass (each side slowed by sharing the cores).
    double overlappedCpuStageSeconds = 0, overlappedGlSplatSeconds = 0;
    double fragmentsPerPass = 0;  ///< fragment shader invocations (0 when the driver cannot count)
    double beamsPerPass = 0;
    double pixelTestsPerPass = 0;  ///< the CPU twin's estimator evaluations

    double overlapEfficiency() const {  ///< hybrid wall per pass / max of the sides alone
        return (1.0 / hybridPassesPerSecond) / std::max(cpuStageSeconds, glSplatSeconds);
    }
};

/// Runs `passes` passes (after one warm-up pass) CPU-only and hybrid (--gpu on), then the sides
/// alone. Throws Error when there is no GL context.
HybridSplit measureHybridSplit(const PassRenderer& renderer, int passes);

/// Prints the figures as a `tyndall bench` section, ratios against the CPU-only loop.
void printHybridSplit(const HybridSplit& b);

}  // namespace tyndall::app
