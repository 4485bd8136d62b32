#include "core/environment_light.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/image_io.h"
#include "core/load_budget.h"

namespace tyndall {

Vec3 EnvironmentLight::directionOf(float u, float v) {
    const float phi = 2.0f * kPi * u, theta = kPi * v;
    const float sinTheta = std::sin(theta);
    return {std::sin(phi) * sinTheta, std::cos(theta), -std::cos(phi) * sinTheta};
}

Vec2 EnvironmentLight::uvOf(const Vec3& local) {
    float u = std::atan2(local.x, -local.z) * (0.5f * kInvPi);
    if (u < 0) u += 1.0f;
    if (u >= 1.0f) u = 0.0f;
    return {u, std::acos(clampValue(local.y, -1.0f, 1.0f)) * kInvPi};
}

EnvironmentLight EnvironmentLight::constant(const Rgb& radiance) {
    Image image(1, 1);
    image.pixels[0] = radiance;
    return fromImage(image, "constant");
}

EnvironmentLight EnvironmentLight::fromFile(const std::string& path, LoadBudget* budget) {
    if (budget) {
        const ImageHeader h = readImageHeader(path);
        const uint64_t texels = uint64_t(std::max(h.width, 0)) * uint64_t(std::max(h.height, 0));
        const std::string what = "environment image '" + path + "': a " + std::to_string(h.width) + " x " +
                                 std::to_string(h.height) + " image of " + std::to_string(h.channels) + " channels";
        budget->check(texels * (uint64_t(std::max(h.channels, 1)) * sizeof(float) + 40), what + " (while it loads)");
        budget->reserve(texels * 20, what);
    }
    return fromImage(readImage(path), path);
}

EnvironmentLight EnvironmentLight::fromImage(const Image& image, const std::string& name) {
    if (image.width <= 0 || image.height <= 0) throw Error("environment '" + name + "': the image is empty");
    auto data = std::make_shared<Data>();
    data->name = name;
    data->width = image.width;
    data->height = image.height;
    data->texels = image.pixels;
    const int w = image.width, h = image.height;
    data->cosTheta.resize(size_t(h) + 1);
    for (int j = 0; j <= h; ++j) data->cosTheta[size_t(j)] = float(std::cos(M_PI * double(j) / double(h)));
    data->cosTheta[0] = 1.0f;
    data->cosTheta[size_t(h)] = -1.0f;
    std::vector<double> weights(size_t(w) * size_t(h));
    double integral[3] = {0, 0, 0};
    data->rowSolidAngle.resize(size_t(h));
    for (int j = 0; j < h; ++j) {
        const double solidAngle =
            2.0 * M_PI / double(w) * (std::cos(M_PI * double(j) / h) - std::cos(M_PI * double(j + 1) / h));
        data->rowSolidAngle[size_t(j)] = float(solidAngle);
        for (int i = 0; i < w; ++i) {
            Rgb& t = data->texels[size_t(j) * size_t(w) + size_t(i)];
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(t[c]))
                    throw Error("environment '" + name + "': texel (" + std::to_string(i) + ", " + std::to_string(j) +
                                ") is not a finite number (NaN or infinite)");
                t[c] = std::max(t[c], 0.0f);  // negative radiance: clamped to 0
                integral[c] += double(t[c]) * solidAngle;
            }
            weights[size_t(j) * size_t(w) + size_t(i)] = double(t.luminance()) * solidAngle;
        }
    }
    data->integral = Rgb(float(integral[0]), float(integral[1]), float(integral[2]));
    data->distribution = PiecewiseConstant2D(weights, w, h);
    return EnvironmentLight(std::move(data));
}

void EnvironmentLight::setRotation(float degrees) {
    m_rotateDegrees = degrees;
    const double r = double(degrees) * M_PI / 180.0;
    m_cos = float(std::cos(r));
    m_sin = float(std::sin(r));
}

Vec3 EnvironmentLight::toWorld(const Vec3& d) const {
    return {m_cos * d.x + m_sin * d.z, d.y, -m_sin * d.x + m_cos * d.z};
}
Vec3 EnvironmentLight::toLocal(const Vec3& d) const {
    return {m_cos * d.x - m_sin * d.z, d.y, m_sin * d.x + m_cos * d.z};
}

void EnvironmentLight::texelOf(const Vec3& local, int* x, int* y) const {
    const Vec2 uv = uvOf(local);
    *x = std::min(int(uv.x * float(m_data->width)), m_data->width - 1);
    *y = std::min(int(uv.y * float(m_data->height)), m_data->height - 1);
}

Rgb EnvironmentLight::eval(const Vec3& d) const {
    if (isConstant()) return m_data->texels[0] * m_scale;
    int x, y;
    texelOf(toLocal(d), &x, &y);
    return m_data->texels[size_t(y) * size_t(m_data->width) + size_t(x)] * m_scale;
}

EnvironmentSample EnvironmentLight::sample(float u1, float u2) const {
    EnvironmentSample s;
    const Data& data = *m_data;
    if (!(data.distribution.total() > 0)) return s;
    const CellSample2D cell = data.distribution.sample(u1, u2);
    if (!(cell.probability > 0)) return s;
    const float phi = 2.0f * kPi * (float(cell.x) + cell.remainder.x) / float(data.width);
    const float c0 = data.cosTheta[size_t(cell.y)], c1 = data.cosTheta[size_t(cell.y) + 1];
    const float cosTheta = clampValue(c0 + cell.remainder.y * (c1 - c0), -1.0f, 1.0f);
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    s.wi = toWorld(Vec3(std::sin(phi) * sinTheta, cosTheta, -std::cos(phi) * sinTheta));
    s.pdf = cell.probability / data.rowSolidAngle[size_t(cell.y)];
    s.radiance = data.texels[size_t(cell.y) * size_t(data.width) + size_t(cell.x)] * m_scale;
    return s;
}

float EnvironmentLight::pdf(const Vec3& d) const {
    const Data& data = *m_data;
    if (!(data.distribution.total() > 0)) return 0.0f;
    int x, y;
    texelOf(toLocal(d), &x, &y);
    return data.distribution.probability(x, y) / data.rowSolidAngle[size_t(y)];
}

}  // namespace tyndall
