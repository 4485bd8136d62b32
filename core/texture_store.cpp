#include "core/texture.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/load_budget.h"

namespace tyndall {

namespace fs = std::filesystem;

TextureTransform TextureTransform::fromOffsetRotationScale(Vec2 offset, float rotation, Vec2 scale) {
    // KHR_texture_transform: T * R * S with R = [[cos, sin], [-sin, cos]].
    float c = std::cos(rotation), s = std::sin(rotation);
    TextureTransform t;
    t.m = {c * scale.x, s * scale.y, offset.x, -s * scale.x, c * scale.y, offset.y};
    return t;
}

float TextureTransform::scale() const { return std::sqrt(std::abs(m[0] * m[4] - m[1] * m[3])); }

namespace {
OIIO::TextureOpt::Wrap oiioWrap(TextureWrap w) {
    switch (w) {
        case TextureWrap::Repeat: return OIIO::TextureOpt::WrapPeriodic;
        case TextureWrap::ClampToEdge: return OIIO::TextureOpt::WrapClamp;
        case TextureWrap::MirroredRepeat: return OIIO::TextureOpt::WrapMirror;
    }
    return OIIO::TextureOpt::WrapPeriodic;
}

/// glTF colours are not premultiplied: keep alpha unassociated (OIIO would premultiply PNGs).
const OIIO::ImageSpec& readConfig() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

std::string extensionForMime(const std::string& mime, const std::string& name) {
    if (mime == "image/png") return "png";
    if (mime == "image/jpeg") return "jpg";
    if (mime == "image/webp") return "webp";
    std::string ext = fs::path(name).extension().string();
    return ext.empty() ? std::string() : ext.substr(1);
}
}  // namespace

struct TextureStore::Impl {
    struct Entry {
        OIIO::ustring file;
        OIIO::TextureSystem::TextureHandle* handle = nullptr;
        OIIO::TextureOpt::Wrap wrapS, wrapT;
        int width = 0, height = 0;
    };
    OIIO::TextureSystem* ts = nullptr;
    fs::path folder;
    std::vector<Entry> entries;
    uint64_t fileBytes = 0;
    float cacheMegabytes = 256;

    ~Impl() {
        if (ts) OIIO::TextureSystem::destroy(ts);
        std::error_code ec;
        if (!folder.empty()) fs::remove_all(folder, ec);
    }

    const fs::path& tempFolder() {
        if (folder.empty()) {
            static std::atomic<int> counter{0};
            fs::path f = fs::temp_directory_path() /
                         ("tyndall-textures-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
            std::error_code ec;
            fs::create_directories(f, ec);
            if (ec) throw Error("cannot create the texture folder " + f.string() + ": " + ec.message());
            folder = f;
        }
        return folder;
    }

    /// `src` holds the decoded image: make it RGBA float, linearise, mip-map into the folder.
    int add(OIIO::ImageBuf& src, TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT, const std::string& where,
            LoadBudget* budget = nullptr) {
        const OIIO::ImageSpec& header = src.spec();  // the header only: no pixel is read yet
        if (budget && header.width > 0 && header.height > 0) {
            // The decoded float image, its RGBA copy, and make_texture's float mip chain.
            const uint64_t pixels =
                uint64_t(header.width) * uint64_t(header.height) * uint64_t(std::max(header.depth, 1));
            const uint64_t channels = uint64_t(std::max(header.nchannels, 1));
            budget->check(pixels * (channels * sizeof(float) + 40),
                          where + ": a " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                              " image of " + std::to_string(channels) + " channels");
        }
        if (budget && !ts) budget->reserve(uint64_t(cacheMegabytes * 1048576.0), where + ": the texture cache");
        if (!src.read(0, 0, true, OIIO::TypeDesc::FLOAT))
            throw Error(where + ": cannot decode the image: " + src.geterror());
        const OIIO::ImageSpec& in = src.spec();
        if (in.width <= 0 || in.height <= 0 || in.nchannels <= 0)
            throw Error(where + ": the image is empty");
        OIIO::ImageSpec spec(in.width, in.height, 4, OIIO::TypeDesc::FLOAT);
        OIIO::ImageBuf rgba(spec);
        const int nc = in.nchannels;
        std::vector<float> px(static_cast<size_t>(nc));
        for (int y = 0; y < in.height; ++y) {
            for (int x = 0; x < in.width; ++x) {
                src.getpixel(x + in.x, y + in.y, px.data(), nc);
                float out[4];
                int colour = nc >= 3 ? 3 : 1;  // grey (+alpha) images replicate the grey channel
                for (int c = 0; c < 3; ++c) out[c] = px[size_t(colour == 3 ? c : 0)];
                out[3] = nc == 2 ? px[1] : nc >= 4 ? px[3] : 1.0f;
                if (enc == TextureEncoding::Srgb)
                    for (int c = 0; c < 3; ++c) out[c] = srgbToLinear(std::clamp(out[c], 0.0f, 1.0f));
                rgba.setpixel(x, y, out, 4);
            }
        }
        fs::path file = tempFolder() / ("texture-" + std::to_string(entries.size()) + ".exr");
        OIIO::ImageSpec config;
        config.format = OIIO::TypeDesc::HALF;
        config.tile_width = config.tile_height = 64;
        config.attribute("maketx:highlightcomp", 0);
        if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, rgba, file.string(), config))
            throw Error(where + ": cannot write the mip-mapped texture " + file.string() + ": " + OIIO::geterror());
        std::error_code ec;
        fileBytes += fs::file_size(file, ec);
        if (!ts) {
            ts = OIIO::TextureSystem::create(false);
            ts->attribute("max_memory_MB", cacheMegabytes);
            ts->attribute("autotile", 0);
            ts->attribute("automip", 0);
        }
        Entry e;
        e.file = OIIO::ustring(file.string());
        e.handle = ts->get_texture_handle(e.file);
        if (!e.handle) throw Error(where + ": the texture system cannot open " + file.string() + ": " + ts->geterror());
        e.wrapS = oiioWrap(wrapS);
        e.wrapT = oiioWrap(wrapT);
        e.width = in.width;
        e.height = in.height;
        entries.push_back(e);
        return int(entries.size() - 1);
    }
};

TextureStore::TextureStore(float cacheMegabytes) : m_impl(std::make_unique<Impl>()) {
    m_impl->cacheMegabytes = cacheMegabytes;
}
TextureStore::~TextureStore() = default;

int TextureStore::addFile(const std::string& path, TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT,
                          const std::string& where, LoadBudget* budget) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw Error(where + ": image file '" + path + "' not found");
    OIIO::ImageBuf src(path, 0, 0, nullptr, &readConfig());
    return m_impl->add(src, enc, wrapS, wrapT, where + " ('" + path + "')", budget);
}

int TextureStore::addEncoded(const std::vector<unsigned char>& bytes, const std::string& mimeType,
                             const std::string& name, TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT,
                             const std::string& where, LoadBudget* budget) {
    std::string ext = extensionForMime(mimeType, name);
    if (ext.empty()) throw Error(where + ": image has no mimeType and no file extension: cannot tell its format");
    OIIO::Filesystem::IOMemReader mem(bytes.data(), bytes.size());
    // The name only selects the decoder; the bytes come from `mem`.
    OIIO::ImageBuf src("memory." + ext, 0, 0, nullptr, &readConfig(), &mem);
    return m_impl->add(src, enc, wrapS, wrapT, where, budget);
}

int TextureStore::addPixels(int width, int height, int channels, const std::vector<float>& pixels,
                            TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT, const std::string& name) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        pixels.size() != size_t(width) * size_t(height) * size_t(channels))
        throw Error(name + ": pixel array does not match " + std::to_string(width) + "x" + std::to_string(height) +
                    "x" + std::to_string(channels));
    OIIO::ImageBuf src(OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::FLOAT), (void*)pixels.data());
    return m_impl->add(src, enc, wrapS, wrapT, name);
}

std::array<float, 4> TextureStore::lookup(int texture, Vec2 uv, float width) const {
    const Impl::Entry& e = m_impl->entries[size_t(texture)];
    OIIO::TextureOpt opt;
    opt.swrap = e.wrapS;
    opt.twrap = e.wrapT;
    // Bilinear within a level (OIIO's default smart-bicubic blurs texel centres, unlike glTF's
    // LINEAR), trilinear between levels; the footprint picks the level.
    opt.interpmode = OIIO::TextureOpt::InterpBilinear;
    opt.mipmode = OIIO::TextureOpt::MipModeTrilinear;
    std::array<float, 4> out{0, 0, 0, 1};
    if (!m_impl->ts->texture(e.handle, nullptr, opt, uv.x, uv.y, width, 0.0f, 0.0f, width, 4, out.data()))
        return {0, 0, 0, 1};
    return out;
}

size_t TextureStore::size() const { return m_impl->entries.size(); }
int TextureStore::width(int texture) const { return m_impl->entries[size_t(texture)].width; }
int TextureStore::height(int texture) const { return m_impl->entries[size_t(texture)].height; }

TextureStats TextureStore::stats() const {
    TextureStats s;
    s.fileBytes = m_impl->fileBytes;
    s.cacheLimitBytes = uint64_t(m_impl->cacheMegabytes * 1024.0 * 1024.0);
    if (m_impl->ts) {
        int64_t used = 0;
        if (m_impl->ts->getattribute("stat:cache_memory_used", OIIO::TypeInt64, &used)) s.cacheBytes = uint64_t(used);
    }
    return s;
}

}  // namespace tyndall
