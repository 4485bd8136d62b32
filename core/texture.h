#pragma once
// Image textures for materials, sampled through OpenImageIO's TextureSystem (mip-mapped, filtered,
// cached, thread-safe). This header keeps OIIO out of everything that includes it; the
// TextureSystem lives in core/texture_store.cpp.
//
// Route of an image into the TextureSystem (the same for files, .glb buffer views and data URIs):
// decode it with OIIO (from the file, or from memory through an IOMemReader), convert sRGB-encoded
// colour channels to linear once, in float (filtering then averages linear values, as it must),
// and write it with ImageBufAlgo::make_texture as a tiled, mip-mapped half-float OpenEXR file in a
// private temporary folder (removed by ~TextureStore). The TextureSystem reads those files
// on demand, tile by tile, within its cache budget. Why not hand the original file over: the
// TextureSystem applies no colour transform of its own in OIIO 2.4, would auto-mip 8-bit sRGB
// values (averaging encoded values, wrong), and cannot read from memory.
//
// Coordinates are glTF's: (u, v) with (0, 0) the top-left corner of the image, v growing downward.
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/sampling.h"

namespace tyndall {

class LoadBudget;

/// glTF sampler wrap modes (REPEAT 10497, CLAMP_TO_EDGE 33071, MIRRORED_REPEAT 33648).
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

/// How the colour channels (the first three) are stored: sRGB (baseColor, emissive) or linear
/// data (metallicRoughness, normal, transmission). Alpha is always linear.
enum class TextureEncoding { Linear, Srgb };

/// KHR_texture_transform as a 2x3 matrix: uv' = (m[0] u + m[1] v + m[2], m[3] u + m[4] v + m[5]).
struct TextureTransform {
    std::array<float, 6> m{1, 0, 0, 0, 1, 0};

    /// glTF's composition T * R * S of offset, rotation (radians, counter-clockwise in uv as the
    /// extension defines it) and scale.
    static TextureTransform fromOffsetRotationScale(Vec2 offset, float rotation, Vec2 scale);
    Vec2 apply(Vec2 uv) const { return {m[0] * uv.x + m[1] * uv.y + m[2], m[3] * uv.x + m[4] * uv.y + m[5]}; }
    /// How much the transform stretches lengths on average (sqrt |det|): scales a footprint.
    float scale() const;
    bool isIdentity() const { return m == std::array<float, 6>{1, 0, 0, 0, 1, 0}; }
};

/// A material's use of a texture: which one, which TEXCOORD_n set, and the uv transform.
struct TextureRef {
    int texture = -1;  ///< index into the scene's TextureStore; -1 = none
    int texcoord = 0;  ///< 0 or 1
    TextureTransform transform;
    bool present() const { return texture >= 0; }
};

/// Counters for docs/performance.md.
struct TextureStats {
    uint64_t cacheBytes = 0;   ///< bytes of tiles the TextureSystem holds now
    uint64_t fileBytes = 0;    ///< bytes of the mip-mapped files written (all levels, compressed)
    uint64_t cacheLimitBytes = 0;
};

/// The textures of one scene. add*() are for loading (single-threaded); lookup() is thread-safe.
class TextureStore {
public:
    /// `cacheMegabytes`: the TextureSystem's tile cache budget.
    explicit TextureStore(float cacheMegabytes = 256.0f);
    ~TextureStore();
    TextureStore(const TextureStore&) = delete;
    TextureStore& operator=(const TextureStore&) = delete;

    /// Decodes an image file (any format OIIO reads: PNG, JPEG, EXR, ...). `where` prefixes the
    /// Error thrown when it cannot be read ("<scene>: material 'x': baseColorTexture"). Returns its id.
    /// `budget` (may be null) is asked, from the image's header before any pixel is read, for the
    /// memory decoding and mip-mapping take (about 40 bytes a pixel for an RGBA image), and, with
    /// the first texture, for the TextureSystem's tile cache (`cacheMegabytes`).
    int addFile(const std::string& path, TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT,
                const std::string& where, LoadBudget* budget = nullptr);
    /// The same for encoded bytes in memory (a .glb buffer view or a data URI). `mimeType` or
    /// `name` picks the decoder ("image/png", "image/jpeg", or a name with an extension).
    int addEncoded(const std::vector<unsigned char>& bytes, const std::string& mimeType, const std::string& name,
                   TextureEncoding enc, TextureWrap wrapS, TextureWrap wrapT, const std::string& where,
                   LoadBudget* budget = nullptr);
    /// Raw pixels, `channels` floats per pixel (1..4), row-major from the top row; for procedural
    /// textures and tests. Colour channels are taken as `enc`-encoded.
    int addPixels(int width, int height, int channels, const std::vector<float>& pixels, TextureEncoding enc,
                  TextureWrap wrapS, TextureWrap wrapT, const std::string& name);

    /// Filtered RGBA at (u, v) with an isotropic footprint `width` in uv units (0 = the finest
    /// level, bilinear). Channels the image lacks read as: grey -> (g, g, g), alpha -> 1.
    std::array<float, 4> lookup(int texture, Vec2 uv, float width) const;

    size_t size() const;
    int width(int texture) const;
    int height(int texture) const;
    TextureStats stats() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

/// The sRGB transfer function (IEC 61966-2-1), encoded [0, 1] -> linear [0, 1].
inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

}  // namespace tyndall
