#include "app/cmd_reference.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/cli_common.h"
#include "cpu/embree_scene.h"
#include "cpu/reference_tracer.h"

namespace tyndall::app {

namespace {
struct ReferenceOptions {
    CommonOptions common;
    ReferenceSettings reference;
    bool noNee = false;
    bool transparent = false;
};

ImageMetadata referenceMetadata(const Scene& scene, const ReferenceSettings& s) {
    return {{"Software", "tyndall"},
            {"tyndall:scene", scene.source},
            {"tyndall:renderer", "reference"},
            {"tyndall:reference_settings", s.toJson().dump()},
            {"tyndall:spp", std::to_string(s.samplesPerPixel)}};
}
}  // namespace

void addReferenceCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<ReferenceOptions>();
    CLI::App* cmd = app.add_subcommand(
        "reference",
        "Render a scene with the unbiased volumetric path tracer (ground truth; misses caustics of point, spot and "
        "directional lights seen through glass or mirrors)");
    addSceneAndOutputOptions(cmd, o->common, "reference.png");
    cmd->add_option("--spp", o->reference.samplesPerPixel, "Samples (camera paths) per pixel")
        ->check(nonNegativeInteger())
        ->capture_default_str();
    cmd->add_option("--max-depth", o->reference.maxDepth,
                    "Most scattering vertices (surface or medium) per path; 1 = direct and single scattering")
        ->capture_default_str();
    addPathLengthOption(cmd, o->common);
    cmd->add_flag("--no-nee", o->noNee, "Disable light sampling (only emissive surfaces hit by paths contribute)");
    cmd->add_flag("--transparent", o->transparent,
                  "Transparent film, as tyndall render's: the environment is not seen as the background and the output "
                  "(.exr, .png, .tif) gets an alpha channel; the render block's \"transparent\"");
    cmd->callback([o, &exitCode]() {
        finishOptions(o->common);
        checkOutputWritable(o->common.output);
        Scene scene = loadScene(o->common);  // also applies the scene file's render block (size, seed)
        ReferenceSettings& s = o->reference;
        s.width = o->common.settings.width;
        s.height = o->common.settings.height;
        s.seed = o->common.settings.seed;
        s.maxPathLength = o->common.settings.maxPathLength;
        s.nextEventEstimation = !o->noNee;
        s.transparentFilm = o->transparent || o->common.settings.transparentFilm;
        if (s.transparentFilm && !formatHasAlpha(o->common.output))
            throw Error("output '" + o->common.output +
                        "': a transparent film writes an alpha channel, which needs .exr, .png or .tif");
        s.validate();
        ThreadLimit threads(o->common.settings.threads);
        auto start = std::chrono::steady_clock::now();
        EmbreeScene rt(scene);
        ReferenceTracer tracer(rt, s);
        bool tty = isatty(fileno(stderr));
        ReferenceImage image = tracer.render([&](int rows) {
            if (tty) std::fprintf(stderr, "\rrow %d / %d ", rows, s.height);
        });
        double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (tty) std::fprintf(stderr, "\n");
        writeImageLayers(o->common.output, image.mean, {}, referenceMetadata(scene, s), o->common.exposure,
                         s.transparentFilm ? &image.alpha : nullptr);
        double paths = double(s.width) * s.height * s.samplesPerPixel;
        std::printf("reference %s: %u spp, %dx%d, %.0f camera paths, %.2f s (%.3f M paths/s) -> %s\n",
                    scene.name.c_str(), s.samplesPerPixel, s.width, s.height, paths, seconds,
                    paths / std::max(seconds, 1e-9) * 1e-6, o->common.output.c_str());
        exitCode = 0;
    });
}

}  // namespace tyndall::app
