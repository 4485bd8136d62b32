// The surface kernel's coverage (cpu/surface_boundary.h) on meshes as real assets have them and at
// every radius: a square floor cut into many triangles, against the kernel's mass on the square by
// quadrature written here, at radii from a fraction of a cell to several times the floor (where the
// coverage is clamped at kMinCoverage, and where the pre-check's grid cells and cached candidate
// lists are smaller than the radius); and the same floor with every other triangle wound the other
// way (common in exported assets: the diffuse gather ignores the winding, so the coverage must too).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cpu/embree_scene.h"
#include "cpu/surface_boundary.h"

namespace tyndall {
namespace {

constexpr int kCells = 6;  // the floor [0, 1]^2 (x, z) at y = 0 in kCells^2 quads, two triangles each

/// The floor facing +y; `alternate` winds every other triangle the other way (facing -y).
Scene floorScene(bool alternate) {
    Scene s;
    s.name = alternate ? "floor-mixed-winding" : "floor";
    s.source = "<test>";
    Material white;
    white.name = "white";
    s.materials = {white};
    TriangleMesh m;
    m.name = "floor";
    for (int i = 0; i <= kCells; ++i)
        for (int j = 0; j <= kCells; ++j) m.positions.push_back({float(j) / kCells, 0.0f, float(i) / kCells});
    auto v = [](int i, int j) { return uint32_t(i * (kCells + 1) + j); };
    int t = 0;
    for (int i = 0; i < kCells; ++i)
        for (int j = 0; j < kCells; ++j) {
            // (v00, v11, v10) and (v00, v01, v11) face +y.
            uint32_t tris[2][3] = {{v(i, j), v(i + 1, j + 1), v(i, j + 1)}, {v(i, j), v(i + 1, j), v(i + 1, j + 1)}};
            for (auto& tri : tris) {
                if (alternate && (t++ % 2 == 1)) std::swap(tri[1], tri[2]);
                m.indices.insert(m.indices.end(), {tri[0], tri[1], tri[2]});
            }
        }
    s.meshes.push_back(m);
    s.camera = Camera::lookAt({0.5f, 2, 0.5f}, {0.5f, 0, 0.5f}, {0, 0, 1}, 1.0f);
    s.finalize();
    return s;
}

/// The normalised Epanechnikov kernel of radius r at (x, z) integrated over the unit square, by
/// quadrature in polar coordinates (the square is convex: each direction leaves it once).
double squareMass(double x, double z, double r) {
    const int n = 20000;
    double sum = 0;
    for (int k = 0; k < n; ++k) {
        const double phi = 2 * kPi * (k + 0.5) / n, c = std::cos(phi), s = std::sin(phi);
        double d = 1e30;
        if (c > 0) d = std::min(d, (1 - x) / c);
        if (c < 0) d = std::min(d, -x / c);
        if (s > 0) d = std::min(d, (1 - z) / s);
        if (s < 0) d = std::min(d, -z / s);
        const double rho = std::min(d, r);
        // int_0^rho 2/(pi r^2) (1 - p^2/r^2) p dp
        sum += 2 / (kPi * r * r) * (rho * rho / 2 - rho * rho * rho * rho / (4 * r * r));
    }
    return sum * 2 * kPi / n;
}

const Vec2 kProbes[] = {{0.5f, 0.5f}, {0.03f, 0.52f}, {0.11f, 0.07f}, {0.93f, 0.61f}, {0.4f, 0.98f}, {0.999f, 0.002f}};
const float kRadii[] = {0.02f, 0.1f, 0.3f, 0.7f, 1.3f, 4.0f};

/// coverage() (and the per-gather cache) at every probe and radius against the quadrature.
void expectCoverageIsTheMassOnTheSquare(const Scene& s) {
    EmbreeScene rt(s);
    SurfaceBoundary b(s, rt);
    EXPECT_EQ(b.featureEdgeCount(), size_t(4 * kCells)) << "only the square's outline is an edge";
    for (Vec2 p : kProbes)
        for (float r : kRadii) {
            // The point's own triangle, as a gather there sees it (its winding gives ng).
            SurfaceHit hit;
            ASSERT_TRUE(rt.intersect(Ray{{p.x, 1.0f, p.y}, {0, -1, 0}}, &hit));
            const double expected = std::clamp(squareMass(p.x, p.y, r), double(SurfaceBoundary::kMinCoverage), 1.0);
            EXPECT_NEAR(b.coverage(hit.p, hit.ng, r), expected, 2e-3)
                << "at (" << p.x << ", " << p.y << ") r " << r << " ng.y " << hit.ng.y;
            // The per-gather cache quantises the radius to 1/32 octave (up to 1/64 of r).
            SurfaceBoundary::AtPoint at(b, hit.p, hit.ng);
            EXPECT_NEAR(at(r), expected, 2e-3 + 0.03 * (1 - expected)) << "at (" << p.x << ", " << p.y << ") r " << r;
        }
}

TEST(SurfaceBoundaryMesh, AtAnyRadiusTheCoverageIsTheKernelMassOnTheSquare) {
    expectCoverageIsTheMassOnTheSquare(floorScene(false));
}

TEST(SurfaceBoundaryMesh, RadiiBelowThePreCheckCellAtEveryPointOfACell) {
    // Radii just under a power of two (the per-cell candidate lists are keyed by the half octave
    // above r) and near the pre-check's cell size, at points stepping across several cells toward
    // an edge: every half-edge within r of the point must be among its cell's candidates.
    Scene s = floorScene(false);
    EmbreeScene rt(s);
    SurfaceBoundary b(s, rt);
    const float cell = b.clearanceGrid().cellSize();
    ASSERT_GT(cell, 0.0f);
    int probes = 0;
    for (float r : {0.99f * 0.0078125f, 0.99f * 0.015625f, 0.99f * 0.03125f})
        for (float x = 0.3f * r; x < 1.2f * r + 2 * cell; x += 0.07f * cell) {
            const double expected = std::clamp(squareMass(x, 0.5, r), double(SurfaceBoundary::kMinCoverage), 1.0);
            const float c = b.coverage(Vec3(x, 0.0f, 0.5f), Vec3(0, 1, 0), r);
            EXPECT_NEAR(c, expected, 2e-4) << "x " << x << " r " << r << " (cell " << cell << ")";
            ++probes;
        }
    EXPECT_GT(probes, 60);
}

TEST(SurfaceBoundaryMesh, MixedWindingMakesNoFalseEdgesInside) {
    Scene s = floorScene(true);
    EmbreeScene rt(s);
    SurfaceBoundary b(s, rt);
    EXPECT_EQ(b.featureEdgeCount(), size_t(4 * kCells)) << "the seams between opposite windings are no edges";
    // Discs that stay inside the square cover every seam between the two windings: coverage 1.
    for (Vec2 p : {Vec2{0.5f, 0.5f}, Vec2{0.31f, 0.62f}, Vec2{0.72f, 0.27f}})
        for (float r : {0.05f, 0.15f, 0.25f}) {
            SurfaceHit hit;
            ASSERT_TRUE(rt.intersect(Ray{{p.x, 1.0f, p.y}, {0, -1, 0}}, &hit));
            EXPECT_FLOAT_EQ(b.coverage(hit.p, hit.ng, r), 1.0f) << "at (" << p.x << ", " << p.y << ") r " << r;
        }
}

// At the outline, a half-edge of an oppositely wound triangle carries the opposite normal: the
// loss past it must be corrected whichever winding the gather point's triangle has (measured before
// the sheets: coverage 1.0 where the kernel's mass on the square is 0.74 at r = 0.1 from an edge).
TEST(SurfaceBoundaryMesh, MixedWindingOutlineMatchesTheKernelMassOnTheSquare) {
    expectCoverageIsTheMassOnTheSquare(floorScene(true));
}

}  // namespace
}  // namespace tyndall
