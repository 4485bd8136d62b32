#pragma once
// Helpers for the GL tests: image comparison with evidence on failure, a trilinear lattice
// density grid with a dense form (the analytic grid the splatter parity tests use), and scenes.
#include <algorithm>
#include <cmath>
#include <string>

#include "core/density_grid.h"
#include "core/image.h"
#include "core/image_io.h"
#include "core/scene.h"
#include "tests/test_util.h"

namespace tyndall::test {

/// Largest relative RMS (relativeRms) allowed between a GL splat and the CPU's, for the same
/// beams, camera and jitter: both evaluate the same estimator in fp32 and differ only by rounding
/// and summation order (measured 0 to 9e-8 on llvmpipe). The CPU side of every parity test is
/// the scalar CPU estimator (PassRenderer::splatPrimary's beam rasterizer, the definition), not
/// a SIMD variant, so that a vectorised CPU path cannot drift together with the GL one unseen;
/// SIMD-vs-scalar agreement is the CPU rasterizer tests' business.
constexpr double kGlCpuParity = 1e-5;

/// sqrt(sum |a - ref|^2 / sum |ref|^2) over all pixels and channels (double sums).
inline double relativeRms(const Image& a, const Image& ref) {
    double num = 0, den = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double d = double(a.pixels[i][c]) - double(ref.pixels[i][c]);
            num += d * d;
            den += double(ref.pixels[i][c]) * double(ref.pixels[i][c]);
        }
    return den > 0 ? std::sqrt(num / den) : std::sqrt(num);
}

/// Pixels where `ref` is clearly non-zero but `a` is zero (a coverage hole), and vice versa.
inline int coverageMismatches(const Image& a, const Image& ref, float threshold) {
    int n = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) {
        bool refLit = ref.pixels[i].maxComponent() > threshold, aLit = a.pixels[i].maxComponent() > threshold;
        bool refDark = ref.pixels[i].isBlack(), aDark = a.pixels[i].isBlack();
        n += (refLit && aDark) || (aLit && refDark);
    }
    return n;
}

/// Pixels where `a` and `ref` differ by more than `relTol` of the pixel's own brightest channel
/// (floored at 1e-3 of the image's mean, so black pixels compare absolutely): float rounding
/// stays near 1e-7, a pixel that lost its splat (an uncovered row or column) differs by its whole
/// media radiance. relativeRms averages such a pixel away over a large image; this does not.
inline int mismatchedPixels(const Image& a, const Image& ref, double relTol) {
    double mean = 0;
    for (const Rgb& p : ref.pixels) mean += p.maxComponent();
    mean /= double(ref.pixels.size() ? ref.pixels.size() : 1);
    int n = 0;
    for (size_t i = 0; i < ref.pixels.size(); ++i) {
        double scale = std::max(double(ref.pixels[i].maxComponent()), 1e-3 * mean);
        for (int c = 0; c < 3; ++c)
            if (std::abs(double(a.pixels[i][c]) - double(ref.pixels[i][c])) > relTol * scale) {
                ++n;
                break;
            }
    }
    return n;
}

/// Writes `name`_gl.exr, `name`_cpu.exr and the absolute difference into the test output folder.
inline void writeEvidence(const std::string& name, const Image& gl, const Image& cpu) {
    Image diff(cpu.width, cpu.height);
    for (size_t i = 0; i < cpu.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) diff.pixels[i][c] = std::abs(gl.pixels[i][c] - cpu.pixels[i][c]);
    writeImage(outputDir() + "/" + name + "_gl.exr", gl);
    writeImage(outputDir() + "/" + name + "_cpu.exr", cpu);
    writeImage(outputDir() + "/" + name + "_diff.exr", diff);
}

/// A density grid given by lattice values f(i, j, k) (smooth, in [0.1, 0.9]) under a rotated,
/// scaled, translated index transform; density() is DensityVolume::sample, and denseVolume()
/// hands the lattice to the GL splatter.
class LatticeTestGrid : public DensityGrid {
public:
    LatticeTestGrid(const Bounds3& box, int n) {
        m_volume.nx = m_volume.ny = m_volume.nz = n;
        // index = S R (p - lo) with R a rotation about z by 0.3 rad, S = (n-1)/extent: the lattice
        // is not axis-aligned with the world.
        Vec3 extent = box.diagonal();
        float c = std::cos(0.3f), s = std::sin(0.3f);
        float R[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
        for (int r = 0; r < 3; ++r) {
            float scale = float(n - 1) / extent[r];
            float t = 0;
            for (int k = 0; k < 3; ++k) {
                m_volume.worldToIndex[r][k] = scale * R[r][k];
                t -= scale * R[r][k] * box.lo[k];
            }
            m_volume.worldToIndex[r][3] = t + 0.5f * float(n - 1) * (r < 2 ? 0.15f : 0.0f);
        }
        m_volume.voxels.resize(m_volume.voxelCount());
        for (int k = 0; k < n; ++k)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    m_volume.voxels[(size_t(k) * n + j) * n + i] =
                        0.5f + 0.4f * std::sin(0.9f * i + 0.3f) * std::cos(0.7f * j - 0.2f * k);
        m_bounds = box;
        // The rotated lattice reaches a bit beyond `box`; bounds() must contain it: pad.
        Vec3 pad = extent * 0.5f;
        m_bounds.lo = m_bounds.lo - pad;
        m_bounds.hi = m_bounds.hi + pad;
    }
    float density(const Vec3& p) const override { return m_volume.sample(p); }
    Bounds3 bounds() const override { return m_bounds; }
    float maxDensity() const override { return 0.9f; }
    float meanDensity() const override { return 0.5f; }
    bool denseVolume(DensityVolume* out, size_t maxVoxels) const override {
        if (m_volume.voxelCount() > maxVoxels) return false;
        *out = m_volume;
        return true;
    }
    const DensityVolume& volume() const { return m_volume; }

private:
    DensityVolume m_volume;
    Bounds3 m_bounds;
};

/// The same field without a dense form: the GL splatter must refuse it.
class OpaqueTestGrid : public LatticeTestGrid {
public:
    using LatticeTestGrid::LatticeTestGrid;
    bool denseVolume(DensityVolume*, size_t) const override { return false; }
};

}  // namespace tyndall::test
