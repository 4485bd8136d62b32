#pragma once
// The heterogeneous-media study of build/bench/tyndall_stages: the cost of free-flight sampling
// (the stored transmittance distances and delta tracking) in density-grid media under the three
// majorants tracking can use, measured in the caller's run so it can be printed as ratios.
#include <cstdint>

#include "cpu/pass_renderer.h"

namespace tyndall::bench {

/// Which bound delta tracking runs against.
enum class MajorantMode {
    Grid,     ///< the grid's majorant grid, walked cell by cell (what the renderer uses)
    Segment,  ///< one bound per segment: the maximum of the majorant cells it crosses
    Global,   ///< the grid's global maximum density
};

struct FreeFlightRate {
    double samplesPerSecond = 0;         ///< collision distances sampled per second (all threads)
    double densityLookupsPerSample = 0;  ///< tentative collisions (density evaluations) per distance
    uint64_t segments = 0;               ///< primary segments in grid media the samples were spread over
};

/// Samples `samples` collision distances along pass 0's primary camera segments that run through
/// density-grid media (as the camera pass does for its stored distances), in parallel with keyed
/// streams. `perSegment` > 1 draws them in sets of that size with sampleCollisionDistances (one
/// majorant walk per set, as the renderer stores them). Zero rates when no primary segment is in a
/// grid medium.
FreeFlightRate measureFreeFlights(const PassRenderer& renderer, uint64_t samples, MajorantMode mode,
                                  int perSegment = 1);

}  // namespace tyndall::bench
