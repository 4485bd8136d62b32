// build/bench/tyndall_stages: every stage of a pass against a baseline measured in the same run
// (Embree alone on the same rays, the other beam BVH kind, the scalar splat, the homogeneous twin
// of a grid medium), the pass rate against its targets, and the hybrid split. What `tyndall bench`
// prints for a user's machine plus the studies behind the design choices (docs/performance.md).
//   build/bench/tyndall_stages [SCENE] [--size WxH] [--passes N] [--photons N] [--threads T] ...
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <thread>

#include "app/cli_common.h"
#include "app/hybrid_split.h"
#include "bench/free_flights.h"
#include "bench/pass_rate_targets.h"
#include "bench/stage_studies.h"
#include "bench/study_cli.h"
#include "cpu/beam_splat_simd.h"
#include "loading/default_smoke_scene.h"
#include "loading/homogeneous_twin.h"

namespace tyndall::bench {
namespace {

using app::printPassRate;
using app::printRate;
using app::ratio;

struct StageOptions {
    app::CommonOptions common;
    int passes = 10;
    uint64_t rays = 4000000;
    uint64_t queries = 200000;
    uint64_t freeFlights = 2000000;
    bool noHybrid = false;
};

void addOptions(CLI::App& cli, StageOptions& o) {
    app::addSceneAndOutputOptions(&cli, o.common, "");
    // Every count divides a rate: 0 would print NaN, so all must be positive.
    cli.add_option("--passes", o.passes, "Passes timed for the passes/s figures")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--photons", o.common.settings.photonsPerPass, "Photon paths per pass")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--rays", o.rays, "Rays for the raw Embree baseline")->check(app::positiveInteger())->capture_default_str();
    cli.add_option("--queries", o.queries, "Beam gather queries per BVH kind")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--free-flights", o.freeFlights, "Free-flight distances sampled per majorant kind")
        ->check(app::positiveInteger())
        ->capture_default_str();
    cli.add_option("--radius", o.common.settings.radius,
                   "Beam radius of the first photon path, scene units (0 = the default schedule's)")
        ->capture_default_str();
    cli.add_option("--radius-offset", o.common.settings.radiusOffset,
                   "Photon paths the radius schedule treats as already traced")
        ->check(app::nonNegativeInteger())
        ->capture_default_str();
    app::addSimdOption(&cli, o.common);
    app::addDirectLightOption(&cli, o.common);
    cli.add_flag("--no-hybrid", o.noHybrid, "Skip the hybrid (GL splat) figures");
}

void printPhotonStudy(const PassRenderer& renderer, int passes, double raw) {
    // The photon stage is ~1 ms a pass: enough passes for a timing well above the clock's noise.
    const int photonPasses = std::max(100, passes);
    std::printf("photon tracing (%d passes of %u paths, best of 3 rounds)\n", photonPasses,
                renderer.settings().photonsPerPass);
    PhotonStageRate ph = measurePhotonStage(renderer, photonPasses, 3);
    printRate("photon paths", ph.tracing.pathsPerSecond / 1e3, "k paths/s");
    printRate("photon beams stored", ph.tracing.beamsPerSecond / 1e3, "k beams/s");
    printRate("photon rays", ph.tracing.raysPerSecond / 1e6, "M rays/s",
              ratio(ph.tracing.raysPerSecond, raw, "raw random-ray rate"));
    printRate("Embree raw, photon rays replayed", ph.replayRaysPerSecond / 1e6, "M rays/s",
              ratio(ph.replayRaysPerSecond, raw, "raw random-ray rate") + " (every ray those passes cast)");
    printRate("  beam rays only", ph.beamReplayRaysPerSecond / 1e6, "M rays/s",
              ratio(ph.beamReplayRaysPerSecond, raw, "raw random-ray rate") + " (the rays that start a beam)");
    printRate("photon rays vs their raw replay", ph.tracing.raysPerSecond / ph.replayRaysPerSecond, "x",
              "(target >= 0.50x; tracing overhead: sampling, beams, surface photons)");
    printRate("  vs the beam rays' replay", ph.tracing.raysPerSecond / ph.beamReplayRaysPerSecond, "x");
}

void printGatherStudy(const PassRenderer& renderer, uint64_t queries) {
    std::printf("beam gather (secondary segments; queries along this pass's primary segments)\n");
    const std::vector<GatherRate> gather =
        measureBeamGather(renderer, {BeamBvh::Kind::UserGeometry, BeamBvh::Kind::FlatCurves}, queries);
    const GatherRate &user = gather[0], &curves = gather[1];
    printRate("user geometry: queries", user.queriesPerSecond / 1e3, "k queries/s",
              "(best of 3 rounds alternating between the kinds)");
    printRate("user geometry: beam hits", user.hitsPerSecond / 1e6, "M hits/s");
    printRate("flat curves: queries", curves.queriesPerSecond / 1e3, "k queries/s",
              ratio(curves.queriesPerSecond, user.queriesPerSecond, "user geometry"));
    printRate("flat curves: beam hits", curves.hitsPerSecond / 1e6, "M hits/s");
    printRate("BVH build: user geometry", user.buildSeconds * 1e3, "ms");
    printRate("BVH build: flat curves", curves.buildSeconds * 1e3, "ms");
}

/// Whole passes (CPU only) judged against the pass-rate targets; returns their rate.
double printPassStudy(const PassRenderer& renderer, int passes, unsigned threads) {
    const RenderSettings& s = renderer.settings();
    std::printf("full passes (CPU only)\n");
    const PassRate pr = measurePasses(renderer, passes);
    printPassRate(pr, s, passRateVerdict(pr.passesPerSecond, s.width, s.height, s.photonsPerPass, threads));
    printRate("Embree alone on the primary rays", measurePrimaryRayReplay(renderer, 1, 3) / 1e6, "M rays/s",
              "(baseline for camera paths/s: pass 1's jittered rays, rtcIntersect1)");
    return pr.passesPerSecond;
}

/// The splat kernels and whole passes with --simd on and off, in the same run.
void printSimdStudy(const Scene& scene, const PassRenderer& renderer, int passes) {
    std::printf("SIMD beam splat (%s) vs the scalar estimator, same beams and pixels\n", splatSimdTarget());
    SplatRate sr = measureSplatKernels(renderer, std::min(passes, 3), 3);
    printRate("scalar splat", sr.scalarEvalsPerSecond / 1e6, "M evals/s");
    printRate("SIMD splat", sr.simdEvalsPerSecond / 1e6, "M evals/s",
              ratio(sr.simdEvalsPerSecond, sr.scalarEvalsPerSecond, "scalar") + " (target >= 4x)");
    RenderSettings scalarSettings = renderer.settings(), simdSettings = renderer.settings();
    scalarSettings.simd = false;
    simdSettings.simd = true;
    PassRenderer scalarRenderer(scene, scalarSettings), simdRenderer(scene, simdSettings);
    PassRate scalarPasses, simdPasses;
    measurePassesAlternating(scalarRenderer, simdRenderer, passes, &scalarPasses, &simdPasses);
    printRate("passes, --simd off", scalarPasses.passesPerSecond, "passes/s", "(alternating pass by pass)");
    printRate("passes, --simd on", simdPasses.passesPerSecond, "passes/s",
              ratio(simdPasses.passesPerSecond, scalarPasses.passesPerSecond, "--simd off"));
    printRate("  splat stage, off / on", scalarPasses.totals.splatSeconds / simdPasses.totals.splatSeconds, "x");
}

void printFreeFlights(const PassRenderer& het, uint64_t count, int perSet) {
    FreeFlightRate grid = measureFreeFlights(het, count, MajorantMode::Grid);
    FreeFlightRate seg = measureFreeFlights(het, count, MajorantMode::Segment);
    FreeFlightRate glob = measureFreeFlights(het, count, MajorantMode::Global);
    FreeFlightRate sets = measureFreeFlights(het, count, MajorantMode::Grid, perSet);
    auto lookups = [](const FreeFlightRate& r) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "(%.2f density lookups each)", r.densityLookupsPerSample);
        return std::string(buf);
    };
    printRate("free flights: majorant grid (DDA)", grid.samplesPerSecond / 1e6, "M samples/s", lookups(grid));
    char setName[64];
    std::snprintf(setName, sizeof setName, "free flights: sets of %d (as passes)", perSet);
    printRate(setName, sets.samplesPerSecond / 1e6, "M samples/s",
              ratio(sets.samplesPerSecond, grid.samplesPerSecond, "one at a time"));
    printRate("free flights: one bound per segment", seg.samplesPerSecond / 1e6, "M samples/s",
              ratio(seg.samplesPerSecond, grid.samplesPerSecond, "majorant grid ") + lookups(seg));
    printRate("free flights: global maximum", glob.samplesPerSecond / 1e6, "M samples/s",
              ratio(glob.samplesPerSecond, grid.samplesPerSecond, "majorant grid ") + lookups(glob));
}

/// Heterogeneous media: the built-in smoke scene against the fog scene (`fogPassesPerSecond`), or
/// a scene's own grid media against their homogeneous twin. Nothing when there is no grid medium.
void printGridMediaStudy(const StageOptions& o, const Scene& scene, double fogPassesPerSecond) {
    const RenderSettings& s = o.common.settings;
    const bool builtIn = o.common.scene.empty();
    Scene het = builtIn ? makeDefaultSmokeScene() : scene;
    bool anyGrid = false;
    for (const Medium& m : het.media) anyGrid |= !m.homogeneous();
    if (!anyGrid) return;
    std::vector<float> twinDensity;
    // The twin fills the grid medium's whole domain: the baseline covers the same extent of medium.
    Scene twin = makeHomogeneousTwin(het, -1.0f, &twinDensity, TwinRegion::Domain);
    PassRenderer hetRenderer(het, s), twinRenderer(twin, s);
    std::printf("heterogeneous media (%s)\n", builtIn ? "built-in smoke scene; baseline: the fog scene above"
                                                      : "this scene's grids; baseline: their homogeneous twin");
    PassRate hp = measurePasses(hetRenderer, o.passes);
    PassRate tp = measurePasses(twinRenderer, o.passes);
    const double perPassRatio = (builtIn ? fogPassesPerSecond : tp.passesPerSecond) / hp.passesPerSecond;
    printRate("passes: grid medium", hp.passesPerSecond, "passes/s");
    char twinName[64];
    std::snprintf(twinName, sizeof twinName, "passes: homogeneous twin (%.3g)", twinDensity.front());
    printRate(twinName, tp.passesPerSecond, "passes/s");
    printRate("time per pass, grid / baseline", perPassRatio, "x",
              perPassRatio <= 2.0 ? "(target <= 2: met)" : "(target <= 2: NOT met)");
    printRate("  photon stage", hp.totals.photonSeconds / hp.passes * 1e3, "ms/pass");
    printRate("  camera stage", hp.totals.cameraSeconds / hp.passes * 1e3, "ms/pass");
    printRate("  primary splat stage", hp.totals.splatSeconds / hp.passes * 1e3, "ms/pass");
    printFreeFlights(hetRenderer, o.freeFlights, s.freeFlightSamples);
    printRate("free flights per pass (camera)", double(s.width) * s.height * s.freeFlightSamples / 1e6, "M samples",
              "(n per pixel, plus n per beam)");
}

void run(StageOptions& o) {
    app::finishOptions(o.common);
    const RenderSettings& s = o.common.settings;
    Scene scene = app::loadScene(o.common);
    app::ThreadLimit threads(s.threads);
    PassRenderer renderer(scene, s);
    const unsigned hw = s.threads > 0 ? unsigned(s.threads) : std::thread::hardware_concurrency();
    std::printf("tyndall_stages: scene '%s', %dx%d, %u photon paths/pass, %u threads\n", scene.name.c_str(), s.width,
                s.height, s.photonsPerPass, hw);
    const double raw = measureRawRayRate(renderer.rayTracer(), o.rays);
    std::printf("baseline\n");
    printRate("Embree raw incoherent rays", raw / 1e6, "M rays/s");
    printPhotonStudy(renderer, o.passes, raw);
    printGatherStudy(renderer, o.queries);
    const double passesPerSecond = printPassStudy(renderer, o.passes, hw);
    printSimdStudy(scene, renderer, o.passes);
    if (!o.noHybrid) app::printHybridSplit(app::measureHybridSplit(renderer, o.passes));
    printGridMediaStudy(o, scene, passesPerSecond);
}

}  // namespace
}  // namespace tyndall::bench

int main(int argc, char** argv) {
    CLI::App cli{"Every stage of a pass against a baseline from the same run (default scene, 512x512)",
                 "tyndall_stages"};
    tyndall::bench::StageOptions o;
    o.common.settings.photonsPerPass = 1000;
    tyndall::bench::addOptions(cli, o);
    return tyndall::bench::runStudy(cli, argc, argv, [&o] { tyndall::bench::run(o); });
}
