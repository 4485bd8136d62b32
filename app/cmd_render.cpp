#include "app/cmd_render.h"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "app/cli_common.h"
#include "app/convergence_log.h"
#include "app/interrupt.h"
#include "app/mpi_ranks.h"
#include "app/progress_meter.h"
#include "app/render_checkpoint.h"
#include "app/render_rounds.h"
#include "core/error.h"
#include "cpu/memory_plan.h"
#include "cpu/radius_defaults.h"
#include "hybrid/pass_scheduler.h"

namespace tyndall::app {

namespace {
struct RenderOptions {
    CommonOptions common;
    std::string checkpoint;
    double checkpointEvery = 60;
    std::string resume;
    bool quiet = false;
    double progressEvery = 5;
    bool aov = false;
    std::string reference;
    std::string convergence;
};

ImageMetadata renderMetadata(const Scene& scene, const RenderSettings& s, const RadiusSetup& radii,
                             const LayerAccumulator& acc, int ranks) {
    nlohmann::json j = s.toJson();
    j["resolved_radius"] = radii.beamRadius;
    j["resolved_surface_radius"] = radii.surfaceRadius;
    return {{"Software", "tyndall"},
            {"tyndall:scene", scene.source},
            {"tyndall:settings", j.dump()},
            {"tyndall:passes", std::to_string(acc.passCount())},
            {"tyndall:photon_paths", std::to_string(acc.passCount() * s.photonsPerPass)},
            {"tyndall:ranks", std::to_string(ranks)},
            {"tyndall:rejected_samples", std::to_string(acc.beauty().rejectedSamples())}};
}

bool given(const CLI::App* cmd, const char* name) {
    const CLI::Option* opt = cmd->get_option_no_throw(name);
    return opt && opt->count() > 0;
}

/// --resume takes everything that shapes the passes from the checkpoint: options that would
/// change them are refused rather than silently ignored.
void rejectWithResume(const CLI::App* cmd) {
    static const char* kFixed[] = {"scene",           "--camera",        "--size",         "--seed",
                                   "--photons",       "--alpha",         "--radius",       "--surface-radius",
                                   "--radius-offset", "--free-flights",  "--exposure",     "--aov",
                                   "--photon-angle",  "--planned-paths", "--direct-light", "--surface-boundary",
                                   "--environment",   "--max-path-length"};
    for (const char* name : kFixed)
        if (given(cmd, name))
            throw Error(std::string("--resume: ") + (name[0] == '-' ? name : "the scene file") +
                        " comes from the checkpoint and cannot be changed (only -o, --passes, --time, --threads, "
                        "--gpu, --checkpoint, --checkpoint-every, --quiet, --progress-every and the convergence "
                        "log may be given)");
}

// Test hooks (environment variables read only here, unset in normal use; docs/production.md,
// "Test hooks"). They let the kill-and-resume tests stop a render at a chosen point and wait for
// the test's signal, so what a test sees never depends on how fast the machine is.
//   TYNDALL_TEST_CHECKPOINT_STALL_AT=K: the K-th checkpoint write of this run stops halfway
//     through its temporary file and waits there until the process is killed or interrupted.
//   TYNDALL_TEST_HOLD_AFTER_PASS=N: once the render holds N passes (resumed ones included) it
//     waits, still writing its periodic checkpoints, until it is killed or interrupted.
// Both give up waiting after kTestHoldLimit (a test that forgot to kill does not hang forever).
constexpr double kTestHoldLimit = 300;

uint64_t testHookValue(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? std::strtoull(v, nullptr, 10) : 0;
}

/// Sleeps in short steps until an interrupt or kTestHoldLimit seconds; `tick` runs at every step.
void holdForTests(const std::function<void()>& tick) {
    const auto start = std::chrono::steady_clock::now();
    while (!interruptRequested() &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < kTestHoldLimit) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (tick) tick();
    }
}

std::function<void()> checkpointStallForTests() {
    const uint64_t at = testHookValue("TYNDALL_TEST_CHECKPOINT_STALL_AT");
    if (!at) return {};
    return [at, writes = uint64_t(0)]() mutable {
        if (++writes == at) holdForTests({});
    };
}

/// Error before rendering when the checkpoint's directory is missing or not writable.
void checkCheckpointWritable(const std::string& path) {
    std::string dir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/') + 1);
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error("--checkpoint '" + path + "': directory '" + dir + "' does not exist or is not writable");
}

void runRender(RenderOptions& o, CLI::App* cmd, int& exitCode) {
    Ranks& ranks = Ranks::world();
    const bool root = ranks.rank() == 0;
    CommonOptions& c = o.common;
    RenderRecord record;
    std::optional<LayerAccumulator> acc;
    Scene scene;
    if (o.resume.empty()) {
        finishOptions(c);
        if (root) checkOutputWritable(c.output);
        scene = loadScene(c);
        {
            // The automatic radii become plain numbers here, once, so a resume or another MPI rank
            // renders with the same ones whatever share of the target it runs. A --time budget plans
            // for the open-ended horizon (a measured rate would differ between ranks and resumes).
            const EmbreeScene rt(scene);
            c.settings = resolveRadiusDefaults(c.settings, rt);
        }
        record = {c.scene, c.camera, sceneHash(c.scene, scene), c.settings, c.output, c.exposure, o.aov, 0.0};
        record.environment = c.environment;
        allocating("the accumulator of a " + std::to_string(c.settings.width) + "x" +
                       std::to_string(c.settings.height) + " image",
                   accumulatorBytes(c.settings, o.aov),
                   [&] { acc.emplace(c.settings.width, c.settings.height, o.aov); });
    } else {
        // Nothing is written before every check passed: a bad resume leaves the checkpoint as it was.
        rejectWithResume(cmd);
        const std::string where = "checkpoint '" + o.resume + "'";
        Checkpoint ck = loadCheckpoint(o.resume);
        record = readRecord(ck, where);
        c.scene = record.scenePath;
        c.camera = record.camera;
        c.environment = record.environment;
        scene = loadScene(c);
        const uint64_t hash = sceneHash(record.scenePath, scene);
        if (hash != record.sceneHash)
            throw Error(where + " was made from a different scene: '" +
                        (record.scenePath.empty() ? std::string("<built-in default scene>") : record.scenePath) +
                        "' changed since (hash " + hashText(hash) + ", the checkpoint's " + hashText(record.sceneHash) +
                        "); render it afresh");
        acc.emplace(LayerAccumulator::fromNamed(std::move(ck.layers), record.aov, where));
        if (acc->beauty().width() != record.settings.width || acc->beauty().height() != record.settings.height)
            throw Error(where + ": its image size does not match its settings");
        if (given(cmd, "--passes")) {
            if (c.settings.passes <= acc->passCount())
                throw Error("--passes " + std::to_string(c.settings.passes) + ": " + where + " already holds " +
                            std::to_string(acc->passCount()) + " passes (the target is the total)");
            record.settings.passes = c.settings.passes;
            record.settings.timeBudget = 0;
        }
        if (given(cmd, "--time")) record.settings.timeBudget = c.settings.timeBudget;
        if (given(cmd, "--threads")) record.settings.threads = c.settings.threads;
        if (given(cmd, "--gpu")) record.settings.gpu = c.settings.gpu;
        if (given(cmd, "-o")) {
            record.output = c.output;
            if (root) checkOutputWritable(record.output);
        }
        if (o.checkpoint.empty()) o.checkpoint = o.resume;
        c.settings = record.settings;
    }
    const RenderSettings& s = record.settings;
    if (root && !o.checkpoint.empty()) checkCheckpointWritable(o.checkpoint);
    if (o.reference.empty() != o.convergence.empty())
        throw Error("--reference and --convergence go together (the CSV logs the error against the reference)");
    std::unique_ptr<ConvergenceLog> log;
    if (root && !o.reference.empty()) log = std::make_unique<ConvergenceLog>(o.reference, o.convergence, s.width, s.height);

    ThreadLimit threads(s.threads);
    const uint64_t passesBefore = acc->passCount();
    const double elapsedBefore = record.elapsed;
    // This run's share of the target.
    RenderSettings run = s;
    run.passes = s.timeBudget > 0 ? s.passes : s.passes - std::min(s.passes, passesBefore);
    run.timeBudget = s.timeBudget > 0 ? std::max(s.timeBudget - elapsedBefore, 1e-9) : 0;
    // A pass does not depend on the target: the same bits as with `s`. The AOV layers' buffers
    // count in the memory plan (record.aov: the same plan when resumed).
    PassRenderer renderer(scene, run, BeamBvh::Kind::FlatCurves, record.aov);
    if (root && renderer.memoryPlan().batches > 1)
        std::fprintf(stderr, "tyndall: %s\n", renderer.memoryPlan().describe().c_str());

    // The hybrid GL scheduler for a single process without layers; rounds otherwise.
    const bool rounds = o.aov || ranks.distributed();
    std::unique_ptr<PassScheduler> scheduler;
    if (!rounds) {
        scheduler = std::make_unique<PassScheduler>(s.gpu);
        scheduler->bind(scene);
        if (!scheduler->notice().empty()) std::fprintf(stderr, "tyndall: %s\n", scheduler->notice().c_str());
    } else if (s.gpu == GpuMode::On) {
        throw Error("--gpu on: --aov and mpirun renders splat on the CPU (use --gpu auto or off)");
    }

    installInterruptHandler();
    ProgressMeter progress(stderr, root ? progressStyleFor(stderr, o.quiet) : ProgressStyle::Quiet,
                           {s.passes, run.timeBudget, passesBefore}, o.progressEvery);
    auto stall = checkpointStallForTests();
    using Clock = std::chrono::steady_clock;
    auto lastCheckpoint = Clock::now();
    double runElapsed = 0;
    // `layers` is the whole state; null in the scheduler's case, where `beauty` is.
    auto writeCheckpoint = [&](const Accumulator& beauty, const LayerAccumulator* layers) {
        record.elapsed = elapsedBefore + runElapsed;
        std::vector<std::pair<std::string, Accumulator>> sums;
        if (layers)
            sums = layers->named();
        else
            sums.emplace_back("beauty", beauty);
        saveCheckpoint(o.checkpoint, makeCheckpoint(record, std::move(sums)), stall);
        lastCheckpoint = Clock::now();
    };
    auto checkpointIfDue = [&](const Accumulator& beauty, const LayerAccumulator* layers) {
        if (o.checkpoint.empty() ||
            std::chrono::duration<double>(Clock::now() - lastCheckpoint).count() < o.checkpointEvery)
            return;
        try {
            writeCheckpoint(beauty, layers);
        } catch (const Error& e) {
            std::fprintf(stderr, "\ntyndall: warning: %s (rendering goes on)\n", e.what());
        }
    };
    const uint64_t holdAfterPass = testHookValue("TYNDALL_TEST_HOLD_AFTER_PASS");
    auto onPass = [&](const Accumulator& beauty, const LayerAccumulator* layers, const RenderProgress& p) {
        runElapsed = p.elapsedSeconds;
        progress.update(p.passesDone, p.elapsedSeconds);
        const uint64_t paths = beauty.passCount() * s.photonsPerPass;
        if (log)
            log->add(beauty, {beauty.passCount(), elapsedBefore + p.elapsedSeconds, paths,
                              renderer.radii().beamRadiusOf(paths ? paths - 1 : 0)});
        checkpointIfDue(beauty, layers);
        if (holdAfterPass && beauty.passCount() == holdAfterPass)
            holdForTests([&] { checkpointIfDue(beauty, layers); });
        return !interruptRequested();
    };

    RenderProgress p;
    if (scheduler) {
        Accumulator beauty = acc->beauty();
        acc.reset();  // one copy of the sums during the render, as the memory plan counts
        CallbackDisplay display([&](const Accumulator& a, const RenderProgress& pr) {
            return onPass(a, nullptr, pr) ? DisplayCommand::Continue : DisplayCommand::Exit;
        });
        p = scheduler->run(renderer, beauty, passesBefore, display);
        acc.emplace(LayerAccumulator::fromNamed({{"beauty", std::move(beauty)}}, false, "render"));
    } else {
        p = renderRounds(renderer, *acc, passesBefore, {run.passes, run.timeBudget}, ranks,
                         [&](const LayerAccumulator& a, const RenderProgress& pr) { return onPass(a.beauty(), &a, pr); });
    }
    runElapsed = p.elapsedSeconds;
    progress.finish();
    if (!root) return;

    const bool interrupted = interruptRequested();
    writeImageLayers(record.output, acc->beauty().mean(), acc->imageLayers(),
                     renderMetadata(scene, s, renderer.radii(), *acc, ranks.size()), record.exposure);
    if (!o.checkpoint.empty()) writeCheckpoint(acc->beauty(), &*acc);
    const uint64_t rejected = acc->beauty().rejectedSamples();
    if (rejected)
        std::fprintf(stderr, "tyndall: warning: %llu pixel samples were NaN or infinite and were left out\n",
                     (unsigned long long)rejected);
    std::string how = ranks.distributed() ? std::to_string(ranks.size()) + " ranks"
                      : scheduler && scheduler->hybrid() ? "hybrid, " + scheduler->glDescription()
                                                        : std::string("CPU");
    std::printf("rendered %s: %llu passes, %llu photon paths, %llu beams, %.2f s (%.2f passes/s, %s)%s -> %s\n",
                scene.name.c_str(), (unsigned long long)acc->passCount(), (unsigned long long)p.totals.photonPaths,
                (unsigned long long)p.totals.beams, p.elapsedSeconds, p.passesDone / std::max(p.elapsedSeconds, 1e-9),
                how.c_str(), interrupted ? " [interrupted]" : "", record.output.c_str());
    if (!o.checkpoint.empty()) std::printf("checkpoint -> %s\n", o.checkpoint.c_str());
    exitCode = interrupted ? 130 : 0;
}
}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene with progressive photon beams");
    addSceneAndOutputOptions(cmd, o->common, "tyndall.png");
    addPpbOptions(cmd, o->common);
    addPathLengthOption(cmd, o->common);
    addGpuOption(cmd, o->common,
                 "Primary-beam splatting on OpenGL: auto (a hardware GPU when there is one, else the CPU), "
                 "on (OpenGL or fail; llvmpipe counts), off (CPU only, never touches OpenGL)");
    cmd->add_option("--checkpoint", o->checkpoint,
                    "Save the render's state to FILE every --checkpoint-every seconds, on Ctrl-C/SIGTERM and at the "
                    "end (atomically: a kill leaves the old or the new file) (default: none, no checkpoints)");
    cmd->add_option("--checkpoint-every", o->checkpointEvery, "Seconds between checkpoints")
        ->check(positiveNumber())
        ->capture_default_str();
    cmd->add_option("--resume", o->resume,
                    "Continue the render saved in FILE (scene, settings and output from it; -o, --passes N (total) or "
                    "--time S (total seconds) may change them); it keeps checkpointing to FILE (default: none, a new render)");
    cmd->add_flag("-q,--quiet", o->quiet, "No progress output (the final summary line stays)");
    cmd->add_option("--progress-every", o->progressEvery,
                    "Seconds between progress lines when stderr is not a terminal (0 = every pass)")
        ->check(CLI::Validator(
            [](std::string& v) {
                char* end = nullptr;
                double x = std::strtod(v.c_str(), &end);
                return end != v.c_str() && *end == '\0' && !(x >= 0 && std::isfinite(x))
                           ? "expected a number of seconds >= 0, got '" + v + "'"
                           : std::string();
            },
            "", "non-negative"))
        ->capture_default_str();
    cmd->add_flag("--aov", o->aov,
                  "EXR output gets layers media_primary, media_secondary, surface (they add up to R,G,B) and variance");
    cmd->add_option("--reference", o->reference, "Reference image (same size) for the --convergence log (default: none)");
    cmd->add_option("--convergence", o->convergence,
                    "CSV: per pass elapsed time, photon paths, beam radius, relative RMSE and bias against --reference "
                    "(default: none)");
    cmd->callback([o, cmd, &exitCode]() {
        try {
            runRender(*o, cmd, exitCode);
        } catch (const Error&) {
            if (Ranks::world().distributed() && Ranks::world().rank() != 0) {
                // Rank 0 reports the same error (every rank read the same input); stay quiet.
                exitCode = 1;
                return;
            }
            throw;
        }
    });
}

}  // namespace tyndall::app
