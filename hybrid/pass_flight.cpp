#include "hybrid/pass_flight.h"

namespace tyndall {

void PassFlight::collectSplat() {
    auto future = std::move(splats.front());
    splats.pop_front();
    try {
        auto [part, seconds] = future.get();
        stats.splatSeconds += seconds;
        if (!glError) addBatch(splatSum, std::move(part));
    } catch (...) {
        if (!glError) glError = std::current_exception();
    }
}

void PassFlight::waitSplats() {
    for (auto& s : splats)
        if (s.valid()) s.wait();
    splats.clear();
}

PassLayers PassFlight::finishGl() {
    while (!splats.empty()) collectSplat();
    if (glError) std::rethrow_exception(glError);
    PassLayers out = std::move(image);
    if (!out.surface.pixels.empty()) addBatch(out.mediaPrimary, Image(splatSum));  // the AOV layers
    splatSum += out.beauty;
    out.beauty = std::move(splatSum);
    return out;
}

}  // namespace tyndall
