#pragma once
// The progressive accumulator: the image shown is the mean of all pass images so far. Keeps the
// per-pixel sum in double precision plus the pass count, so accumulators from different processes
// or machines can be summed exactly (merge) and saved/loaded for checkpoint and resume.
// Not thread-safe: one owner (the render loop) adds passes; readers take mean() copies.
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

    /// Binary checkpoint (little-endian: magic "TYNACC1\0", width, height, passes, doubles).
    void save(const std::string& path) const;
    static Accumulator load(const std::string& path);

private:
    int m_width = 0;
    int m_height = 0;
    uint64_t m_passes = 0;
    std::vector<double> m_sum;  // 3 per pixel
};

}  // namespace tyndall
