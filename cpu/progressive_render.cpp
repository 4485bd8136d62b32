#include "cpu/progressive_render.h"

#include <chrono>

namespace tyndall {

RenderProgress renderProgressive(const PassRenderer& renderer, Accumulator& acc, uint64_t firstPass,
                                 const std::function<bool(const RenderProgress&)>& onPass) {
    const RenderSettings& s = renderer.settings();
    auto start = std::chrono::steady_clock::now();
    RenderProgress p;
    for (uint64_t pass = firstPass;; ++pass) {
        if (s.timeBudget <= 0 && p.passesDone >= s.passes) break;
        if (s.timeBudget > 0 && p.elapsedSeconds >= s.timeBudget) break;
        acc.addPass(renderer.renderPass(pass, &p.totals));
        p.pass = pass;
        p.passesDone++;
        p.elapsedSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (onPass && !onPass(p)) break;
    }
    return p;
}

}  // namespace tyndall
