#pragma once
// A linear float RGB image, row-major, (0,0) at the top-left.
#include <utility>
#include <vector>

#include "core/math.h"

namespace tyndall {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<Rgb> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)) {}
    Rgb& at(int x, int y) { return pixels[size_t(y) * width + x]; }
    const Rgb& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
    Image& operator+=(const Image& o) {
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] += o.pixels[i];
        return *this;
    }
};

/// Adds `part` to the running sum `sum` of a pass's photon batches (or their layers): the first
/// part is moved in, so a sum of one part is that part bit for bit.
inline void addBatch(Image& sum, Image&& part) {
    if (sum.pixels.empty())
        sum = std::move(part);
    else
        sum += part;
}

}  // namespace tyndall
