#include "app/cmd_bench.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <thread>

#include "app/cli_common.h"
#include "app/hybrid_split.h"
#include "app/stage_rates.h"
#include "core/error.h"

namespace tyndall::app {

namespace {
struct BenchOptions {
    CommonOptions common;
    int passes = 10;
    bool noHybrid = false;
};

void addOptions(CLI::App* cmd, BenchOptions& o) {
    addSceneAndOutputOptions(cmd, o.common, "");
    // Every count divides a rate: 0 would print NaN, so all must be positive.
    cmd->add_option("--passes", o.passes, "Passes timed for the passes/s figures")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--photons", o.common.settings.photonsPerPass, "Photon paths per pass")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--radius", o.common.settings.radius,
                    "Beam radius of the first photon path, scene units (0 = the default schedule's)")
        ->capture_default_str();
    cmd->add_option("--radius-offset", o.common.settings.radiusOffset,
                    "Photon paths the radius schedule treats as already traced")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    addSimdOption(cmd, o.common);
    addDirectLightOption(cmd, o.common);
    cmd->add_flag("--no-hybrid", o.noHybrid, "Skip the hybrid (GL splat) figures");
}

void printPhotonStage(const PassRenderer& renderer, int passes) {
    // The photon stage is ~1 ms a pass: enough passes for a timing well above the clock's and the
    // scheduler's noise, at the renderer's own pass size.
    const int photonPasses = std::max(100, passes);
    std::printf("photon tracing (%d passes of %u paths, best of 3 rounds)\n", photonPasses,
                renderer.settings().photonsPerPass);
    PhotonRate ph = measurePhotonTracing(renderer, photonPasses, 3);
    printRate("photon paths", ph.pathsPerSecond / 1e3, "k paths/s");
    printRate("photon beams stored", ph.beamsPerSecond / 1e3, "k beams/s");
    printRate("photon rays", ph.raysPerSecond / 1e6, "M rays/s");
    printRate("beams per photon path", ph.beamsPerPath, "beams");
    printRate("mean beam length", ph.meanBeamLength, "scene units");
}

void printPasses(const PassRenderer& renderer, int passes) {
    const RenderSettings& s = renderer.settings();
    std::printf("full passes (CPU only, --simd %s)\n", onOffText(s.simd));
    printPassRate(measurePasses(renderer, passes), s);
}
}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<BenchOptions>();
    o->common.settings.photonsPerPass = 1000;
    CLI::App* cmd = app.add_subcommand(
        "bench", "Measure this machine: throughput of every stage and the CPU/GL split (default scene, 512x512)");
    addOptions(cmd, *o);
    cmd->callback([o, &exitCode]() {
        finishOptions(o->common);
        const RenderSettings& s = o->common.settings;
        Scene scene = loadScene(o->common);
        ThreadLimit threads(s.threads);
        PassRenderer renderer(scene, s);
        unsigned hw = s.threads > 0 ? unsigned(s.threads) : std::thread::hardware_concurrency();
        std::printf("tyndall bench: scene '%s', %dx%d, %u photon paths/pass, %u threads\n", scene.name.c_str(), s.width,
                    s.height, s.photonsPerPass, hw);
        const uint64_t offset = renderer.radii().schedule.offset();  // resolved: the automatic one too
        std::printf("  first beam radius %.6g (%.3g%% of the scene diagonal), radius offset %llu%s\n",
                    renderer.radii().beamRadius, 100.0 * renderer.radii().beamRadius / length(scene.bounds.diagonal()),
                    (unsigned long long)offset, offset == s.radiusOffset ? "" : " (automatic)");
        printPhotonStage(renderer, o->passes);
        printPasses(renderer, o->passes);
        if (!o->noHybrid) {
            try {
                printHybridSplit(measureHybridSplit(renderer, o->passes));
            } catch (const Error& e) {
                std::printf("hybrid: skipped (%s)\n", e.what());
            }
        }
        exitCode = 0;
    });
}

}  // namespace tyndall::app
