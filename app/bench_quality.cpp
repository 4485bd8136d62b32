#include "app/bench_quality.h"

#include <time.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/label_text.h"
#include "core/accumulator.h"
#include "core/error.h"
#include "core/image_io.h"
#include "cpu/pass_renderer.h"
#include "cpu/pixel_footprint.h"
#include "cpu/radius_defaults.h"
#include "cpu/reference_tracer.h"
#include "loading/scene_file.h"

namespace tyndall::app {

namespace {
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// The defaults `tyndall render` had when issue 10 was filed (before ca56336): the scene-relative
/// radii (withSceneRelativeRadii), no photon cone, surfaces lit by photons alone (no shadow rays),
/// the plain surface kernel. The LEGACY row: "today's defaults" the issue measures against.
RenderSettings withLegacyDefaults(RenderSettings s, const Scene& scene) {
    s = withSceneRelativeRadii(s, scene);
    s.photonAngle = 0;
    s.directLight = "off";
    s.surfaceBoundary = "off";
    return s;
}

/// A row label as a file-name part: "DEFAULTS (--TIME)" -> "defaults-time".
std::string rowSlug(const std::string& label) {
    std::string row;
    for (unsigned char c : label)
        if (std::isalnum(c)) row += char(std::tolower(c));
        else if (!row.empty() && row.back() != '-') row += '-';
    while (!row.empty() && row.back() == '-') row.pop_back();
    return row;
}

struct Reference {
    Image mean;
    double noiseVariance = 0;  ///< the reference's own variance of the mean, averaged over pixels and channels
    Image variance;            ///< per pixel (cached beside the mean); empty in caches written without it
};

Reference loadOrRenderReference(const Scene& scene, const std::string& name, const RenderSettings& s,
                                const QualityBenchOptions& o) {
    namespace fs = std::filesystem;
    fs::create_directories(o.referenceDir);
    std::string path = o.referenceDir + "/" + name + "-" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       "-" + std::to_string(o.referenceSpp) + "spp.exr";
    Reference ref;
    if (fs::exists(path)) {
        ref.mean = readImage(path);
        ref.noiseVariance = std::stod(readImageAttribute(path, "tyndall:mean_variance_of_mean"));
        std::string variancePath = path.substr(0, path.size() - 4) + "-variance.exr";
        if (fs::exists(variancePath)) ref.variance = readImage(variancePath);
        std::printf("  reference %s (cached)\n", path.c_str());
        return ref;
    }
    ReferenceSettings rs;
    rs.width = s.width;
    rs.height = s.height;
    rs.samplesPerPixel = o.referenceSpp;
    rs.seed = 1000 + s.seed;  // independent of the PPB renders' streams
    rs.validate();
    EmbreeScene rt(scene);
    double t0 = processCpuSeconds();
    ReferenceImage image = ReferenceTracer(rt, rs).render();
    double v = 0;
    for (const Rgb& p : image.varianceOfMean.pixels) v += (p.r + p.g + p.b) / 3.0;
    v /= double(image.varianceOfMean.pixels.size());
    char text[64];
    std::snprintf(text, sizeof(text), "%.9g", v);
    writeImage(path, image.mean,
               {{"Software", "tyndall"}, {"tyndall:renderer", "reference"}, {"tyndall:scene", scene.source},
                {"tyndall:reference_settings", rs.toJson().dump()}, {"tyndall:mean_variance_of_mean", text}});
    writeImage(path.substr(0, path.size() - 4) + "-variance.exr", image.varianceOfMean);
    ref.variance = image.varianceOfMean;
    std::printf("  reference %s rendered (%u spp, %.0f CPU s)\n", path.c_str(), o.referenceSpp, processCpuSeconds() - t0);
    ref.mean = std::move(image.mean);
    ref.noiseVariance = v;
    return ref;
}

struct ImageError {
    double relRmse = 0, relBias = 0;
    double relRmse99 = 0;  ///< relative RMSE without the brightest 1% of the reference's pixels
};

/// Relative RMSE (the reference's own noise variance removed) and relative bias of the image mean;
/// also the RMSE over the pixels below the reference's 99th brightness percentile, which leaves out
/// singular glows (a point light seen in fog) that any kernel radius blurs.
ImageError measure(const Image& x, const Reference& ref) {
    std::vector<float> brightness;
    for (const Rgb& p : ref.mean.pixels) brightness.push_back(p.r + p.g + p.b);
    std::vector<float> sorted = brightness;
    size_t k = size_t(0.99 * double(sorted.size()));
    std::nth_element(sorted.begin(), sorted.begin() + k, sorted.end());
    const float cut = sorted[k];
    double se = 0, sum = 0, sumRef = 0, se99 = 0, sumRef99 = 0, n99 = 0, noise99 = 0;
    const bool perPixelNoise = !ref.variance.pixels.empty();
    for (size_t i = 0; i < x.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double d = double(x.pixels[i][c]) - ref.mean.pixels[i][c];
            se += d * d;
            sum += x.pixels[i][c];
            sumRef += ref.mean.pixels[i][c];
            if (brightness[i] < cut) {
                se99 += d * d, sumRef99 += ref.mean.pixels[i][c], n99 += 1;
                noise99 += perPixelNoise ? ref.variance.pixels[i][c] : ref.noiseVariance;
            }
        }
    double n = 3.0 * double(x.pixels.size()), meanRef = sumRef / n;
    ImageError e;
    e.relRmse = std::sqrt(std::max(0.0, se / n - ref.noiseVariance)) / meanRef;
    e.relBias = (sum - sumRef) / sumRef;
    // Below the cut, the reference's own noise is that of those pixels (the image average, an
    // overestimate there, for caches written without the variance image).
    if (n99 > 0) e.relRmse99 = std::sqrt(std::max(0.0, (se99 - noise99) / n99)) / (sumRef99 / n99);
    return e;
}

struct Curve {
    std::string label;
    std::vector<std::pair<double, double>> points;  // (passes or CPU seconds, relative RMSE)
    Rgb color;
};

void drawLine(Image& img, double x0, double y0, double x1, double y1, const Rgb& c) {
    int steps = int(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0))) + 1;
    for (int i = 0; i <= steps; ++i) {
        double t = double(i) / steps;
        int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
                if (x + dx >= 0 && x + dx < img.width && y + dy >= 0 && y + dy < img.height) img.at(x + dx, y + dy) = c;
    }
}

/// A log-log plot of relative RMSE against `xLabel` (passes, or CPU seconds), one panel per scene,
/// drawn into a PNG. Grey: the N^(-alpha/2) slope of a fixed schedule's noise (time is proportional
/// to N, so the slope is the same against time) through the last point of the first curve.
void writePlot(const std::string& path, const std::vector<std::pair<std::string, std::vector<Curve>>>& panels,
               double alpha, const std::string& xLabel) {
    const int pw = 420, ph = 320, margin = 50;
    const int columns = std::min<int>(3, std::max<int>(1, int(panels.size())));
    const int rows = (int(panels.size()) + columns - 1) / columns;
    Image img(pw * columns, ph * std::max(1, rows));
    const Rgb white(50.0f), grey(0.6f), black(0.0f);
    for (Rgb& p : img.pixels) p = white;
    for (size_t k = 0; k < panels.size(); ++k) {
        const auto& [title, curves] = panels[k];
        double xmin = 1e300, xmax = 0, ymin = 1e300, ymax = 0;
        for (const Curve& c : curves)
            for (auto [x, y] : c.points)
                if (y > 0) xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
        if (!(xmax > xmin) || !(ymax > 0)) continue;
        double lx0 = std::log10(xmin), lx1 = std::log10(xmax), ly0 = std::floor(std::log10(ymin) * 4) / 4,
               ly1 = std::ceil(std::log10(ymax) * 4) / 4;
        // Panels in rows of three; oy moves every y of this panel down to its row.
        const int ox = int(k % size_t(columns)) * pw, oy = int(k / size_t(columns)) * ph;
        auto X = [&](double x) { return ox + margin + (std::log10(x) - lx0) / (lx1 - lx0) * (pw - margin - 15); };
        auto Y = [&](double y) { return oy + ph - margin - (std::log10(y) - ly0) / (ly1 - ly0) * (ph - margin - 40); };
        drawLine(img, ox + margin, oy + ph - margin, ox + pw - 15, oy + ph - margin, black);
        drawLine(img, ox + margin, oy + ph - margin, ox + margin, oy + 40, black);
        // Decade and half-decade ticks on the error axis, labelled in percent.
        for (double ly = std::ceil(ly0 * 2) / 2; ly <= ly1 + 1e-9; ly += 0.5) {
            double y = Y(std::pow(10.0, ly));
            drawLine(img, ox + margin - 4, y, ox + pw - 15, y, grey);
            char t[32];
            std::snprintf(t, sizeof(t), "%.3g%%", 100 * std::pow(10.0, ly));
            drawLabel(img, ox + 2, int(y) - 5, t, 1, black, white);
        }
        // Ticks at 1, 2 and 5 per decade when the axis spans less than two decades.
        const bool fine = lx1 - lx0 < 2;
        for (double lx = std::floor(lx0); lx <= lx1 + 1e-9; lx += 1)
            for (double m : {1.0, 2.0, 5.0}) {
                if ((m != 1.0 && !fine) || std::log10(m) + lx < lx0 - 1e-9 || std::log10(m) + lx > lx1 + 1e-9) continue;
                double x = X(m * std::pow(10.0, lx));
                drawLine(img, x, oy + ph - margin, x, oy + ph - margin + 4, black);
                char t[32];
                std::snprintf(t, sizeof(t), "%g", m * std::pow(10.0, lx));
                drawLabel(img, int(x) - 8, oy + ph - margin + 6, t, 1, black, white);
            }
        drawLabel(img, ox + margin + 60, oy + ph - 20, xLabel, 1, black, white);
        // Long scene names get the small font, so the title stays within its panel.
        const std::string heading = title + ": RELATIVE RMSE";
        drawLabel(img, ox + 8, oy + 6, heading, heading.size() > 24 ? 1 : 2, black, white);
        // The N^(-alpha/2) slope of a fixed schedule's noise, through the last point of the first curve.
        if (!curves.empty() && !curves[0].points.empty()) {
            auto [xe, ye] = curves[0].points.back();
            double xs = xmin, ys = ye * std::pow(xs / xe, -alpha / 2);
            drawLine(img, X(xs), Y(std::min(ys, std::pow(10.0, ly1))), X(xe), Y(ye), grey);
            char t[48];
            std::snprintf(t, sizeof(t), "GREY: SLOPE -%.2g", alpha / 2);
            drawLabel(img, ox + pw - 200, oy + 46, t, 1, Rgb(0.3f), white);
        }
        int legendY = oy + 60;
        for (const Curve& c : curves) {
            for (size_t i = 1; i < c.points.size(); ++i)
                drawLine(img, X(c.points[i - 1].first), Y(c.points[i - 1].second), X(c.points[i].first),
                         Y(c.points[i].second), c.color);
            for (auto [x, y] : c.points) drawLine(img, X(x) - 2, Y(y) - 2, X(x) + 2, Y(y) + 2, c.color);
            drawLabel(img, ox + pw - 200, legendY, c.label, 1, c.color, white);
            legendY += 12;
        }
    }
    writeImage(path, img);
}
}  // namespace

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
}  // namespace

void runQualityBench(const CommonOptions& common, const QualityBenchOptions& o) {
    if (!o.imageDir.empty()) std::filesystem::create_directories(o.imageDir);
    std::vector<std::pair<std::string, std::vector<Curve>>> panels;
    const bool equalTime = o.cpuSeconds > 0;
    if (equalTime)
        std::printf("quality at equal time: %.1f CPU s per render (the passes' process CPU time), %dx%d, %u photon "
                    "paths/pass, reference %u spp (its noise removed), %d seed(s)\n",
                    o.cpuSeconds, common.settings.width, common.settings.height, common.settings.photonsPerPass,
                    o.referenceSpp, o.seeds);
    else
        std::printf("quality at equal work: %dx%d, %u photon paths/pass, reference %u spp (its noise removed), %d seed(s)\n",
                    common.settings.width, common.settings.height, common.settings.photonsPerPass, o.referenceSpp,
                    o.seeds);
    std::printf("  %-16s %-18s %7s %8s %9s %9s %9s %8s\n", "scene", "radii", "passes", "CPU s", "rel RMSE",
                "(-1% top)", "rel bias", "r_end/px");
    std::vector<std::pair<std::string, bool>> entries;  // (FILE[:PASSES], from the library)
    for (const std::string& entry : o.scenes) entries.push_back({entry, false});
    if (!o.library.empty()) {
        namespace fs = std::filesystem;
        if (!fs::is_directory(o.library)) throw Error("--quality-library '" + o.library + "': not a folder");
        std::vector<std::string> files;
        for (const auto& e : fs::directory_iterator(o.library))
            if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path().string());
        std::sort(files.begin(), files.end());
        for (const std::string& f : files) entries.push_back({f, true});
    }
    for (const auto& [entry, fromLibrary] : entries) {
        // FILE:PASSES; with a CPU budget the pass count is optional (it adds a row planned for it).
        size_t colon = entry.rfind(':');
        std::string file = entry;
        uint64_t passes = 0;
        if (colon != std::string::npos && colon + 1 < entry.size() &&
            entry.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
            file = entry.substr(0, colon);
            passes = std::stoull(entry.substr(colon + 1));
        }
        if (passes == 0 && !equalTime)
            throw Error("--quality-scene '" + entry + "': expected FILE:PASSES (a positive pass count; FILE alone "
                        "only with --quality-cpu-seconds)");
        SceneFile sf = loadSceneFile(file, {});
        if (fromLibrary) {
            sf.scene = withoutSpecularSurfaces(sf.scene);
            sf.scene.name += "-no-specular";
        }
        Scene& scene = sf.scene;
        RenderSettings base = common.settings;
        base.passes = passes > 0 ? passes : 1;
        base.timeBudget = 0;
        Reference ref = loadOrRenderReference(scene, scene.name, base, o);

        struct Variant {
            std::string label;
            RenderSettings s;
            Rgb color;
        };
        std::vector<Variant> variants;
        variants.push_back({"LEGACY", withLegacyDefaults(base, scene), Rgb(40.0f, 0.0f, 0.0f)});
        RenderSettings open = base;
        open.plannedPaths = RadiusDefaults::kOpenEndedPathsPerPixel * uint64_t(base.width) * uint64_t(base.height);
        if (equalTime) {
            // What `tyndall render --time S` resolves (the open-ended plan), then, given a pass
            // count, the same planned for it (`--planned-paths`).
            variants.push_back({"DEFAULTS (--TIME)", open, Rgb(0.0f, 0.0f, 40.0f)});
            if (passes > 0) {
                RenderSettings planned = base;
                planned.plannedPaths = passes * uint64_t(base.photonsPerPass);
                variants.push_back({"AUTO, PLANNED", planned, Rgb(0.0f, 8.0f, 0.0f)});
            }
        } else {
            variants.push_back({"AUTO, PLANNED", base, Rgb(0.0f, 0.0f, 40.0f)});
            RenderSettings noCone = base;
            noCone.photonAngle = 0;
            variants.push_back({"AUTO, NO CONE", noCone, Rgb(20.0f, 0.0f, 20.0f)});
            variants.push_back({"AUTO, OPEN-ENDED", open, Rgb(0.0f, 8.0f, 0.0f)});
        }

        std::vector<Curve> curves;
        for (const Variant& v : variants) {
            std::vector<Run> runs;
            for (int k = 0; k < o.seeds; ++k) {
                RenderSettings sk = v.s;
                sk.seed = base.seed + uint64_t(k);
                runs.push_back(renderRun(scene, sk, ref, passes, o.cpuSeconds));
                if (!o.imageDir.empty())
                    writeImage(o.imageDir + "/" + scene.name + "-" + rowSlug(v.label) + "-seed" + std::to_string(sk.seed) +
                                   ".exr",
                               runs.back().image, {{"Software", "tyndall"}, {"tyndall:settings", sk.toJson().dump()},
                                                   {"tyndall:passes", std::to_string(runs.back().passesDone)}});
            }
            // Over the seeds: errors as root mean squares, bias, CPU time and passes as means. The
            // curve's points are the doubling pass counts every seed reached (at their mean CPU time),
            // then the ends.
            Curve curve{v.label, {}, v.color};
            size_t shared = runs[0].passes.size() - 1;
            for (const Run& r : runs) shared = std::min(shared, r.passes.size() - 1);
            ImageError e;
            double cpu = 0, passesDone = 0;
            for (size_t i = 0; i <= shared; ++i) {
                double x = 0, y = 0;
                for (const Run& r : runs) {
                    size_t j = i < shared ? i : r.passes.size() - 1;
                    x += (equalTime ? r.cpu[j] : r.passes[j]) / o.seeds;
                    y += r.relRmse[j] * r.relRmse[j] / o.seeds;
                }
                if (curve.points.empty() || x > curve.points.back().first) curve.points.push_back({x, std::sqrt(y)});
            }
            for (const Run& r : runs) {
                e.relRmse += r.end.relRmse * r.end.relRmse / o.seeds;
                e.relRmse99 += r.end.relRmse99 * r.end.relRmse99 / o.seeds;
                e.relBias += r.end.relBias / o.seeds;
                cpu += r.cpuSeconds / o.seeds;
                passesDone += double(r.passesDone) / o.seeds;
            }
            e.relRmse = std::sqrt(e.relRmse);
            e.relRmse99 = std::sqrt(e.relRmse99);
            const PassRenderer& renderer = *runs.back().renderer;
            const RenderSettings& r = renderer.settings();
            // The beam radius at the end, in pixel footprints where the media are.
            PixelFootprint fp = measurePixelFootprint(renderer.rayTracer(), scene.camera, base.width, base.height);
            double rEnd = renderer.radii().beamRadiusOf(runs.back().passesDone * r.photonsPerPass);
            std::printf("  %-16s %-18s %7.0f %8.1f %8.2f%% %8.2f%% %+8.2f%% %8.2f   (radius %.4g, surface %.4g, offset %llu, "
                        "photon angle %.3g, direct light %s, boundary %s)\n",
                        scene.name.c_str(), v.label.c_str(), passesDone, cpu, 100 * e.relRmse, 100 * e.relRmse99,
                        100 * e.relBias, rEnd / fp.beam(1.0), r.radius, r.surfaceRadius,
                        (unsigned long long)r.radiusOffset, r.photonAngle, r.directLight.c_str(),
                        r.surfaceBoundary.c_str());
            std::fflush(stdout);
            curves.push_back(std::move(curve));
        }
        panels.push_back({scene.name, std::move(curves)});
    }
    if (!o.plot.empty()) {
        writePlot(o.plot, panels, common.settings.alpha, equalTime ? "CPU SECONDS (EQUAL TIME)" : "PASSES (EQUAL WORK)");
        std::printf("plot -> %s\n", o.plot.c_str());
    }
}

}  // namespace tyndall::app
