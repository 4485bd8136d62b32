#pragma once
// The environment light: radiance arriving from infinitely far away, from every direction, given
// by a latitude-longitude (equirectangular) image or a constant colour.
//
// Mapping (the convention of Mitsuba 3's `envmap`; +Y is up, as in glTF). A direction seen from
// the scene, d = (x, y, z) unit, with the rotation undone, reads the image at
//   u = atan2(x, -z) / (2 pi)   wrapped into [0, 1)    (0 = left edge, grows to the right)
//   v = acos(y) / pi                                  (0 = top edge: straight up; 1 = straight down)
// so the image's centre (u, v) = (1/2, 1/2) is the direction +Z, its left and right edges -Z,
// u = 1/4 is +X and u = 3/4 is -X; the top row is the sky overhead (+Y), the horizon the middle
// row. Texel (i, j) (column i, row j from the top) is the constant radiance of the solid angle
// u in [i, i + 1) / W, v in [j, j + 1) / H (nearest texel, no filtering). `rotate` turns the
// environment by that many degrees about +Y (right-handed: 90 takes the image's centre from +Z to
// +X). `scale` multiplies every texel.
//
// Importance sampling: a texel with probability proportional to its luminance times its solid
// angle (2 pi / W)(cos theta_j - cos theta_{j+1}) (PiecewiseConstant2D), then a direction uniform
// in solid angle inside it, so pdf(d) = P(texel) / (texel solid angle), exactly proportional to
// the luminance seen in d (a constant map: 1 / (4 pi) everywhere). Zero-luminance texels are never
// sampled (pdf 0) yet may carry colour (a luminance-0 colour is black here: Rec. 709 weights are
// all positive, so only black has luminance 0).
//
// Value type: the image and its distribution are shared (immutable), so copying a Scene is
// cheap; scale, rotation and visibility are per copy.
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "core/piecewise_constant.h"

namespace tyndall {

class LoadBudget;

/// A direction toward the environment chosen for next-event estimation or photon emission.
struct EnvironmentSample {
    Vec3 wi;          ///< unit world direction toward the environment (from the scene)
    Rgb radiance;     ///< eval(wi), scale included
    float pdf = 0;    ///< solid-angle pdf of wi; 0 = no sample (an all-black environment)
};

class EnvironmentLight {
public:
    /// Uniform radiance from every direction.
    static EnvironmentLight constant(const Rgb& radiance);
    /// A lat-long image (any size >= 1 x 1; 2:1 is the usual aspect, other aspects are stretched).
    /// `name` (a file name, or a description) is kept for messages and metadata. Throws Error
    /// naming it and the texel when a texel is NaN or infinite; negative values are clamped to 0.
    static EnvironmentLight fromImage(const Image& image, const std::string& name);
    /// Reads a lat-long image through OpenImageIO (EXR, Radiance .hdr, or any format it reads;
    /// 8-bit formats are sRGB-decoded). Throws Error naming the file when it cannot be read. With
    /// a budget, the size the image's header declares is weighed first, no pixel read: while
    /// loading, C x 4 + 40 bytes a texel (the decoded file, the image, the texels, the sampling
    /// weights and distribution) are checked; 20 a texel (texels, distribution) stay reserved.
    static EnvironmentLight fromFile(const std::string& path, LoadBudget* budget = nullptr);

    /// Radiance arriving from world direction `d` (unit, pointing away from the scene), scale included.
    Rgb eval(const Vec3& d) const;
    /// A direction with pdf proportional to the luminance of eval (u1, u2 in [0, 1)).
    EnvironmentSample sample(float u1, float u2) const;
    /// Solid-angle pdf with which sample() returns world direction `d`.
    float pdf(const Vec3& d) const;
    /// Integral of eval over the sphere, W m^-2 (per unit projected area): photons leaving a disc
    /// of radius R carry pi R^2 x this in all.
    Rgb integral() const { return m_data->integral * m_scale; }

    float scale() const { return m_scale; }
    void setScale(float scale) { m_scale = scale; }
    /// Rotation about +Y in degrees.
    float rotation() const { return m_rotateDegrees; }
    void setRotation(float degrees);
    /// False: camera rays that leave the scene without any scattering see black; the light, its
    /// reflections and refractions are unchanged.
    bool visible() const { return m_visible; }
    void setVisible(bool visible) { m_visible = visible; }

    const std::string& name() const { return m_data->name; }
    int width() const { return m_data->width; }
    int height() const { return m_data->height; }
    bool isConstant() const { return m_data->width == 1 && m_data->height == 1; }

    /// The direction (in the environment's own frame, rotation not applied) of image coordinates
    /// (u, v) in [0, 1]^2, and back. For tests and documentation.
    static Vec3 directionOf(float u, float v);
    static Vec2 uvOf(const Vec3& local);

private:
    struct Data {
        std::string name;
        int width = 0, height = 0;
        std::vector<Rgb> texels;          // row-major from the top row
        std::vector<float> rowSolidAngle;  // per row: solid angle of one texel of it
        std::vector<float> cosTheta;       // height + 1 row edges, cos(pi j / H)
        PiecewiseConstant2D distribution;  // luminance x texel solid angle
        Rgb integral;                      // sum texel x solid angle
    };
    explicit EnvironmentLight(std::shared_ptr<const Data> data) : m_data(std::move(data)) {}
    Vec3 toLocal(const Vec3& d) const;
    Vec3 toWorld(const Vec3& d) const;
    /// Texel index (column, row) holding local direction `d`.
    void texelOf(const Vec3& local, int* x, int* y) const;

    std::shared_ptr<const Data> m_data;
    float m_scale = 1.0f;
    float m_rotateDegrees = 0.0f;
    float m_cos = 1.0f, m_sin = 0.0f;  // of the rotation
    bool m_visible = true;
};

}  // namespace tyndall
