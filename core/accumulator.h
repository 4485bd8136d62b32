#pragma once
// The progressive accumulator: the image shown is the mean of all pass images so far. Keeps the
// per-pixel sum in double precision plus the pass count, so accumulators from different processes
// or machines can be summed exactly (merge) and saved/loaded for checkpoint and resume.
// Not thread-safe: one owner (the render loop) adds passes; readers take mean() copies.
//
// No NaN or infinity ever reaches the sums: addPass drops a pixel whose pass value is not finite
// (it counts as black in that pass) and counts it in rejectedSamples(), which the render command
// reports at the end. One bad sample would otherwise poison the pixel for the rest of the render.
#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace tyndall {

class Accumulator {
public:
    Accumulator() = default;
    Accumulator(int width, int height);

    void addPass(const Image& pass);
    /// Adds another accumulator's passes (same size), as if its passes had been added here.
    void merge(const Accumulator& other);
    void reset();

    /// Running mean of the passes as float; black when no pass was added.
    Image mean() const;
    uint64_t passCount() const { return m_passes; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// Mean of pixel (x, y), channel c, in double.
    double meanAt(int x, int y, int c) const;
    /// Pixel samples dropped by addPass because a channel was NaN or infinite (merge adds them).
    uint64_t rejectedSamples() const { return m_rejected; }

    /// The state itself: 3 doubles per pixel (r, g, b), row-major, each the sum over the passes.
    /// Checkpoints and MPI ranks move these; adding the same passes in the same order gives the
    /// same bits.
    const std::vector<double>& sums() const { return m_sum; }
    /// An accumulator from saved state; throws Error when `sums` does not hold 3 x width x height.
    static Accumulator fromSums(int width, int height, uint64_t passes, uint64_t rejected, std::vector<double> sums);

    /// Binary checkpoint (little-endian: magic "TYNACC1\0", width, height, passes, doubles).
    void save(const std::string& path) const;
    static Accumulator load(const std::string& path);

private:
    int m_width = 0;
    int m_height = 0;
    uint64_t m_passes = 0;
    uint64_t m_rejected = 0;
    std::vector<double> m_sum;  // 3 per pixel
};

}  // namespace tyndall
