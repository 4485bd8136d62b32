#pragma once
// Image files through OpenImageIO, format chosen by extension:
//   .exr  linear half/float RGB, with `metadata` (e.g. "tyndall:settings" JSON) in the header;
//   .png  (and .jpg/.tif): exposure-scaled, ACES-fitted filmic tone curve, sRGB-encoded 8 bit.
#include <string>
#include <utility>
#include <vector>

#include "core/image.h"

namespace tyndall {

using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Throws Error naming the file when it cannot be written (bad directory, unknown extension).
void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata = {}, float exposure = 1.0f);
/// Reads an image as linear float RGB (PNG/JPG are sRGB-decoded). Throws Error naming the file.
Image readImage(const std::string& path);
/// The header attribute `name` of an image file (e.g. "tyndall:settings" of an EXR written with
/// metadata) as text; "" when the file has no such attribute. Throws Error naming the file.
std::string readImageAttribute(const std::string& path, const std::string& name);
/// Throws Error when `path` has an extension writeImage does not handle, before any rendering.
void checkImageExtension(const std::string& path);

/// The display transform used for PNG: filmic tone curve then sRGB, per channel, in [0, 1].
float toneMapChannel(float linear, float exposure);

}  // namespace tyndall
