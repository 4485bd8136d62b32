#pragma once
// The render loop for AOV layers and for MPI: passes go out in rounds of one pass per rank (pass
// firstPass + k*ranks + r on rank r, so which rank renders a pass never depends on timing), the
// pass images are gathered to rank 0 and added there in pass order. Adding the same float pass
// images in the same order makes the double sums, and so the image, equal bit for bit to a
// single-process render of the same passes (a reduction of per-rank sums would not: double
// addition is not associative). Rank 0 decides before each round how many passes it holds (the
// pass target, the time budget, a stop from the callback) and broadcasts it, so with --time
// all ranks agree on one pass count.
//
// The primary media are splatted by the CPU twin here (PassRenderer::renderPassLayers): the
// hybrid GL scheduler serves the single-process render without layers.
#include <functional>

#include "app/mpi_ranks.h"
#include "core/layer_accumulator.h"
#include "cpu/pass_renderer.h"
#include "cpu/progressive_render.h"

namespace tyndall::app {

struct RoundLimits {
    uint64_t passes = 0;  ///< passes to add in this run (used when seconds == 0)
    double seconds = 0;   ///< > 0: start rounds until this many seconds of this run have passed
};

/// Called on rank 0 after each pass is added, in pass order; false stops after the round.
using PassAddedFn = std::function<bool(const LayerAccumulator&, const RenderProgress&)>;

/// Renders passes firstPass, firstPass+1, ... into `acc` (rank 0's; other ranks' stays empty).
/// Every rank must call it with the same arguments. Returns rank 0's progress (others': theirs).
RenderProgress renderRounds(const PassRenderer& renderer, LayerAccumulator& acc, uint64_t firstPass,
                            RoundLimits limits, const Ranks& ranks, const PassAddedFn& passAdded);

}  // namespace tyndall::app
