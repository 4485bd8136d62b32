#pragma once
// One pass between its CPU stages and the accumulator, inside the render driver
// (hybrid/pass_scheduler.h): with GL, the splats of its photon batches still under way and the
// sums of what has come back; on the CPU alone, the finished pass.
#include <cstdint>
#include <deque>
#include <exception>
#include <future>
#include <utility>

#include "cpu/pass_renderer.h"

namespace tyndall {

struct PassFlight {
    uint64_t pass = 0;
    bool gl = false;  ///< its primary media go through the GL splatter
    PassStats stats;
    /// GL: the primary-media images of the batches still being splatted, in batch order, with
    /// their seconds.
    std::deque<std::future<std::pair<Image, double>>> splats;
    Image splatSum;           ///< GL: the sum of the splats collected so far, in batch order
    std::exception_ptr glError;  ///< GL: the first splat that failed (the pass is then re-rendered)
    /// GL: the secondary stage's sums (beauty = its radiance; with layers, its media and surface
    /// parts). CPU: the finished pass.
    PassLayers image;

    /// Waits for the oldest pending splat and adds it to splatSum; a failed splat is kept in
    /// glError instead (the batches after it are still waited for).
    void collectSplat();
    /// Waits for every pending splat, their images dropped (a pass thrown away).
    void waitSplats();
    /// GL: collects the remaining splats and returns the pass: beauty = splats + secondary
    /// radiance, mediaPrimary = the splats + the CPU's primary-segment share. Rethrows glError.
    PassLayers finishGl();
};

}  // namespace tyndall
