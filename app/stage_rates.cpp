#include "app/stage_rates.h"

#include <ctime>

namespace tyndall::app {

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

PassRate measurePasses(const PassRenderer& renderer, int passes) {
    PassRate r;
    renderer.renderPass(0);  // warm-up: page in, build caches
    auto t0 = std::chrono::steady_clock::now();
    for (int i = 1; i <= passes; ++i) renderer.renderPass(uint64_t(i), &r.totals);
    double s = secondsSince(t0);
    r.passes = passes;
    r.passesPerSecond = passes / s;
    return r;
}

PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes, int rounds) {
    PhotonRate best;
    for (int round = 0; round < rounds; ++round) {
        uint64_t paths = 0, beams = 0, traced = 0;
        auto t0 = std::chrono::steady_clock::now();
        for (int i = 0; i < passes; ++i) {
            PhotonMap m = renderer.tracePhotons(uint64_t(i));
            paths += m.pathCount;
            beams += m.beams.size();
            traced += m.raysTraced;
        }
        double s = secondsSince(t0);
        if (traced / s > best.raysPerSecond) best = {paths / s, beams / s, traced / s};
    }
    return best;
}

}  // namespace tyndall::app
