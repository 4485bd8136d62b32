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
/// Like writeImage, plus named layers: an EXR becomes multi-layer, the beauty image as R, G, B and
/// each layer as "<name>.R", "<name>.G", "<name>.B" (all the same size as `beauty`); other formats
/// hold the beauty image only.
using ImageLayers = std::vector<std::pair<std::string, Image>>;
/// `alpha` (its r channel; the transparent film's coverage): an EXR gets channel A after R, G, B,
/// a PNG or TIFF an alpha channel, unassociated as those formats keep it (the colour divided by
/// alpha before the tone map); formatHasAlpha() says which outputs can hold it.
void writeImageLayers(const std::string& path, const Image& beauty, const ImageLayers& layers,
                      const ImageMetadata& metadata = {}, float exposure = 1.0f, const Image* alpha = nullptr);
/// .exr, .png, .tif: the outputs that hold an alpha channel.
bool formatHasAlpha(const std::string& path);
/// The channels "<layer>.R/G/B" of an image file ("" = R, G, B) as an image; Error naming the
/// file and the channels it does have when they are missing.
Image readImageLayer(const std::string& path, const std::string& layer);
/// The channel names of an image file, in order.
std::vector<std::string> readImageChannels(const std::string& path);
/// Reads an image as linear float RGB (PNG/JPG are sRGB-decoded). Throws Error naming the file.
Image readImage(const std::string& path);
/// An image file's size as its header declares it, no pixel read. Throws Error naming the file.
struct ImageHeader {
    int width = 0, height = 0, channels = 0;
};
ImageHeader readImageHeader(const std::string& path);
/// The header attribute `name` of an image file (e.g. "tyndall:settings" of an EXR written with
/// metadata) as text; "" when the file has no such attribute. Throws Error naming the file.
std::string readImageAttribute(const std::string& path, const std::string& name);
/// Throws Error when `path` has an extension writeImage does not handle, before any rendering.
void checkImageExtension(const std::string& path);

/// The display transform used for PNG: filmic tone curve then sRGB, per channel, in [0, 1].
float toneMapChannel(float linear, float exposure);

}  // namespace tyndall
