#include "app/cmd_render.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "app/cli_common.h"
#include "app/interrupt.h"
#include "core/accumulator.h"
#include "cpu/progressive_render.h"
#include "hybrid/pass_scheduler.h"

namespace tyndall::app {

namespace {
ImageMetadata renderMetadata(const Scene& scene, const RenderSettings& s, const RadiusSetup& radii, uint64_t passes) {
    nlohmann::json j = s.toJson();
    j["resolved_radius"] = radii.beamRadius;
    j["resolved_surface_radius"] = radii.surfaceRadius;
    return {{"Software", "tyndall"},
            {"tyndall:scene", scene.source},
            {"tyndall:settings", j.dump()},
            {"tyndall:passes", std::to_string(passes)},
            {"tyndall:photon_paths", std::to_string(passes * s.photonsPerPass)}};
}
}  // namespace

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<CommonOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a scene with progressive photon beams");
    addSceneAndOutputOptions(cmd, *o, "tyndall.png");
    addPpbOptions(cmd, *o);
    cmd->add_option("--gpu", o->settings.gpu,
                    "Primary-beam splatting on OpenGL: auto (a hardware GPU when there is one, else the CPU), "
                    "on (OpenGL or fail; llvmpipe counts), off (CPU only, never touches OpenGL)")
        ->capture_default_str();
    cmd->callback([o, &exitCode]() {
        finishOptions(*o);
        checkOutputWritable(o->output);
        Scene scene = loadScene(*o);
        ThreadLimit threads(o->settings.threads);
        PassScheduler scheduler(parseGpuMode(o->settings.gpu));
        PassRenderer renderer(scene, o->settings);
        Accumulator acc = allocating("the accumulator of a " + std::to_string(o->settings.width) + "x" +
                                         std::to_string(o->settings.height) + " image",
                                     uint64_t(o->settings.width) * o->settings.height * 3 * sizeof(double),
                                     [&] { return Accumulator(o->settings.width, o->settings.height); });
        if (renderer.memoryPlan().batches > 1)
            std::fprintf(stderr, "tyndall: %s\n", renderer.memoryPlan().describe().c_str());
        installInterruptHandler();
        bool tty = isatty(fileno(stderr));
        CallbackDisplay display([&](const Accumulator&, const RenderProgress& pr) {
            if (tty) {
                double rate = pr.passesDone / std::max(pr.elapsedSeconds, 1e-9);
                std::fprintf(stderr, "\rpass %llu  %.1f s  %.2f passes/s ", (unsigned long long)pr.passesDone,
                             pr.elapsedSeconds, rate);
            }
            return interruptRequested() ? DisplayCommand::Exit : DisplayCommand::Continue;
        });
        scheduler.bind(scene);
        if (!scheduler.notice().empty()) std::fprintf(stderr, "tyndall: %s\n", scheduler.notice().c_str());
        RenderProgress p = scheduler.run(renderer, acc, 0, display);
        if (tty) std::fprintf(stderr, "\n");
        writeImage(o->output, acc.mean(), renderMetadata(scene, o->settings, renderer.radii(), acc.passCount()), o->exposure);
        std::printf("rendered %s: %llu passes, %llu photon paths, %llu beams, %.2f s (%.2f passes/s, %s)%s -> %s\n",
                    scene.name.c_str(), (unsigned long long)acc.passCount(), (unsigned long long)p.totals.photonPaths,
                    (unsigned long long)p.totals.beams, p.elapsedSeconds,
                    acc.passCount() / std::max(p.elapsedSeconds, 1e-9),
                    scheduler.hybrid() ? ("hybrid, " + scheduler.glDescription()).c_str() : "CPU",
                    interruptRequested() ? " [interrupted]" : "", o->output.c_str());
        exitCode = interruptRequested() ? 130 : 0;
    });
}

}  // namespace tyndall::app
