#pragma once
// Small value types shared by every stage: Vec3 (positions, directions, in scene units),
// Rgb (linear radiometric triples), Frame (orthonormal basis) and Ray. Header-only, no
// dependencies, usable from the GLSL-twin code in beam_estimator.h.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tyndall {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 1.0f / kPi;
constexpr float kInv4Pi = 1.0f / (4.0f * kPi);
constexpr float kInfinity = std::numeric_limits<float>::infinity();

struct Vec3 {
    float x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
    Vec3& operator-=(const Vec3& o) { x -= o.x; y -= o.y; z -= o.z; return *this; }
    Vec3& operator*=(float s) { x *= s; y *= s; z *= s; return *this; }
};
constexpr Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator*(const Vec3& a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(float s, const Vec3& a) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator/(const Vec3& a, float s) { return {a.x / s, a.y / s, a.z / s}; }
constexpr Vec3 mul(const Vec3& a, const Vec3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
constexpr float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(const Vec3& a) { return std::sqrt(dot(a, a)); }
constexpr float lengthSquared(const Vec3& a) { return dot(a, a); }
inline Vec3 normalize(const Vec3& a) { return a / length(a); }
inline Vec3 vmin(const Vec3& a, const Vec3& b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 vmax(const Vec3& a, const Vec3& b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
inline bool isFinite(const Vec3& a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

/// Linear RGB radiometric triple (radiance, power, coefficients per unit length, albedo).
struct Rgb {
    float r = 0, g = 0, b = 0;
    constexpr Rgb() = default;
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(float s) : r(s), g(s), b(s) {}
    constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    float& operator[](int i) { return i == 0 ? r : (i == 1 ? g : b); }
    Rgb& operator+=(const Rgb& o) { r += o.r; g += o.g; b += o.b; return *this; }
    Rgb& operator*=(const Rgb& o) { r *= o.r; g *= o.g; b *= o.b; return *this; }
    Rgb& operator*=(float s) { r *= s; g *= s; b *= s; return *this; }
    constexpr bool isBlack() const { return r == 0 && g == 0 && b == 0; }
    constexpr float maxComponent() const { return std::max(r, std::max(g, b)); }
    constexpr float average() const { return (r + g + b) / 3.0f; }
    constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
};
constexpr Rgb operator+(const Rgb& a, const Rgb& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr Rgb operator-(const Rgb& a, const Rgb& b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr Rgb operator*(const Rgb& a, const Rgb& b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr Rgb operator*(const Rgb& a, float s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Rgb operator*(float s, const Rgb& a) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Rgb operator/(const Rgb& a, float s) { return {a.r / s, a.g / s, a.b / s}; }
inline Rgb exp(const Rgb& a) { return {std::exp(a.r), std::exp(a.g), std::exp(a.b)}; }
inline bool isFinite(const Rgb& a) { return std::isfinite(a.r) && std::isfinite(a.g) && std::isfinite(a.b); }

/// Orthonormal basis with `n` as the local z axis (Duff et al. 2017, branchless).
struct Frame {
    Vec3 s, t, n;
    Frame() = default;
    explicit Frame(const Vec3& normal) : n(normal) {
        float sign = std::copysign(1.0f, n.z);
        float a = -1.0f / (sign + n.z);
        float b = n.x * n.y * a;
        s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
        t = {b, sign + n.y * n.y * a, -n.y};
    }
    Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
    Vec3 toLocal(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
};

/// A ray segment o + t d, t in [tMin, tMax]; `d` is unit length unless a stage says otherwise.
struct Ray {
    Vec3 o;
    Vec3 d;
    float tMin = 0.0f;
    float tMax = kInfinity;
    Vec3 at(float t) const { return o + d * t; }
};

struct Bounds3 {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};
    void extend(const Vec3& p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void extend(const Bounds3& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    Vec3 center() const { return (lo + hi) * 0.5f; }
    Vec3 diagonal() const { return hi - lo; }
    bool contains(const Vec3& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    }
};

template <typename T>
constexpr T clampValue(T v, T lo, T hi) { return v < lo ? lo : (v > hi ? hi : v); }
inline float safeSqrt(float v) { return std::sqrt(std::max(v, 0.0f)); }

}  // namespace tyndall
