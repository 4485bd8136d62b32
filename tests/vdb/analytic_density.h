#pragma once
// Analytic density fields for the heterogeneous-media tests, each with its exact optical depth
// along a ray and an exact (dilated) majorant grid, plus their voxelised OpenVDB twins.
//
// All live in the unit box [0,1]^3 and vary along x only:
//   constant: d(x) = v
//   ramp:     d(x) = a + b x
//   slab:     d(x) = v for x in [s0, s1], else 0
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/density_grid.h"
#include "core/majorant_grid.h"
#include "loading/vdb_grid.h"

namespace tyndall::test {

class AnalyticDensity : public DensityGrid {
public:
    enum class Kind { Constant, Ramp, Slab };
    /// `majorantCells` > 0 builds a majorant grid with that many cells along x (1 along y, z);
    /// 0 leaves majorantGrid() null, so tracking uses the global maximum.
    AnalyticDensity(Kind kind, int majorantCells) : m_kind(kind) {
        if (majorantCells > 0) {
            // Cells along x over [-0.5, 1.5] so the grid extends past the box on both sides.
            Affine3 worldToCell = Affine3::scaleTranslate(Vec3(float(majorantCells) / 2.0f, 1.0f, 1.0f),
                                                          Vec3(0.5f * float(majorantCells) / 2.0f, 0.0f, 0.0f));
            m_majorants = std::make_unique<MajorantGrid>(worldToCell, majorantCells, 1, 1);
            for (int i = 0; i < majorantCells; ++i) {
                // Exact max over the cell's x range widened by 1e-4 (float rounding at faces).
                float x0 = -0.5f + 2.0f * float(i) / float(majorantCells) - 1e-4f;
                float x1 = -0.5f + 2.0f * float(i + 1) / float(majorantCells) + 1e-4f;
                m_majorants->at(i, 0, 0) = maxOver(x0, x1);
            }
            m_majorants->finish();
        }
    }

    static constexpr float kConstant = 1.0f, kRampA = 0.2f, kRampB = 1.6f, kSlab = 2.0f, kSlab0 = 0.3f, kSlab1 = 0.6f;

    Kind kind() const { return m_kind; }
    float profile(float x) const {
        if (x < 0 || x > 1) return 0.0f;
        switch (m_kind) {
            case Kind::Constant:
                return kConstant;
            case Kind::Ramp:
                return kRampA + kRampB * x;
            case Kind::Slab:
                return x >= kSlab0 && x <= kSlab1 ? kSlab : 0.0f;
        }
        return 0.0f;
    }
    /// Exact integral of the profile over [x0, x1].
    double integral(double x0, double x1) const {
        if (x1 < x0) std::swap(x0, x1);
        auto clip = [&](double lo, double hi, double* a, double* b) {
            *a = std::max(x0, lo);
            *b = std::min(x1, hi);
            return *b > *a;
        };
        double a, b;
        switch (m_kind) {
            case Kind::Constant:
                return clip(0, 1, &a, &b) ? kConstant * (b - a) : 0.0;
            case Kind::Ramp:
                return clip(0, 1, &a, &b) ? kRampA * (b - a) + 0.5 * kRampB * (b * b - a * a) : 0.0;
            case Kind::Slab:
                return clip(kSlab0, kSlab1, &a, &b) ? kSlab * (b - a) : 0.0;
        }
        return 0.0;
    }
    float maxOver(float x0, float x1) const {
        x0 = std::max(x0, 0.0f);
        x1 = std::min(x1, 1.0f);
        if (x1 < x0) return 0.0f;
        switch (m_kind) {
            case Kind::Constant:
                return kConstant;
            case Kind::Ramp:
                return kRampA + kRampB * x1;
            case Kind::Slab:
                return x1 >= kSlab0 && x0 <= kSlab1 ? kSlab : 0.0f;
        }
        return 0.0f;
    }

    float density(const Vec3& p) const override {
        if (p.y < 0 || p.y > 1 || p.z < 0 || p.z > 1) return 0.0f;
        return profile(p.x);
    }
    Bounds3 bounds() const override { return {Vec3(0.0f), Vec3(1.0f)}; }
    const MajorantGrid* majorantGrid() const override { return m_majorants.get(); }
    float maxDensity() const override { return maxOver(0.0f, 1.0f); }
    float meanDensity() const override { return float(integral(0, 1)); }

private:
    Kind m_kind;
    std::unique_ptr<MajorantGrid> m_majorants;
};

inline const char* kindName(AnalyticDensity::Kind k) {
    switch (k) {
        case AnalyticDensity::Kind::Constant:
            return "constant";
        case AnalyticDensity::Kind::Ramp:
            return "ramp";
        case AnalyticDensity::Kind::Slab:
            return "slab";
    }
    return "?";
}

/// The analytic field voxelised into an in-memory OpenVDB grid: `n` voxels per unit along x,
/// voxel centres at ((i + 0.5) / n, ...). Inside [0.5/n, 1 - 0.5/n] the trilinear constant and
/// ramp are exact; the slab's edges become one-voxel linear ramps, and every field falls to zero
/// over one voxel outside the box. Tests integrate this grid's own density() for its reference.
inline std::shared_ptr<const VdbDensityGrid> voxelise(const AnalyticDensity& field, int n) {
    int dims[3] = {n, n, n};
    std::vector<float> v(size_t(n) * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) v[(size_t(k) * n + j) * n + i] = field.profile((float(i) + 0.5f) / float(n));
    Affine3 indexToWorld = Affine3::scaleTranslate(Vec3(1.0f / float(n)), Vec3(0.5f / float(n)));
    return VdbDensityGrid::fromDense(dims, v, indexToWorld, "voxelised " + std::string(kindName(field.kind())));
}

/// Optical depth of `grid` (density units x length) along ray.o + s ray.d, s in [s0, s1], by
/// composite Simpson with `steps` (even) intervals. The voxelised fields are piecewise linear
/// along a ray with kinks at voxel faces; Simpson's error there is O(h^2) per kink, negligible
/// for the tables built here (h ~ 3e-5, i.e. relative errors ~1e-7).
inline double numericOpticalDepth(const DensityGrid& grid, const Ray& ray, double s0, double s1, int steps) {
    if (s1 <= s0) return 0.0;
    double h = (s1 - s0) / steps, sum = 0;
    for (int i = 0; i <= steps; ++i) {
        double w = (i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * grid.density(ray.at(float(s0 + i * h)));
    }
    return sum * h / 3.0;
}

}  // namespace tyndall::test
