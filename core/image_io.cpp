#include "core/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "core/error.h"

namespace tyndall {

namespace {
std::string extensionOf(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}
bool isLinearFormat(const std::string& ext) {
    return ext == ".exr" || ext == ".hdr";
}
bool isDisplayFormat(const std::string& ext) {
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff";
}
float srgbEncode(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}
float srgbDecode(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}
}  // namespace

float toneMapChannel(float linear, float exposure) {
    float x = std::max(0.0f, linear * exposure);
    if (!std::isfinite(x)) x = 0.0f;
    // Narkowicz's fit of the ACES filmic curve: gentle toe, soft shoulder for bright caustics.
    float mapped = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
    return srgbEncode(clampValue(mapped, 0.0f, 1.0f));
}

void checkImageExtension(const std::string& path) {
    std::string ext = extensionOf(path);
    if (!isLinearFormat(ext) && !isDisplayFormat(ext))
        throw Error("output '" + path + "': unknown image type '" + ext + "' (use .exr, .hdr, .png, .jpg or .tif)");
}

void writeImage(const std::string& path, const Image& image, const ImageMetadata& metadata, float exposure) {
    checkImageExtension(path);
    std::string ext = extensionOf(path);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    if (!out) throw Error("output '" + path + "': " + OIIO::geterror());
    const bool linear = isLinearFormat(ext);
    OIIO::ImageSpec spec(image.width, image.height, 3, linear ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    for (const auto& [k, v] : metadata) spec.attribute(k, v);
    if (linear) spec.attribute("compression", "zip");
    if (!out->open(path, spec)) throw Error("cannot write '" + path + "': " + out->geterror());
    bool ok;
    if (linear) {
        ok = out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data());
    } else {
        std::vector<uint8_t> bytes(image.pixels.size() * 3);
        for (size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                bytes[3 * i + c] = uint8_t(std::lround(255.0f * toneMapChannel(image.pixels[i][c], exposure)));
        ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    if (!ok || !out->close()) throw Error("failed writing '" + path + "': " + out->geterror());
}

bool formatHasAlpha(const std::string& path) {
    const std::string ext = extensionOf(path);
    return ext == ".exr" || ext == ".png" || ext == ".tif" || ext == ".tiff";
}

namespace {
/// A display format with an alpha channel: RGBA bytes, the colour unassociated before the tone map.
void writeDisplayWithAlpha(const std::string& path, const Image& image, const Image& alpha,
                           const ImageMetadata& metadata, float exposure) {
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    if (!out) throw Error("output '" + path + "': " + OIIO::geterror());
    OIIO::ImageSpec spec(image.width, image.height, 4, OIIO::TypeDesc::UINT8);
    spec.alpha_channel = 3;
    spec.attribute("oiio:UnassociatedAlpha", 1);
    for (const auto& [k, v] : metadata) spec.attribute(k, v);
    if (!out->open(path, spec)) throw Error("cannot write '" + path + "': " + out->geterror());
    std::vector<uint8_t> bytes(image.pixels.size() * 4);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        const float a = clampValue(alpha.pixels[i].r, 0.0f, 1.0f);
        for (int c = 0; c < 3; ++c)
            bytes[4 * i + c] =
                a > 0 ? uint8_t(std::lround(255.0f * toneMapChannel(image.pixels[i][c] / a, exposure))) : uint8_t(0);
        bytes[4 * i + 3] = uint8_t(std::lround(255.0f * a));
    }
    if (!out->write_image(OIIO::TypeDesc::UINT8, bytes.data()) || !out->close())
        throw Error("failed writing '" + path + "': " + out->geterror());
}
}  // namespace

void writeImageLayers(const std::string& path, const Image& beauty, const ImageLayers& layers,
                      const ImageMetadata& metadata, float exposure, const Image* alpha) {
    checkImageExtension(path);
    if (alpha) {
        TYNDALL_CHECK(alpha->width == beauty.width && alpha->height == beauty.height, "alpha size differs");
        if (!formatHasAlpha(path)) throw Error("output '" + path + "': an alpha channel needs .exr, .png or .tif");
        if (extensionOf(path) != ".exr") return writeDisplayWithAlpha(path, beauty, *alpha, metadata, exposure);
    } else if (layers.empty() || extensionOf(path) != ".exr") {
        return writeImage(path, beauty, metadata, exposure);
    }
    const int first = alpha ? 4 : 3;  // the layers' first channel
    const int nch = first + 3 * int(layers.size());
    OIIO::ImageSpec spec(beauty.width, beauty.height, nch, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B"};
    if (alpha) {
        spec.channelnames.push_back("A");
        spec.alpha_channel = 3;
    }
    for (const auto& [name, image] : layers) {
        TYNDALL_CHECK(image.width == beauty.width && image.height == beauty.height, "layer '" + name + "' size differs");
        for (const char* c : {".R", ".G", ".B"}) spec.channelnames.push_back(name + c);
    }
    for (const auto& [k, v] : metadata) spec.attribute(k, v);
    spec.attribute("compression", "zip");
    std::vector<float> data(size_t(beauty.width) * beauty.height * nch);
    for (size_t i = 0; i < beauty.pixels.size(); ++i) {
        float* px = &data[i * nch];
        for (int c = 0; c < 3; ++c) px[c] = beauty.pixels[i][c];
        if (alpha) px[3] = alpha->pixels[i].r;
        for (size_t l = 0; l < layers.size(); ++l)
            for (int c = 0; c < 3; ++c) px[first + 3 * l + c] = layers[l].second.pixels[i][c];
    }
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path);
    if (!out) throw Error("output '" + path + "': " + OIIO::geterror());
    if (!out->open(path, spec)) throw Error("cannot write '" + path + "': " + out->geterror());
    if (!out->write_image(OIIO::TypeDesc::FLOAT, data.data()) || !out->close())
        throw Error("failed writing '" + path + "': " + out->geterror());
}

std::vector<std::string> readImageChannels(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read image '" + path + "': " + OIIO::geterror());
    return in->spec().channelnames;
}

Image readImageLayer(const std::string& path, const std::string& layer) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const std::string prefix = layer.empty() ? "" : layer + ".";
    int idx[3];
    std::string have;
    for (int c = 0; c < 3; ++c) {
        idx[c] = spec.channelindex(prefix + "RGB"[c]);
        if (idx[c] < 0) {
            for (const auto& n : spec.channelnames) have += (have.empty() ? "" : ", ") + n;
            throw Error("image '" + path + "' has no channel '" + prefix + "RGB"[c] + "' (channels: " + have + ")");
        }
    }
    std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
        throw Error("cannot read image '" + path + "': " + in->geterror());
    Image img(spec.width, spec.height);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = Rgb(data[i * spec.nchannels + idx[0]], data[i * spec.nchannels + idx[1]],
                            data[i * spec.nchannels + idx[2]]);
    return img;
}

Image readImage(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
        throw Error("cannot read image '" + path + "': " + in->geterror());
    Image img(spec.width, spec.height);
    bool decode = !isLinearFormat(extensionOf(path));
    for (size_t i = 0; i < img.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            float v = data[i * spec.nchannels + std::min(c, spec.nchannels - 1)];
            img.pixels[i][c] = decode ? srgbDecode(v) : v;
        }
    in->close();
    return img;
}

ImageHeader readImageHeader(const std::string& path) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    ImageHeader h{spec.width, spec.height * std::max(spec.depth, 1), spec.nchannels};
    in->close();
    return h;
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw Error("cannot read image '" + path + "': " + OIIO::geterror());
    const OIIO::ParamValue* p = in->spec().find_attribute(name);
    std::string value = p ? p->get_string() : std::string();
    in->close();
    return value;
}

}  // namespace tyndall
