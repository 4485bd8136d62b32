#pragma once
// Tests' PNG writer: encodes 8-bit pixels to PNG bytes in memory (stb_image_write, libstb-dev).
#include <stb_image_write.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tyndall::test {

/// `px`: width * height * channels bytes, top row first.
inline std::string pngBytes(int width, int height, int channels, const std::vector<uint8_t>& px) {
    std::string out;
    stbi_write_png_to_func(
        [](void* ctx, void* data, int size) { static_cast<std::string*>(ctx)->append(static_cast<char*>(data), size); },
        &out, width, height, channels, px.data(), width * channels);
    return out;
}

}  // namespace tyndall::test
