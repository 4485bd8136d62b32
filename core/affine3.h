#pragma once
// A 3D affine map p -> A p + b stored as a row-major 3x4 matrix [A | b]. Used for density-grid
// transforms (index space <-> world space, anisotropic voxels, rotations). Affine maps keep the
// ray parameter: if p(t) = o + t d then M p(t) = M o + t A d, so t values carry over between spaces.
#include <array>

#include "core/math.h"

namespace tyndall {

struct Affine3 {
    /// Rows of [A | b]; the identity by default.
    float m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    /// From a row-major 4x4 matrix acting on column vectors (the last row must be 0 0 0 1).
    static Affine3 fromRowMajor4x4(const std::array<double, 16>& r) {
        Affine3 a;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) a.m[i][j] = float(r[4 * i + j]);
        return a;
    }
    static Affine3 scaleTranslate(const Vec3& s, const Vec3& t) {
        Affine3 a;
        for (int i = 0; i < 3; ++i) {
            a.m[i][i] = s[i];
            a.m[i][3] = t[i];
        }
        return a;
    }

    Vec3 point(const Vec3& p) const {
        return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
                m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
                m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
    }
    Vec3 vector(const Vec3& v) const {
        return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
    }
    float determinant() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    /// The inverse map; the caller checks determinant() != 0 first (a singular map has no inverse).
    Affine3 inverse() const {
        // Cofactors in double: voxel sizes of 1e-3 give determinants of 1e-9.
        double a[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) a[i][j] = m[i][j];
        double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1], c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2],
               c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
        double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
        double inv[3][3] = {{c00, a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][1] * a[1][2] - a[0][2] * a[1][1]},
                            {c01, a[0][0] * a[2][2] - a[0][2] * a[2][0], a[0][2] * a[1][0] - a[0][0] * a[1][2]},
                            {c02, a[0][1] * a[2][0] - a[0][0] * a[2][1], a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
        Affine3 r;
        for (int i = 0; i < 3; ++i) {
            double t = 0;
            for (int j = 0; j < 3; ++j) {
                r.m[i][j] = float(inv[i][j] / det);
                t += inv[i][j] / det * m[j][3];
            }
            r.m[i][3] = float(-t);
        }
        return r;
    }
};

/// a after b: (a * b)(p) = a(b(p)).
inline Affine3 operator*(const Affine3& a, const Affine3& b) {
    Affine3 r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            double s = j == 3 ? a.m[i][3] : 0.0;
            for (int k = 0; k < 3; ++k) s += double(a.m[i][k]) * b.m[k][j];
            r.m[i][j] = float(s);
        }
    }
    return r;
}

/// World-space bounding box of the image of box `b` under `a` (its 8 corners).
inline Bounds3 transformBounds(const Affine3& a, const Bounds3& b) {
    Bounds3 r;
    if (b.empty()) return r;
    for (int c = 0; c < 8; ++c)
        r.extend(a.point({(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z}));
    return r;
}

}  // namespace tyndall
