#include "app/cmd_compare.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/cli_common.h"
#include "app/interrupt.h"
#include "app/label_text.h"
#include "core/accumulator.h"
#include "loading/default_smoke_scene.h"
#include "loading/homogeneous_twin.h"
#include "core/error.h"
#include "hybrid/pass_scheduler.h"

namespace tyndall::app {

namespace {
struct CompareOptions {
    CommonOptions common;
    float density = -1.0f;  // < 0: each grid's mean over the twin's region
    TwinRegion twin = TwinRegion::Support;
};

struct Half {
    Image image;
    uint64_t passes = 0;
    double seconds = 0;
    bool hybrid = false;
};

/// Renders `scene` progressively through `scheduler` (GL splat or CPU); `passes` > 0 forces that
/// many passes (the twin matches the heterogeneous half's count even when that one ran on a time
/// budget or was interrupted). Stops early once `stopAtInterrupt` interrupts were received. Prints
/// the scheduler's notice unless it is `lastNotice` (both halves falling back for one reason).
Half renderHalf(PassScheduler& scheduler, const Scene& scene, RenderSettings settings, uint64_t passes,
                const char* what, int stopAtInterrupt, std::string& lastNotice) {
    if (passes > 0) {
        settings.passes = passes;
        settings.timeBudget = 0;
    }
    PassRenderer renderer(scene, settings);
    Accumulator acc(settings.width, settings.height);
    bool tty = isatty(fileno(stderr));
    CallbackDisplay display([&](const Accumulator&, const RenderProgress& pr) {
        if (tty)
            std::fprintf(stderr, "\r%s: pass %llu  %.1f s ", what, (unsigned long long)pr.passesDone,
                         pr.elapsedSeconds);
        return interruptCount() >= stopAtInterrupt ? DisplayCommand::Exit : DisplayCommand::Continue;
    });
    scheduler.bind(scene);
    if (!scheduler.notice().empty() && scheduler.notice() != lastNotice)
        std::fprintf(stderr, "tyndall: %s\n", scheduler.notice().c_str());
    lastNotice = scheduler.notice();
    RenderProgress p = scheduler.run(renderer, acc, 0, display);
    if (tty) std::fprintf(stderr, "\n");
    return {acc.mean(), acc.passCount(), p.elapsedSeconds, scheduler.hybrid()};
}

std::string withSuffix(const std::string& path, const std::string& suffix) {
    std::filesystem::path p(path);
    return (p.parent_path() / (p.stem().string() + suffix)).string();
}

std::string formatDensity(float d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", d);
    return buf;
}

/// The two halves side by side with a dark gap, each labelled at its top-left (clipped to its half;
/// `shortLabel` when the full one does not fit).
Image sideBySide(const Image& left, const Image& right, const std::string (&labels)[2],
                 const std::string (&shortLabels)[2]) {
    const int w = left.width, h = left.height, gap = std::max(2, w / 128);
    const int scale = std::max(1, h / 256), margin = 2 * scale;
    Image out(2 * w + gap, h);
    const Image* halves[2] = {&left, &right};
    for (int i = 0; i < 2; ++i) {
        Image half = *halves[i];
        const std::string& text = labelWidth(labels[i], scale) + 2 * margin <= w ? labels[i] : shortLabels[i];
        // Linear values: glyphs at 20 saturate to white under the PNG tone curve at any sane exposure.
        drawLabel(half, margin, margin, text, scale, Rgb(20.0f), Rgb(0.0f));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) out.at(i * (w + gap) + x, y) = half.at(x, y);
    }
    return out;
}
}  // namespace

void addCompareCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<CompareOptions>();
    CLI::App* cmd = app.add_subcommand(
        "compare",
        "Render a scene's density-grid medium next to its homogeneous twin (same albedo and g, constant density), "
        "same passes and photons; writes one labelled side-by-side image plus one EXR per half");
    addSceneAndOutputOptions(cmd, o->common, "compare.png");
    addPpbOptions(cmd, o->common);
    addGpuOption(cmd, o->common, "Primary-beam splatting on OpenGL: auto, on or off (as for `tyndall render`)");
    CLI::Option* density = cmd->add_option(
        "--density", o->density, "Density of the homogeneous twin (default: each grid's mean over the twin's region)");
    addTwinOption(cmd, o->twin);
    cmd->callback([o, density, &exitCode]() {
        CommonOptions& c = o->common;
        finishOptions(c);
        if (density->count() == 0)
            o->density = -1.0f;
        else if (!(o->density >= 0.0f && std::isfinite(o->density)))
            throw Error("--density must be a finite number >= 0");
        const std::string hetPath = withSuffix(c.output, "-heterogeneous.exr");
        const std::string homPath = withSuffix(c.output, "-homogeneous.exr");
        checkOutputWritable(c.output);
        checkOutputWritable(hetPath);
        checkOutputWritable(homPath);

        // loadScene checks --camera and applies the file's render block; the built-in case then
        // swaps the default scene for its smoke variant (same camera).
        Scene scene = loadScene(c);
        if (c.scene.empty()) scene = makeDefaultSmokeScene();
        scene.validate();
        std::vector<float> used;
        const TwinRegion region = o->twin;
        Scene twin = makeHomogeneousTwin(scene, o->density, &used, region);
        twin.validate();

        ThreadLimit threads(c.settings.threads);
        PassScheduler scheduler(c.settings.gpu);
        // Ctrl-C ends the heterogeneous half (written at once); its twin still renders as many
        // passes, unless Ctrl-C comes again; a third quits.
        installInterruptHandler(3);
        std::string notice;
        Half het = renderHalf(scheduler, scene, c.settings, 0, "heterogeneous", 1, notice);
        if (interruptRequested())
            std::fprintf(stderr,
                         "tyndall: heterogeneous half stopped after %llu passes; rendering the homogeneous twin to "
                         "as many (Ctrl-C again stops it)\n",
                         (unsigned long long)het.passes);

        std::string densities;
        for (size_t i = 0; i < used.size(); ++i) densities += (i ? "," : "") + formatDensity(used[i]);
        nlohmann::json settings = c.settings.toJson();
        ImageMetadata meta = {{"Software", "tyndall compare"},
                              {"tyndall:scene", scene.source},
                              {"tyndall:settings", settings.dump()},
                              {"tyndall:twin_density", densities},
                              {"tyndall:twin_region", twinRegionName(region)}};
        auto withHalf = [&](const char* half, uint64_t passes) {
            ImageMetadata m = meta;
            m.push_back({"tyndall:half", half});
            m.push_back({"tyndall:passes", std::to_string(passes)});
            return m;
        };
        writeImage(hetPath, het.image, withHalf("heterogeneous", het.passes));
        Half hom = renderHalf(scheduler, twin, c.settings, het.passes, "homogeneous", interruptCount() + 1, notice);
        writeImage(homPath, hom.image, withHalf("homogeneous", hom.passes));
        const std::string labels[2] = {
            "heterogeneous (OpenVDB grid)",
            (o->density >= 0 ? "homogeneous, density " : "homogeneous, mean density ") + densities};
        const std::string shortLabels[2] = {"heterogeneous", "homogeneous"};
        meta.push_back({"tyndall:passes", std::to_string(het.passes)});
        meta.push_back({"tyndall:twin_passes", std::to_string(hom.passes)});
        writeImage(c.output, sideBySide(het.image, hom.image, labels, shortLabels), meta, c.exposure);

        double hetPerPass = het.seconds / std::max<uint64_t>(het.passes, 1);
        double homPerPass = hom.seconds / std::max<uint64_t>(hom.passes, 1);
        std::string passes = het.passes == hom.passes ? std::to_string(het.passes) + " passes each"
                                                      : std::to_string(het.passes) + " and " +
                                                            std::to_string(hom.passes) + " passes (twin stopped early)";
        std::printf(
            "compared %s: %s; heterogeneous %.3f s/pass (%s), homogeneous (density %s, twin region %s) %.3f "
            "s/pass (%s) (ratio %.2f)%s -> %s, %s, %s\n",
            scene.name.c_str(), passes.c_str(), hetPerPass, het.hybrid ? "hybrid" : "CPU", densities.c_str(),
            twinRegionName(region),
            homPerPass, hom.hybrid ? "hybrid" : "CPU", hetPerPass / std::max(homPerPass, 1e-12),
            interruptRequested() ? " [interrupted]" : "", c.output.c_str(), hetPath.c_str(), homPath.c_str());
        exitCode = interruptRequested() ? 130 : 0;
    });
}

}  // namespace tyndall::app
