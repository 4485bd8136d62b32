#include "app/cmd_render.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "app/cli_common.h"
#include "app/convergence_log.h"
#include "app/interrupt.h"
#include "app/mpi_ranks.h"
#include "app/progress_meter.h"
#include "app/render_checkpoint.h"
#include "app/test_hooks.h"
#include "core/error.h"
#include "core/timing.h"
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
    bool transparent = false;
    std::string reference;
    std::string convergence;
};

/// What a render starts from: a new one, or the state of a checkpoint.
struct RenderStart {
    RenderRecord record;
    std::optional<LayerAccumulator> acc;
    Scene scene;
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
                                   "--environment",   "--max-path-length", "--equiangular", "--photon-planes",
                                   "--transparent",   "--equiangular-samples", "--scattered-beam-mfp",
                                   "--medium-points", "--indirect-photon-spread"};
    for (const char* name : kFixed)
        if (given(cmd, name))
            throw Error(std::string("--resume: ") + (name[0] == '-' ? name : "the scene file") +
                        " comes from the checkpoint and cannot be changed (only -o, --passes, --time, --threads, "
                        "--gpu, --checkpoint, --checkpoint-every, --quiet, --progress-every and the convergence "
                        "log may be given)");
}

/// Error before rendering when the checkpoint's directory is missing or not writable.
void checkCheckpointWritable(const std::string& path) {
    std::string dir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/') + 1);
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error("--checkpoint '" + path + "': directory '" + dir + "' does not exist or is not writable");
}

RenderStart startNew(RenderOptions& o, bool root) {
    CommonOptions& c = o.common;
    RenderStart r;
    finishOptions(c);
    if (root) checkOutputWritable(c.output);
    r.scene = loadScene(c);
    if (o.transparent) c.settings.transparentFilm = true;
    if (c.settings.transparentFilm && root && !formatHasAlpha(c.output))
        throw Error("output '" + c.output + "': a transparent film writes an alpha channel, which needs .exr, .png or .tif");
    {
        // The automatic radii become plain numbers here, once, so a resume or another MPI rank
        // renders with the same ones whatever share of the target it runs. A --time budget plans
        // for the open-ended horizon (a measured rate would differ between ranks and resumes).
        // So does the automatic equiangular sample count.
        const EmbreeScene rt(r.scene);
        c.settings = resolveEquiangularSamples(resolveRadiusDefaults(c.settings, rt));
    }
    r.record = {c.scene, c.camera, sceneHash(c.scene, r.scene), c.settings, c.output, c.exposure, o.aov, 0.0,
                c.environment};
    allocating("the accumulator of a " + std::to_string(c.settings.width) + "x" + std::to_string(c.settings.height) +
                   " image",
               accumulatorBytes(c.settings, o.aov), [&] {
                   r.acc.emplace(c.settings.width, c.settings.height, o.aov, c.settings.transparentFilm);
               });
    return r;
}

RenderStart startResumed(RenderOptions& o, const CLI::App* cmd, bool root) {
    // Nothing is written before every check passed: a bad resume leaves the checkpoint as it was.
    CommonOptions& c = o.common;
    RenderStart r;
    rejectWithResume(cmd);
    const std::string where = "checkpoint '" + o.resume + "'";
    const LoadBudget budget(loadMemoryBytes(c));
    Checkpoint ck = loadCheckpoint(o.resume, &budget);
    r.record = readRecord(ck, where);
    RenderRecord& record = r.record;
    c.scene = record.scenePath;
    c.camera = record.camera;
    c.environment = record.environment;
    r.scene = loadScene(c);
    const uint64_t hash = sceneHash(record.scenePath, r.scene);
    if (hash != record.sceneHash)
        throw Error(where + " was made from a different scene: '" +
                    (record.scenePath.empty() ? std::string("<built-in default scene>") : record.scenePath) +
                    "' changed since (hash " + hashText(hash) + ", the checkpoint's " + hashText(record.sceneHash) +
                    "); render it afresh");
    r.acc.emplace(LayerAccumulator::fromNamed(std::move(ck.layers), record.aov, where, record.settings.transparentFilm));
    if (r.acc->beauty().width() != record.settings.width || r.acc->beauty().height() != record.settings.height)
        throw Error(where + ": its image size does not match its settings");
    if (given(cmd, "--passes")) {
        if (c.settings.passes <= r.acc->passCount())
            throw Error("--passes " + std::to_string(c.settings.passes) + ": " + where + " already holds " +
                        std::to_string(r.acc->passCount()) + " passes (the target is the total)");
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
    return r;
}

/// Periodic checkpoints of one run (rank 0): every `every` seconds and at the end. A failed
/// write, the last one included, is a warning (CheckpointWrites): the render goes on.
class Checkpointer {
public:
    Checkpointer(std::string path, double every, RenderRecord& record, double elapsedBefore)
        : m_writes(path), m_path(std::move(path)), m_every(every), m_record(record), m_elapsedBefore(elapsedBefore),
          m_stall(RenderTestHooks::fromEnvironment().checkpointStall()) {}
    bool enabled() const { return !m_path.empty(); }
    void write(const LayerAccumulator& acc, double runElapsed) {
        m_record.elapsed = m_elapsedBefore + runElapsed;
        m_writes.save(makeCheckpoint(m_record, acc), acc.passCount(), m_stall);
        m_last = Clock::now();
    }
    void ifDue(const LayerAccumulator& acc, double runElapsed) {
        if (enabled() && secondsSince(m_last) >= m_every) write(acc, runElapsed);
    }
    const CheckpointWrites& writes() const { return m_writes; }

private:
    CheckpointWrites m_writes;
    std::string m_path;
    double m_every;
    RenderRecord& m_record;
    double m_elapsedBefore;
    std::function<void()> m_stall;
    Clock::time_point m_last = Clock::now();
};

/// The summary line's "how": ranks, hybrid or CPU.
std::string renderedHow(const Ranks& ranks, const PassScheduler& scheduler) {
    if (ranks.distributed())
        return std::to_string(ranks.size()) + " ranks" + (scheduler.hybrid() ? ", hybrid" : "");
    return scheduler.hybrid() ? "hybrid, " + scheduler.glDescription() : std::string("CPU");
}

void runRender(RenderOptions& o, CLI::App* cmd, int& exitCode) {
    Ranks& ranks = Ranks::world();
    const bool root = ranks.rank() == 0;
    RenderStart start = o.resume.empty() ? startNew(o, root) : startResumed(o, cmd, root);
    RenderRecord& record = start.record;
    LayerAccumulator& acc = *start.acc;
    const RenderSettings& s = record.settings;
    if (root && !o.checkpoint.empty()) checkCheckpointWritable(o.checkpoint);
    if (o.reference.empty() != o.convergence.empty())
        throw Error("--reference and --convergence go together (the CSV logs the error against the reference)");
    std::unique_ptr<ConvergenceLog> log;
    if (root && !o.reference.empty()) log = std::make_unique<ConvergenceLog>(o.reference, o.convergence, s.width, s.height);

    ThreadLimit threads(s.threads);
    const uint64_t passesBefore = acc.passCount();
    const double elapsedBefore = record.elapsed;
    // This run's share of the target.
    RenderSettings run = s;
    run.passes = s.timeBudget > 0 ? s.passes : s.passes - std::min(s.passes, passesBefore);
    run.timeBudget = s.timeBudget > 0 ? std::max(s.timeBudget - elapsedBefore, 1e-9) : 0;
    // A pass does not depend on the target: the same bits as with `s`. The AOV layers' buffers
    // count in the memory plan (record.aov: the same plan when resumed).
    PassRenderer renderer(start.scene, run, BeamBvh::Kind::FlatCurves, record.aov);
    const RenderTestHooks& hooks = RenderTestHooks::fromEnvironment();
    renderer.setTestHooks(hooks.passHooks());
    if (root && renderer.memoryPlan().batches > 1)
        std::fprintf(stderr, "tyndall: %s\n", renderer.memoryPlan().describe().c_str());
    SchedulerOptions schedulerOptions;
    schedulerOptions.hooks = hooks.passHooks();
    PassScheduler scheduler(s.gpu, schedulerOptions);
    scheduler.bind(start.scene);
    if (root && !scheduler.notice().empty()) std::fprintf(stderr, "tyndall: %s\n", scheduler.notice().c_str());

    installInterruptHandler();
    ProgressMeter progress(stderr, root ? progressStyleFor(stderr, o.quiet) : ProgressStyle::Quiet,
                           {s.passes, run.timeBudget, passesBefore}, o.progressEvery);
    Checkpointer checkpoints(o.checkpoint, o.checkpointEvery, record, elapsedBefore);
    double runElapsed = 0;
    CallbackDisplay display(
        [&](const Accumulator& beauty, const RenderProgress& p) {
            runElapsed = p.elapsedSeconds;
            progress.update(p.passesDone, p.elapsedSeconds);
            const uint64_t paths = beauty.passCount() * s.photonsPerPass;
            if (log)
                log->add(beauty, {beauty.passCount(), elapsedBefore + p.elapsedSeconds, paths,
                                  renderer.radii().beamRadiusOf(paths ? paths - 1 : 0)});
            checkpoints.ifDue(acc, runElapsed);
            if (hooks.holdAfterPass() && beauty.passCount() == hooks.holdAfterPass())
                holdForTests([&] { checkpoints.ifDue(acc, runElapsed); });
            return interruptRequested() ? DisplayCommand::Exit : DisplayCommand::Continue;
        },
        {}, [](const std::string& line) { std::fprintf(stderr, "tyndall: warning: %s\n", line.c_str()); });
    RenderProgress p = scheduler.run(renderer, acc, passesBefore, display, ranks);
    runElapsed = p.elapsedSeconds;
    progress.finish();
    if (!root) return;

    const bool interrupted = interruptRequested();
    const Image alpha = acc.transparent() ? acc.alpha() : Image();
    writeImageLayers(record.output, acc.beauty().mean(), acc.imageLayers(),
                     renderMetadata(start.scene, s, renderer.radii(), acc, ranks.size()), record.exposure,
                     acc.transparent() ? &alpha : nullptr);
    if (checkpoints.enabled()) checkpoints.write(acc, runElapsed);
    const uint64_t rejected = acc.beauty().rejectedSamples();
    if (rejected)
        std::fprintf(stderr, "tyndall: warning: %llu pixel samples were NaN or infinite and were left out\n",
                     (unsigned long long)rejected);
    std::printf("rendered %s: %llu passes, %llu photon paths, %llu beams, %.2f s (%.2f passes/s, %s)%s -> %s\n",
                start.scene.name.c_str(), (unsigned long long)acc.passCount(), (unsigned long long)p.totals.photonPaths,
                (unsigned long long)p.totals.beams, p.elapsedSeconds, p.passesDone / std::max(p.elapsedSeconds, 1e-9),
                renderedHow(ranks, scheduler).c_str(), interrupted ? " [interrupted]" : "", record.output.c_str());
    if (checkpoints.writes().failures())
        std::fprintf(stderr, "tyndall: warning: %s\n", checkpoints.writes().summary().c_str());
    else if (checkpoints.enabled())
        std::printf("checkpoint -> %s\n", o.checkpoint.c_str());
    exitCode = interrupted ? 130 : 0;
}
}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene with progressive photon beams");
    addSceneAndOutputOptions(cmd, o->common, "tyndall.png");
    addPpbOptions(cmd, o->common);
    addPathLengthOption(cmd, o->common);
    addRegionOption(cmd, o->common);
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
    cmd->add_flag("--transparent", o->transparent,
                  "Transparent film: the environment is not seen as the background (it still lights the scene) and "
                  "the EXR/PNG gets an alpha channel, the pixel's coverage (fog in front of the background: 1 minus "
                  "its transmittance); the render block's \"transparent\"");
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
