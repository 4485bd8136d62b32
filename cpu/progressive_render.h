#pragma once
// The progressive loop: runs passes, adds each to the accumulator, reports after every pass and
// stops on the pass count, the time budget, or when the callback says so (cancel). Resetting is
// the caller's: reset the accumulator and start again at pass 0.
#include <functional>

#include "core/accumulator.h"
#include "cpu/pass_renderer.h"

namespace tyndall {

struct RenderProgress {
    uint64_t pass = 0;         ///< index of the pass just added
    uint64_t passesDone = 0;   ///< passes added by this call
    double elapsedSeconds = 0;
    PassStats totals;
};

/// Renders passes firstPass, firstPass+1, ... into `acc` until settings.passes passes were added
/// (or, with settings.timeBudget > 0, until the budget is spent). `onPass` may return false to stop.
RenderProgress renderProgressive(const PassRenderer& renderer, Accumulator& acc, uint64_t firstPass,
                                 const std::function<bool(const RenderProgress&)>& onPass = {});

}  // namespace tyndall
