#include "app/cmd_bench.h"

#include <cstdio>
#include <memory>
#include <thread>

#include "app/bench_cpu.h"
#include "app/bench_hybrid.h"
#include "app/bench_media.h"
#include "app/bench_quality.h"
#include "app/bench_targets.h"
#include "app/cli_common.h"
#include "cpu/beam_splat_simd.h"
#include "loading/default_smoke_scene.h"

namespace tyndall::app {

namespace {
struct BenchOptions {
    CommonOptions common;
    int passes = 10;
    uint64_t rays = 4000000;
    uint64_t queries = 200000;
    uint64_t freeFlights = 2000000;
    bool noHybrid = false;
    bool quality = false;
    QualityBenchOptions qualityOptions;
};

void printRate(const char* what, double value, const char* unit, const std::string& note = "") {
    std::printf("  %-34s %12.3f %-12s %s\n", what, value, unit, note.c_str());
}
std::string ratio(double value, double base, const char* baseName) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "= %.2fx %s", value / base, baseName);
    return buf;
}
}  // namespace

void addBenchCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<BenchOptions>();
    o->common.settings.photonsPerPass = 1000;
    CLI::App* cmd = app.add_subcommand("bench", "Measure the throughput of every stage (default scene, 512x512)");
    addSceneAndOutputOptions(cmd, o->common, "");
    // Every count divides a rate: 0 would print NaN, so all must be positive.
    cmd->add_option("--passes", o->passes, "Passes timed for the passes/s figure")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--photons", o->common.settings.photonsPerPass, "Photon paths per pass")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--rays", o->rays, "Rays for the raw Embree baseline")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--queries", o->queries, "Beam gather queries per BVH kind")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--free-flights", o->freeFlights, "Free-flight distances sampled per majorant kind")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--radius", o->common.settings.radius,
                    "Beam radius of the first photon path, scene units (0 = the default schedule's)")
        ->capture_default_str();
    cmd->add_option("--radius-offset", o->common.settings.radiusOffset,
                    "Photon paths the radius schedule treats as already traced")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    addSimdOption(cmd, o->common);
    addDirectLightOption(cmd, o->common);
    cmd->add_flag("--no-hybrid", o->noHybrid, "Skip the hybrid (GL splat) figures");
    cmd->add_flag("--quality", o->quality,
                  "Instead of throughput: image error against cached path-traced references, legacy against "
                  "automatic radii at equal work (docs/performance.md, 'Equal-work quality'); --photons "
                  "defaults to 4000 here");
    o->qualityOptions.scenes = {"bench/scenes/fog-box.json:1584", "bench/scenes/walls-fog-box.json:421",
                                "bench/scenes/fog-lamp-box.json:1584"};
    cmd->add_option("--quality-scene", o->qualityOptions.scenes,
                    "With --quality: FILE:PASSES (or FILE with --quality-cpu-seconds), repeatable (default: bench/scenes' fog box and fog box with a lamp "
                    "in view at 1584 passes and the box with walls at 421: 60 s at 256x256 on an idle 2-core machine)");
    cmd->add_option("--reference-dir", o->qualityOptions.referenceDir, "With --quality: the reference cache")
        ->capture_default_str();
    cmd->add_option("--reference-spp", o->qualityOptions.referenceSpp,
                    "With --quality: samples per pixel of a reference rendered when not cached")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--quality-seeds", o->qualityOptions.seeds,
                    "With --quality: render each setting with this many seeds; errors are their root mean square")
        ->check(positiveInteger())
        ->capture_default_str();
    cmd->add_option("--quality-cpu-seconds", o->qualityOptions.cpuSeconds,
                    "With --quality: equal time instead of equal work: every render stops when its passes' process "
                    "CPU time reaches this many seconds (CPU time for wall time on a shared machine; 117 = 60 s wall "
                    "with 2 threads on an idle 2-core machine); --quality-scene's :PASSES is then optional and adds "
                    "a row planned for it (default: 0, equal work)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--quality-library", o->qualityOptions.library,
                    "With --quality and --quality-cpu-seconds: also every scene file in this folder (scenes/), its "
                    "mirrors and glass made index-matched so that the path tracer is valid; replaces the default "
                    "--quality-scene list unless one is given (default: none)");
    cmd->add_option("--quality-images", o->qualityOptions.imageDir,
                    "With --quality: write every row's final image per seed, <dir>/<scene>-<row>-seed<N>.exr, "
                    "to look at beside the reference (default: none)");
    cmd->add_option("--plot", o->qualityOptions.plot,
                    "With --quality: write the error plot (PNG): against passes, or against CPU seconds with "
                    "--quality-cpu-seconds (default: none)");
    cmd->callback([o, &exitCode]() {
        if (o->quality) {
            if (o->common.command->get_option("--photons")->count() == 0) o->common.settings.photonsPerPass = 4000;
            if (o->common.command->get_option("--size")->count() == 0) o->common.size = "256x256";
            if (!o->qualityOptions.library.empty() && o->common.command->get_option("--quality-scene")->count() == 0)
                o->qualityOptions.scenes.clear();
            if (!o->qualityOptions.library.empty() && !(o->qualityOptions.cpuSeconds > 0))
                throw CLI::ValidationError("--quality-library", "needs --quality-cpu-seconds (library scenes have no pass count)");
            finishOptions(o->common);
            ThreadLimit threads(o->common.settings.threads);
            runQualityBench(o->common, o->qualityOptions);
            exitCode = 0;
            return;
        }
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

        double raw = measureRawRayRate(renderer.rayTracer(), o->rays);
        std::printf("baseline\n");
        printRate("Embree raw incoherent rays", raw / 1e6, "M rays/s");

        // The photon stage is ~1 ms a pass: enough passes for a timing well above the clock's
        // and the scheduler's noise, at the renderer's own pass size.
        const int photonPasses = std::max(100, o->passes);
        std::printf("photon tracing (%d passes of %u paths, best of 3 rounds)\n", photonPasses, s.photonsPerPass);
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

        std::printf("beam gather (secondary segments; queries along this pass's primary segments)\n");
        const std::vector<GatherRate> gather =
            measureBeamGather(renderer, {BeamBvh::Kind::UserGeometry, BeamBvh::Kind::FlatCurves}, o->queries);
        const GatherRate &user = gather[0], &curves = gather[1];
        printRate("user geometry: queries", user.queriesPerSecond / 1e3, "k queries/s",
                  "(best of 3 rounds alternating between the kinds)");
        printRate("user geometry: beam hits", user.hitsPerSecond / 1e6, "M hits/s");
        printRate("flat curves: queries", curves.queriesPerSecond / 1e3, "k queries/s",
                  ratio(curves.queriesPerSecond, user.queriesPerSecond, "user geometry"));
        printRate("flat curves: beam hits", curves.hitsPerSecond / 1e6, "M hits/s");
        printRate("BVH build: user geometry", user.buildSeconds * 1e3, "ms");
        printRate("BVH build: flat curves", curves.buildSeconds * 1e3, "ms");

        std::printf("full passes (CPU only)\n");
        PassRate pr = measurePasses(renderer, o->passes);
        double perPass = 1.0 / pr.passesPerSecond;
        double pixels = double(s.width) * s.height * pr.passes;
        printRate("passes", pr.passesPerSecond, "passes/s",
                  passRateVerdict(pr.passesPerSecond, s.width, s.height, s.photonsPerPass, hw));
        printRate("camera paths", pixels / pr.totals.cameraSeconds / 1e6, "M paths/s");
        printRate("secondary gather queries", pr.totals.beamQueries / pr.totals.cameraSeconds / 1e3, "k queries/s",
                  "(inside the camera pass)");
        printRate("primary splat estimator evals", pr.totals.rasterTests / pr.totals.splatSeconds / 1e6, "M evals/s");
        printRate("  photon stage", pr.totals.photonSeconds / pr.passes * 1e3, "ms/pass",
                  ratio(pr.totals.photonSeconds / pr.passes, perPass, "of a pass"));
        printRate("  camera stage", pr.totals.cameraSeconds / pr.passes * 1e3, "ms/pass",
                  ratio(pr.totals.cameraSeconds / pr.passes, perPass, "of a pass"));
        printRate("  primary splat stage", pr.totals.splatSeconds / pr.passes * 1e3, "ms/pass",
                  ratio(pr.totals.splatSeconds / pr.passes, perPass, "of a pass"));
        printRate("beams per pass", double(pr.totals.beams) / pr.passes, "beams");
        printRate("Embree alone on the primary rays", measurePrimaryRayReplay(renderer, 1, 3) / 1e6, "M rays/s",
                  "(baseline for camera paths/s: pass 1's jittered rays, rtcIntersect1)");

        // The splat kernels and whole passes with --simd on and off, in the same run.
        std::printf("SIMD beam splat (%s) vs the scalar estimator, same beams and pixels\n", splatSimdTarget());
        SplatRate sr = measureSplatKernels(renderer, std::min(o->passes, 3), 3);
        printRate("scalar splat", sr.scalarEvalsPerSecond / 1e6, "M evals/s");
        printRate("SIMD splat", sr.simdEvalsPerSecond / 1e6, "M evals/s",
                  ratio(sr.simdEvalsPerSecond, sr.scalarEvalsPerSecond, "scalar") + " (target >= 4x)");
        RenderSettings scalarSettings = s, simdSettings = s;
        scalarSettings.simd = "off";
        simdSettings.simd = "on";
        PassRenderer scalarRenderer(scene, scalarSettings), simdRenderer(scene, simdSettings);
        PassRate scalarPasses, simdPasses;
        measurePassesAlternating(scalarRenderer, simdRenderer, o->passes, &scalarPasses, &simdPasses);
        printRate("passes, --simd off", scalarPasses.passesPerSecond, "passes/s", "(alternating pass by pass)");
        printRate("passes, --simd on", simdPasses.passesPerSecond, "passes/s",
                  ratio(simdPasses.passesPerSecond, scalarPasses.passesPerSecond, "--simd off"));
        printRate("  splat stage, off / on", scalarPasses.totals.splatSeconds / simdPasses.totals.splatSeconds, "x");
        if (!o->noHybrid) printHybridBench(measureHybrid(renderer, o->passes));

        // Heterogeneous media: the built-in smoke scene against this (fog) scene, or a scene's own
        // grid media against their homogeneous twin.
        bool builtIn = o->common.scene.empty();
        Scene het = builtIn ? makeDefaultSmokeScene() : scene;
        bool anyGrid = false;
        for (const Medium& m : het.media) anyGrid |= !m.homogeneous();
        if (anyGrid) {
            std::vector<float> twinDensity;
            Scene twin = makeHomogeneousTwin(het, -1.0f, &twinDensity);
            PassRenderer hetRenderer(het, s), twinRenderer(twin, s);
            std::printf("heterogeneous media (%s)\n", builtIn ? "built-in smoke scene; baseline: the fog scene above"
                                                              : "this scene's grids; baseline: their homogeneous twin");
            PassRate hp = measurePasses(hetRenderer, o->passes);
            PassRate tp = measurePasses(twinRenderer, o->passes);
            double base = builtIn ? pr.passesPerSecond : tp.passesPerSecond;
            double perPassRatio = base / hp.passesPerSecond;
            printRate("passes: grid medium", hp.passesPerSecond, "passes/s");
            char twinName[64];
            std::snprintf(twinName, sizeof twinName, "passes: homogeneous twin (%.3g)", twinDensity.front());
            printRate(twinName, tp.passesPerSecond, "passes/s");
            printRate("time per pass, grid / baseline", perPassRatio, "x",
                      perPassRatio <= 2.0 ? "(target <= 2: met)" : "(target <= 2: NOT met)");
            printRate("  photon stage", hp.totals.photonSeconds / hp.passes * 1e3, "ms/pass");
            printRate("  camera stage", hp.totals.cameraSeconds / hp.passes * 1e3, "ms/pass");
            printRate("  primary splat stage", hp.totals.splatSeconds / hp.passes * 1e3, "ms/pass");
            FreeFlightRate grid = measureFreeFlights(hetRenderer, o->freeFlights, MajorantMode::Grid);
            FreeFlightRate seg = measureFreeFlights(hetRenderer, o->freeFlights, MajorantMode::Segment);
            FreeFlightRate glob = measureFreeFlights(hetRenderer, o->freeFlights, MajorantMode::Global);
            auto lookups = [](const FreeFlightRate& r) {
                char buf[64];
                std::snprintf(buf, sizeof buf, "(%.2f density lookups each)", r.densityLookupsPerSample);
                return std::string(buf);
            };
            FreeFlightRate sets =
                measureFreeFlights(hetRenderer, o->freeFlights, MajorantMode::Grid, s.freeFlightSamples);
            printRate("free flights: majorant grid (DDA)", grid.samplesPerSecond / 1e6, "M samples/s", lookups(grid));
            char setName[64];
            std::snprintf(setName, sizeof setName, "free flights: sets of %d (as passes)", s.freeFlightSamples);
            printRate(setName, sets.samplesPerSecond / 1e6, "M samples/s",
                      ratio(sets.samplesPerSecond, grid.samplesPerSecond, "one at a time"));
            printRate("free flights: one bound per segment", seg.samplesPerSecond / 1e6, "M samples/s",
                      ratio(seg.samplesPerSecond, grid.samplesPerSecond, "majorant grid ") + lookups(seg));
            printRate("free flights: global maximum", glob.samplesPerSecond / 1e6, "M samples/s",
                      ratio(glob.samplesPerSecond, grid.samplesPerSecond, "majorant grid ") + lookups(glob));
            printRate("free flights per pass (camera)", double(s.width) * s.height * s.freeFlightSamples / 1e6,
                      "M samples", "(n per pixel, plus n per beam)");
        }
        exitCode = 0;
    });
}

}  // namespace tyndall::app
