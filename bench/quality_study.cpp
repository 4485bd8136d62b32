#include "bench/quality_study.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/stage_rates.h"
#include "bench/quality_plot.h"
#include "bench/quality_reference.h"
#include "core/accumulator.h"
#include "core/error.h"
#include "core/image_io.h"
#include "bench/equiangular_pilot.h"
#include "cpu/pass_renderer.h"
#include "cpu/pixel_footprint.h"
#include "cpu/radius_defaults.h"
#include "cpu/reference_tracer.h"
#include "loading/scene_file.h"

namespace tyndall::bench {

using app::processCpuSeconds;

RenderSettings withLegacyDefaults(RenderSettings s, const Scene& scene) {
    s = withSceneRelativeRadii(s, scene);
    s.photonAngle = 0;
    s.directLight = false;
    s.surfaceBoundary = false;
    s.equiangular = false;
    s.scatteredBeamMfp = 0;
    return s;
}

namespace {
/// One render of one setting and seed: the error at doubling pass counts and at its end.
struct Run {
    std::vector<double> passes, cpu, relRmse;  ///< at n = 1, 2, 4, ... and the last pass
    ImageError end;
    uint64_t passesDone = 0;
    double cpuSeconds = 0;  ///< process CPU time of the passes (the error measurements excluded)
    Image image;            ///< the mean after the last pass
    std::unique_ptr<PassRenderer> renderer;
};

/// Renders passes 0, 1, ... of `s` until `passes` are done, or, with a CPU budget (> 0), until the
/// passes' CPU time reaches it (at least one pass). The image is the running mean either way, so it
/// stays a pure function of the pass count; the budget only decides where it stops.
Run renderRun(const Scene& scene, const RenderSettings& s, const Reference& ref, uint64_t passes, double cpuBudget) {
    Run run;
    run.renderer = std::make_unique<PassRenderer>(scene, s);
    Accumulator acc(s.width, s.height);
    for (uint64_t i = 0;; ++i) {
        const double t0 = processCpuSeconds();
        acc.addPass(run.renderer->renderPass(i));
        run.cpuSeconds += processCpuSeconds() - t0;
        const uint64_t n = i + 1;
        const bool last = cpuBudget > 0 ? run.cpuSeconds >= cpuBudget : n == passes;
        if ((n & (n - 1)) == 0 || last) {
            Image mean = acc.mean();
            ImageError e = measure(mean, ref);
            run.passes.push_back(double(n));
            run.cpu.push_back(run.cpuSeconds);
            run.relRmse.push_back(e.relRmse);
            if (last) run.end = e, run.image = std::move(mean);
        }
        if (last) {
            run.passesDone = n;
            return run;
        }
    }
}

struct Variant {
    std::string label;
    RenderSettings s;
};

/// The rows of one scene: equal work compares radius choices at `passes`; equal time the legacy
/// defaults with today's (and, given `passes`, the radii planned for it).
std::vector<Variant> variantsFor(const Scene& scene, const RenderSettings& base, uint64_t passes, bool equalTime,
                                 bool legacy, bool switches, const std::vector<double>& equiangularSamples,
                                 const std::vector<double>& scatteredBeamMfp,
                                 const std::vector<double>& mediumPointMfp,
                                 const std::vector<double>& indirectPhotonSpread) {
    std::vector<Variant> variants;
    if (legacy) variants.push_back({"LEGACY", withLegacyDefaults(base, scene)});
    RenderSettings open = base;
    open.plannedPaths = RadiusDefaults::kOpenEndedPathsPerPixel * uint64_t(base.width) * uint64_t(base.height);
    if (equalTime) {
        // What `tyndall render --time S` resolves (the open-ended plan), then, given a pass
        // count, the same planned for it (`--planned-paths`).
        variants.push_back({"DEFAULTS (--TIME)", open});
        if (switches) {
            RenderSettings switched = open;
            switched.equiangular = !open.equiangular;
            variants.push_back({switched.equiangular ? "EQUIANGULAR ON" : "EQUIANGULAR OFF", switched});
            // --film-light-sampling switched, where it acts (with the equiangular estimator).
            RenderSettings film = open.equiangular ? open : switched;
            film.filmLightSampling = !film.filmLightSampling;
            variants.push_back({film.filmLightSampling ? "FILM LIGHT ON" : "FILM LIGHT OFF", film});
        }
        for (double n : equiangularSamples) {
            RenderSettings counted = open;
            counted.equiangular = true;
            counted.equiangularSamples = n;
            char label[64];
            if (n == RenderSettings::kAutoEquiangularSamples)
                std::snprintf(label, sizeof label, "EQUIANGULAR AUTO");
            else
                std::snprintf(label, sizeof label, "EQUIANGULAR %g", n);
            variants.push_back({label, counted});
        }
        for (double c : scatteredBeamMfp) {
            RenderSettings widened = open;
            widened.scatteredBeamMfp = c;
            char label[64];
            std::snprintf(label, sizeof label, "SCATTERED BEAMS %g MFP", c);
            variants.push_back({label, widened});
        }
        for (double c : mediumPointMfp) {
            RenderSettings pointed = open;
            pointed.mediumPointMfp = c;
            char label[64];
            std::snprintf(label, sizeof label, "MEDIUM POINTS %g MFP", c);
            variants.push_back({label, pointed});
        }
        for (double c : indirectPhotonSpread) {
            RenderSettings spread = open;
            spread.indirectPhotonSpread = c;
            char label[64];
            std::snprintf(label, sizeof label, "INDIRECT PHOTONS %g", c);
            variants.push_back({label, spread});
        }
        if (passes > 0) {
            RenderSettings planned = base;
            planned.plannedPaths = passes * uint64_t(base.photonsPerPass);
            variants.push_back({"AUTO, PLANNED", planned});
        }
    } else {
        variants.push_back({"AUTO, PLANNED", base});
        RenderSettings noCone = base;
        noCone.photonAngle = 0;
        variants.push_back({"AUTO, NO CONE", noCone});
        variants.push_back({"AUTO, OPEN-ENDED", open});
    }
    return variants;
}

/// Over the seeds' runs: the curve (the doubling pass counts every seed reached, at their mean x,
/// then the ends; errors as root mean squares) and the end's error (bias as the mean).
Curve combineSeeds(const std::string& label, const std::vector<Run>& runs, bool equalTime, ImageError* end) {
    const double seeds = double(runs.size());
    Curve curve{label, {}};
    size_t shared = runs[0].passes.size() - 1;
    for (const Run& r : runs) shared = std::min(shared, r.passes.size() - 1);
    for (size_t i = 0; i <= shared; ++i) {
        double x = 0, y = 0;
        for (const Run& r : runs) {
            size_t j = i < shared ? i : r.passes.size() - 1;
            x += (equalTime ? r.cpu[j] : r.passes[j]) / seeds;
            y += r.relRmse[j] * r.relRmse[j] / seeds;
        }
        if (curve.points.empty() || x > curve.points.back().first) curve.points.push_back({x, std::sqrt(y)});
    }
    *end = ImageError{};
    for (const Run& r : runs) {
        end->relRmse += r.end.relRmse * r.end.relRmse / seeds;
        end->relRmse99 += r.end.relRmse99 * r.end.relRmse99 / seeds;
        end->relBias += r.end.relBias / seeds;
    }
    end->relRmse = std::sqrt(end->relRmse);
    end->relRmse99 = std::sqrt(end->relRmse99);
    return curve;
}

/// Renders one row with every seed, prints its line of the table and returns its curve.
Curve studyRow(const Scene& scene, const Variant& v, const Reference& ref, uint64_t passes,
               const QualityStudyOptions& o) {
    std::vector<Run> runs;
    for (int k = 0; k < o.seeds; ++k) {
        RenderSettings sk = v.s;
        sk.seed = v.s.seed + uint64_t(k);
        runs.push_back(renderRun(scene, sk, ref, passes, o.cpuSeconds));
        if (!o.imageDir.empty())
            writeImage(o.imageDir + "/" + scene.name + "-" + rowSlug(v.label) + "-seed" + std::to_string(sk.seed) + ".exr",
                       runs.back().image, {{"Software", "tyndall"}, {"tyndall:settings", sk.toJson().dump()},
                                           {"tyndall:passes", std::to_string(runs.back().passesDone)}});
    }
    ImageError e;
    Curve curve = combineSeeds(v.label, runs, o.cpuSeconds > 0, &e);
    double cpu = 0, passesDone = 0;
    for (const Run& r : runs) {
        cpu += r.cpuSeconds / o.seeds;
        passesDone += double(r.passesDone) / o.seeds;
    }
    const PassRenderer& renderer = *runs.back().renderer;
    const RenderSettings& r = renderer.settings();
    // The beam radius at the end, in pixel footprints where the media are.
    PixelFootprint fp = measurePixelFootprint(renderer.rayTracer(), scene.camera, r.width, r.height);
    double rEnd = renderer.radii().beamRadiusOf(runs.back().passesDone * r.photonsPerPass);
    std::printf("  %-16s %-18s %7.0f %8.1f %8.2f%% %8.2f%% %+8.2f%% %8.2f   (radius %.4g, surface %.4g, offset %llu, "
                "photon angle %.3g, direct light %s, boundary %s, equiangular %s, %.4g samples, film light %s)\n",
                scene.name.c_str(), v.label.c_str(), passesDone, cpu, 100 * e.relRmse, 100 * e.relRmse99,
                100 * e.relBias, rEnd / fp.beam(1.0), r.radius, r.surfaceRadius, (unsigned long long)r.radiusOffset,
                r.photonAngle, onOffText(r.directLight), onOffText(r.surfaceBoundary), onOffText(r.equiangular),
                r.equiangularSamples, onOffText(r.filmLightSampling));
    std::fflush(stdout);
    return curve;
}

/// The study's scene entries: (FILE[:PASSES], from the library).
std::vector<std::pair<std::string, bool>> sceneEntries(const QualityStudyOptions& o) {
    std::vector<std::pair<std::string, bool>> entries;
    for (const std::string& entry : o.scenes) entries.push_back({entry, false});
    if (o.library.empty()) return entries;
    namespace fs = std::filesystem;
    if (!fs::is_directory(o.library)) throw Error("--library '" + o.library + "': not a folder");
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(o.library))
        if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) entries.push_back({f, true});
    return entries;
}

/// FILE:PASSES split; with a CPU budget the pass count is optional (0 when absent).
std::pair<std::string, uint64_t> fileAndPasses(const std::string& entry, bool equalTime) {
    size_t colon = entry.rfind(':');
    if (colon != std::string::npos && colon + 1 < entry.size() &&
        entry.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
        uint64_t passes = std::stoull(entry.substr(colon + 1));
        if (passes > 0) return {entry.substr(0, colon), passes};
    }
    if (!equalTime)
        throw Error("--scene '" + entry + "': expected FILE:PASSES (a positive pass count; FILE alone only with "
                    "--cpu-seconds)");
    return {entry, 0};
}

void printHeading(const RenderSettings& s, const QualityStudyOptions& o) {
    if (o.cpuSeconds > 0)
        std::printf("quality at equal time: %.1f CPU s per render (the passes' process CPU time), %dx%d, %u photon "
                    "paths/pass, reference %u spp (its noise removed), %d seed(s)\n",
                    o.cpuSeconds, s.width, s.height, s.photonsPerPass, o.referenceSpp, o.seeds);
    else
        std::printf("quality at equal work: %dx%d, %u photon paths/pass, reference %u spp (its noise removed), %d seed(s)\n",
                    s.width, s.height, s.photonsPerPass, o.referenceSpp, o.seeds);
    std::printf("  %-16s %-18s %7s %8s %9s %9s %9s %8s\n", "scene", "radii", "passes", "CPU s", "rel RMSE",
                "(-1% top)", "rel bias", "r_end/px");
}
}  // namespace

void runQualityStudy(const RenderSettings& settings, const QualityStudyOptions& o) {
    if (!o.imageDir.empty()) std::filesystem::create_directories(o.imageDir);
    const bool equalTime = o.cpuSeconds > 0;
    printHeading(settings, o);
    std::vector<PlotPanel> panels;
    for (const auto& [entry, fromLibrary] : sceneEntries(o)) {
        auto [file, passes] = fileAndPasses(entry, equalTime);
        const std::string stem = std::filesystem::path(file).stem().string();
        if (!o.only.empty() && std::find(o.only.begin(), o.only.end(), stem) == o.only.end()) continue;
        SceneFile sf = loadSceneFile(file, {});
        if (fromLibrary) {
            sf.scene = withoutSpecularSurfaces(sf.scene);
            sf.scene.name += "-no-specular";
        }
        const Scene& scene = sf.scene;
        RenderSettings base = settings;
        base.passes = passes > 0 ? passes : 1;
        base.timeBudget = 0;
        if ((equalTime || o.pilotOnly) && settings.equiangular) {
            // What the automatic equiangular count saw (bench/equiangular_pilot.h), for the open-ended
            // plan the rows render.
            RenderSettings open = base;
            open.plannedPaths = RadiusDefaults::kOpenEndedPathsPerPixel * uint64_t(base.width) * uint64_t(base.height);
            const EmbreeScene rt(scene);
            const EquiangularPilot p = runEquiangularPilot(scene, resolveRadiusDefaults(open, rt));
            std::printf("  %-16s equiangular pilot: V_ea %.4g (%d stratified %.4g: exponent %.2f), V_rest %.4g (pass "
                        "%.4g), %.0f of %.0f pixels in a medium, %.0f photon paths, C_0/c %.3g: %.4g samples\n",
                        scene.name.c_str(), p.equiangularVariance, EquiangularAuto::kStratified, p.stratifiedVariance,
                        equiangularStratificationExponent(p.equiangularVariance, p.stratifiedVariance),
                        p.restVariance, p.passVariance, p.segments, p.pixels, p.photonPaths, p.costRatio, p.samples);
        }
        if (o.pilotOnly) continue;
        Reference ref = loadOrRenderReference(scene, scene.name, base, o.referenceDir, o.referenceSpp);
        std::vector<Curve> curves;
        for (const Variant& v : variantsFor(scene, base, passes, equalTime, o.legacy, o.switches, o.equiangularSamples,
                                            o.scatteredBeamMfp, o.mediumPointMfp, o.indirectPhotonSpread))
            curves.push_back(studyRow(scene, v, ref, passes, o));
        panels.push_back({scene.name, std::move(curves)});
    }
    if (o.plot.empty()) return;
    writePlotData(o.plot, panels, settings.alpha, equalTime ? "CPU seconds (equal time)" : "passes (equal work)");
    std::string why;
    if (runGnuplot(o.plot, &why))
        std::printf("plot -> %s.png (data %s.csv, script %s.gp)\n", o.plot.c_str(), o.plot.c_str(), o.plot.c_str());
    else
        std::printf("plot data -> %s.csv, script %s.gp; no %s.png: %s\n", o.plot.c_str(), o.plot.c_str(),
                    o.plot.c_str(), why.c_str());
}

}  // namespace tyndall::bench
