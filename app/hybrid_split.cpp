#include "app/hybrid_split.h"

#include <cstdio>
#include <cstdlib>

#include "app/stage_rates.h"
#include "core/timing.h"
#include "gpu/beam_splatter.h"
#include "hybrid/gl_thread.h"
#include "hybrid/pass_scheduler.h"

namespace tyndall::app {

namespace {

struct LoopRun {
    double wall = 0, cpu = 0;
    RenderProgress progress;
};

/// `passes` passes through the scheduler after a one-pass warm-up (shader compilation, caches).
LoopRun runLoop(PassScheduler& scheduler, const PassRenderer& renderer, int passes) {
    RenderSettings warm = renderer.settings();
    warm.passes = 1;
    warm.timeBudget = 0;
    PassRenderer warmRenderer(renderer.scene(), warm);
    CallbackDisplay display([](const Accumulator&, const RenderProgress&) { return DisplayCommand::Continue; });
    Accumulator acc(warm.width, warm.height);
    scheduler.run(warmRenderer, acc, 1000, display);

    RenderSettings s = renderer.settings();
    s.passes = uint64_t(passes);
    s.timeBudget = 0;
    PassRenderer measured(renderer.scene(), s);
    Accumulator acc2(s.width, s.height);
    LoopRun r;
    double c0 = processCpuSeconds();
    auto t0 = Clock::now();
    r.progress = scheduler.run(measured, acc2, 0, display);
    r.wall = secondsSince(t0);
    r.cpu = processCpuSeconds() - c0;
    return r;
}
}  // namespace

HybridSplit measureHybridSplit(const PassRenderer& renderer, int passes) {
    HybridSplit b;
    b.passes = passes;
    {
        PassScheduler cpuOnly(GpuMode::Off);
        LoopRun r = runLoop(cpuOnly, renderer, passes);
        b.cpuOnlyPassesPerSecond = passes / r.wall;
        b.cpuOnlyCpuSecondsPerPass = r.cpu / passes;
    }
    {
        PassScheduler hybrid(GpuMode::On);
        b.gl = hybrid.glDescription();
        LoopRun r = runLoop(hybrid, renderer, passes);
        b.hybridPassesPerSecond = passes / r.wall;
        b.hybridCpuSecondsPerPass = r.cpu / passes;
        b.overlappedCpuStageSeconds = (r.progress.totals.photonSeconds + r.progress.totals.cameraSeconds) / passes;
        b.overlappedGlSplatSeconds = r.progress.totals.splatSeconds / passes;
    }

    // Each side alone, on the same passes.
    GlThread gl;
    auto splatter = gl.submit([&](GlContext& ctx) {
                          auto s = std::make_shared<GlBeamSplatter>(ctx, renderer.scene());
                          s->countFragments(true);
                          return s;
                      }).get();
    for (int i = 0; i <= passes; ++i) {
        auto t0 = Clock::now();
        PhotonMap photons = renderer.tracePhotons(uint64_t(i));
        CameraPassResult camera = renderer.traceCamera(uint64_t(i), photons);
        double cpuStage = secondsSince(t0);

        double c0 = processCpuSeconds();
        auto t1 = Clock::now();
        GlSplatStats stats;
        gl.submit([&](GlContext&) { return splatter->splat(camera.primary, photons, &stats); }).get();
        double glWall = secondsSince(t1), glCpu = processCpuSeconds() - c0;

        c0 = processCpuSeconds();
        auto t2 = Clock::now();
        RasterStats raster;
        renderer.splatPrimary(camera.primary, photons, &raster);
        double cpuSplatWall = secondsSince(t2), cpuSplatCpu = processCpuSeconds() - c0;
        if (i == 0) continue;  // warm-up
        b.cpuStageSeconds += cpuStage / passes;
        b.glSplatSeconds += glWall / passes;
        b.glSplatCpuSeconds += glCpu / passes;
        b.cpuSplatSeconds += cpuSplatWall / passes;
        b.cpuSplatCpuSeconds += cpuSplatCpu / passes;
        b.fragmentsPerPass += double(stats.fragments) / passes;
        b.beamsPerPass += double(photons.beams.size()) / passes;
        b.pixelTestsPerPass += double(raster.pixelTests) / passes;
    }
    gl.submit([&](GlContext&) { splatter.reset(); }).get();
    return b;
}

void printHybridSplit(const HybridSplit& b) {
    const char* lp = std::getenv("LP_NUM_THREADS");
    std::printf("hybrid: GL splat on %s (LP_NUM_THREADS=%s), %d passes per figure\n", b.gl.c_str(), lp ? lp : "unset",
                b.passes);
    printRate("CPU-only loop", b.cpuOnlyPassesPerSecond, "passes/s");
    printRate("hybrid loop", b.hybridPassesPerSecond, "passes/s",
        ratio(b.hybridPassesPerSecond, b.cpuOnlyPassesPerSecond, "CPU-only"));
    printRate("  process CPU time, CPU-only", b.cpuOnlyCpuSecondsPerPass, "s/pass");
    printRate("  process CPU time, hybrid", b.hybridCpuSecondsPerPass, "s/pass",
        ratio(b.hybridCpuSecondsPerPass, b.cpuOnlyCpuSecondsPerPass, "CPU-only"));
    printRate("CPU side alone (photons+camera)", b.cpuStageSeconds * 1e3, "ms/pass");
    printRate("GL splat alone", b.glSplatSeconds * 1e3, "ms/pass", ratio(b.glSplatSeconds, b.cpuSplatSeconds, "CPU twin"));
    printRate("CPU twin splat alone", b.cpuSplatSeconds * 1e3, "ms/pass");
    printRate("  GL splat process CPU time", b.glSplatCpuSeconds * 1e3, "ms/pass",
        ratio(b.glSplatCpuSeconds, b.cpuSplatCpuSeconds, "CPU twin's"));
    printRate("  CPU twin process CPU time", b.cpuSplatCpuSeconds * 1e3, "ms/pass");
    printRate("CPU side inside the hybrid loop", b.overlappedCpuStageSeconds * 1e3, "ms/pass",
        ratio(b.overlappedCpuStageSeconds, b.cpuStageSeconds, "alone"));
    printRate("GL splat inside the hybrid loop", b.overlappedGlSplatSeconds * 1e3, "ms/pass",
        ratio(b.overlappedGlSplatSeconds, b.glSplatSeconds, "alone"));
    printRate("overlap efficiency", b.overlapEfficiency(), "", "hybrid s/pass / max(sides alone)");
    printRate("GL fragments", b.fragmentsPerPass / 1e6, "M/pass",
        ratio(b.fragmentsPerPass, b.pixelTestsPerPass, "the CPU twin's estimator evaluations"));
    printRate("GL fragment rate", b.fragmentsPerPass / b.glSplatSeconds / 1e6, "M frags/s");
    printRate("GL time per beam", b.glSplatSeconds / b.beamsPerPass * 1e6, "us/beam",
        ratio(b.glSplatSeconds, b.cpuSplatSeconds, "CPU twin"));
}

}  // namespace tyndall::app
