#include "bench/pass_rate_targets.h"

#include <cstdio>

namespace tyndall::bench {

namespace {
constexpr unsigned kTargetThreads = 2;  // every target is "on 2 cores"
constexpr PassRateTarget kTargets[] = {
    {512, 512, 1000, 3.0},
    {1920, 1080, 4000, 1.0},
};

std::string describe(const PassRateTarget& t) {
    char buf[128];
    std::snprintf(buf, sizeof buf, ">= %g passes/s is the target for %dx%d, %u photon paths/pass, %u threads",
                  t.passesPerSecond, t.width, t.height, t.photonsPerPass, kTargetThreads);
    return buf;
}
}  // namespace

const PassRateTarget* passRateTarget(int width, int height, unsigned photonsPerPass) {
    for (const PassRateTarget& t : kTargets)
        if (t.width == width && t.height == height && t.photonsPerPass == photonsPerPass) return &t;
    return nullptr;
}

std::string passRateVerdict(double passesPerSecond, int width, int height, unsigned photonsPerPass,
                            unsigned threads) {
    if (const PassRateTarget* t = passRateTarget(width, height, photonsPerPass)) {
        if (threads != kTargetThreads) return "(not judged: " + describe(*t) + ")";
        char buf[96];
        std::snprintf(buf, sizeof buf, "(target at %dx%d: >= %g: %s)", width, height, t->passesPerSecond,
                      passesPerSecond >= t->passesPerSecond ? "met" : "NOT met");
        return buf;
    }
    for (const PassRateTarget& t : kTargets)
        if (t.width == width && t.height == height) return "(not judged: " + describe(t) + ")";
    return "(no pass-rate target at this size: " + describe(kTargets[0]) + "; " + describe(kTargets[1]) + ")";
}

}  // namespace tyndall::bench
