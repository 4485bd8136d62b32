#pragma once
// Affine transforms for scene loading (glTF node hierarchies, scene-file shape transforms).
// Double precision so that deep hierarchies and large coordinates compose without drift; the
// results are rounded to float when applied. Header-only.
#include <cmath>

#include "core/math.h"

namespace tyndall {

/// x' = A x + t, stored as 3 rows of [A | t].
struct Affine {
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    static Affine translation(double x, double y, double z) {
        Affine a;
        a.m[0][3] = x, a.m[1][3] = y, a.m[2][3] = z;
        return a;
    }
    static Affine scaling(double x, double y, double z) {
        Affine a;
        a.m[0][0] = x, a.m[1][1] = y, a.m[2][2] = z;
        return a;
    }
    /// Rotation by unit quaternion (x, y, z, w) (glTF order); normalised here.
    static Affine rotation(double x, double y, double z, double w) {
        double n = std::sqrt(x * x + y * y + z * z + w * w);
        if (n > 0) x /= n, y /= n, z /= n, w /= n;
        Affine a;
        a.m[0][0] = 1 - 2 * (y * y + z * z), a.m[0][1] = 2 * (x * y - z * w), a.m[0][2] = 2 * (x * z + y * w);
        a.m[1][0] = 2 * (x * y + z * w), a.m[1][1] = 1 - 2 * (x * x + z * z), a.m[1][2] = 2 * (y * z - x * w);
        a.m[2][0] = 2 * (x * z - y * w), a.m[2][1] = 2 * (y * z + x * w), a.m[2][2] = 1 - 2 * (x * x + y * y);
        return a;
    }
    /// Rotation by `degrees` about `axis` (right-handed).
    static Affine rotationAxisAngle(const Vec3& axis, double degrees) {
        double rad = degrees * 3.14159265358979323846 / 180.0;
        double len = std::sqrt(double(axis.x) * axis.x + double(axis.y) * axis.y + double(axis.z) * axis.z);
        double s = std::sin(0.5 * rad) / (len > 0 ? len : 1);
        return rotation(axis.x * s, axis.y * s, axis.z * s, std::cos(0.5 * rad));
    }
    /// From 16 numbers in column-major order (glTF `matrix`); the bottom row is ignored.
    static Affine fromColumnMajor(const double* c) {
        Affine a;
        for (int r = 0; r < 3; ++r)
            for (int col = 0; col < 4; ++col) a.m[r][col] = c[col * 4 + r];
        return a;
    }

    /// this * o (apply o first).
    Affine operator*(const Affine& o) const {
        Affine r;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 4; ++j) {
                double v = (j == 3) ? m[i][3] : 0.0;
                for (int k = 0; k < 3; ++k) v += m[i][k] * o.m[k][j];
                r.m[i][j] = v;
            }
        }
        return r;
    }

    double determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    bool isFinite() const {
        for (const auto& row : m)
            for (double v : row)
                if (!std::isfinite(v)) return false;
        return true;
    }

    Vec3 point(const Vec3& p) const {
        return {float(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3]),
                float(m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3]),
                float(m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3])};
    }
    Vec3 vector(const Vec3& v) const {
        return {float(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
                float(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
                float(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z)};
    }
    /// A surface normal: transformed by the inverse transpose (cofactor matrix, same direction),
    /// not normalised. Zero for a singular transform.
    Vec3 normal(const Vec3& n) const {
        double c[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
                c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
            }
        double sign = determinant() < 0 ? -1.0 : 1.0;  // cofactor = det * inverse^T; keep orientation
        return {float(sign * (c[0][0] * n.x + c[0][1] * n.y + c[0][2] * n.z)),
                float(sign * (c[1][0] * n.x + c[1][1] * n.y + c[1][2] * n.z)),
                float(sign * (c[2][0] * n.x + c[2][1] * n.y + c[2][2] * n.z))};
    }
};

}  // namespace tyndall
