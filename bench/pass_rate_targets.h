#pragma once
// The whole-pass rate targets build/bench/tyndall_stages judges its "passes" figure against. Each
// target holds for one image size, one photon count per pass and 2 threads (CPU only); a run at
// other settings is not judged, and its note says which settings would be.
#include <string>

namespace tyndall::bench {

struct PassRateTarget {
    int width, height;        ///< image size in pixels
    unsigned photonsPerPass;  ///< photon paths per pass
    double passesPerSecond;   ///< the target: at least this many passes per second
};

/// The target for `width` x `height` with `photonsPerPass` photon paths per pass, or nullptr:
/// >= 3 passes/s at 512x512 with 1000, >= 1.0 at 1920x1080 with 4000.
const PassRateTarget* passRateTarget(int width, int height, unsigned photonsPerPass);

/// The note printed after the measured pass rate: the applicable target and "met" or "NOT met"
/// when size, photon count and `threads` (2) match a target; otherwise why the run is not judged
/// and which settings are.
std::string passRateVerdict(double passesPerSecond, int width, int height, unsigned photonsPerPass,
                            unsigned threads);

}  // namespace tyndall::bench
