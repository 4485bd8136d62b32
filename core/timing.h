#pragma once
// Wall-clock seconds for stage timings and time budgets (a steady clock: never jumps with the
// system time).
#include <chrono>

namespace tyndall {

using Clock = std::chrono::steady_clock;

/// Seconds from `t0` to now.
inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace tyndall
