#include "bench/quality_reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/stage_rates.h"
#include "core/image_io.h"
#include "cpu/embree_scene.h"
#include "cpu/reference_tracer.h"

namespace tyndall::bench {

using app::processCpuSeconds;

Reference loadOrRenderReference(const Scene& scene, const std::string& name, const RenderSettings& s,
                                const std::string& dir, uint32_t spp) {
    namespace fs = std::filesystem;
    fs::create_directories(dir);
    std::string path = dir + "/" + name + "-" + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       "-" + std::to_string(spp) + "spp.exr";
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
    rs.samplesPerPixel = spp;
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
    std::printf("  reference %s rendered (%u spp, %.0f CPU s)\n", path.c_str(), spp, processCpuSeconds() - t0);
    ref.mean = std::move(image.mean);
    ref.noiseVariance = v;
    return ref;
}

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

}  // namespace tyndall::bench
