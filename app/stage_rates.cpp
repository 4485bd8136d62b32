#include "app/stage_rates.h"

#include <algorithm>
#include <cstdio>
#include <ctime>

namespace tyndall::app {

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

PassRate measurePasses(const PassRenderer& renderer, int passes) {
    PassRate r;
    renderer.renderPass(0);  // warm-up: page in, build caches
    auto t0 = Clock::now();
    const double c0 = processCpuSeconds();
    for (int i = 1; i <= passes; ++i) renderer.renderPass(uint64_t(i), &r.totals);
    r.cpuSeconds = processCpuSeconds() - c0;
    double s = secondsSince(t0);
    r.passes = passes;
    r.passesPerSecond = passes / s;
    return r;
}

void printRate(const char* what, double value, const char* unit, const std::string& note) {
    std::printf("  %-34s %12.3f %-12s %s\n", what, value, unit, note.c_str());
}

std::string ratio(double value, double base, const char* baseName) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "= %.2fx %s", value / base, baseName);
    return buf;
}

void printPassRate(const PassRate& pr, const RenderSettings& settings, const std::string& passesNote) {
    const PassStats& t = pr.totals;
    const double perPass = 1.0 / pr.passesPerSecond;
    const double pixels = double(settings.width) * settings.height * pr.passes;
    printRate("passes", pr.passesPerSecond, "passes/s", passesNote);
    printRate("camera paths", pixels / t.cameraSeconds / 1e6, "M paths/s");
    printRate("secondary gather queries", t.beamQueries / t.cameraSeconds / 1e3, "k queries/s",
              "(inside the camera stage)");
    printRate("primary splat estimator evals", t.rasterTests / t.splatSeconds / 1e6, "M evals/s");
    printRate("  photon stage", t.photonSeconds / pr.passes * 1e3, "ms/pass",
              ratio(t.photonSeconds / pr.passes, perPass, "of a pass"));
    printRate("  camera stage", t.cameraSeconds / pr.passes * 1e3, "ms/pass",
              ratio(t.cameraSeconds / pr.passes, perPass, "of a pass"));
    printRate("  primary splat stage", t.splatSeconds / pr.passes * 1e3, "ms/pass",
              ratio(t.splatSeconds / pr.passes, perPass, "of a pass"));
    if (pr.cpuSeconds > 0)
        printRate("CPU time per pass", pr.cpuSeconds / pr.passes * 1e3, "ms/pass", "(the process, every thread)");
    printRate("beams per pass", double(t.beams) / pr.passes, "beams");
}

PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes, int rounds) {
    PhotonRate best;
    for (int round = 0; round < rounds; ++round) {
        uint64_t paths = 0, beams = 0, traced = 0;
        double length = 0, s = 0;  // s: the tracing alone, not the tallies below
        for (int i = 0; i < passes; ++i) {
            const auto t0 = Clock::now();
            PhotonMap m = renderer.tracePhotons(uint64_t(i));
            s += secondsSince(t0);
            paths += m.pathCount;
            beams += m.beams.size();
            traced += m.raysTraced;
            for (const PhotonBeam& b : m.beams) length += double(b.tMax);
        }
        if (traced / s > best.raysPerSecond)
            best = {paths / s, beams / s, traced / s, double(beams) / double(std::max<uint64_t>(paths, 1)),
                    beams > 0 ? length / double(beams) : 0.0};
    }
    return best;
}

}  // namespace tyndall::app
