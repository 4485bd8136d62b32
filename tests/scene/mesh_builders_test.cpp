// Procedural shapes for scene files: closed where they bound volumes, outward, the right size,
// and the reflector actually focuses.
#include "loading/mesh_builders.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/fresnel.h"

namespace tyndall {
namespace {

/// Signed volume by the divergence theorem: positive when the normals point out.
double signedVolume(const TriangleMesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) v += dot(m.vertex(t, 0), m.geometricNormal(t)) / 6.0;
    return v;
}

/// Every shading normal on the side of its triangles' geometric normals.
bool normalsAgreeWithWinding(const TriangleMesh& m) {
    for (size_t t = 0; t < m.triangleCount(); ++t)
        for (int k = 0; k < 3 && !m.normals.empty(); ++k)
            if (dot(m.normals[m.indices[3 * t + k]], m.geometricNormal(t)) <= 0) return false;
    return true;
}

TEST(MeshBuilders, ClosedShapesAreOutwardWithTheRightVolume) {
    const double pi = 3.14159265358979;
    TriangleMesh bumpy = makeBumpySphere("b", {1, 2, 3}, 1.0f, 4, 0.1f, 6.0f, 8, 3, 0);
    TriangleMesh water = makeWaterVolume("w", {0, 1, 0}, 4.0f, 2.0f, 1.5f, 16, 8, {{0.1f, 1.0f, 1, 0.3f, 0.5f}}, 0);
    TriangleMesh lens = makeLens("l", {0, 0, 0}, {0, 0, 1}, 0.5f, 0.2f, 2.0f, 8, 32, 0);
    TriangleMesh sphere = makeSphere("s", {0, 0, 0}, 2.0f, 4, 0);
    for (const TriangleMesh* m : {&bumpy, &water, &lens, &sphere}) {
        EXPECT_TRUE(m->isClosed()) << m->name;
        EXPECT_TRUE(normalsAgreeWithWinding(*m)) << m->name;
    }
    EXPECT_NEAR(signedVolume(sphere), 4.0 / 3.0 * pi * 8.0, 0.02 * 4.0 / 3.0 * pi * 8.0);
    // Bumps of RMS 10% around a unit sphere: the volume stays within ~30% of the sphere's.
    EXPECT_NEAR(signedVolume(bumpy), 4.0 / 3.0 * pi, 0.3 * 4.0 / 3.0 * pi);
    // Sinusoidal waves over whole wavelengths average out: volume ~ 4 x 2 x 1.5.
    EXPECT_NEAR(signedVolume(water), 12.0, 0.2);
    // Biconvex lens: edge thickness 0.2 - 2 sag, volume between a disk and the lens hull.
    double sag = 2.0 - std::sqrt(4.0 - 0.25);
    double diskEdge = pi * 0.25 * (0.2 - 2 * sag), diskCentre = pi * 0.25 * 0.2;
    EXPECT_GT(signedVolume(lens), diskEdge);
    EXPECT_LT(signedVolume(lens), diskCentre);
}

TEST(MeshBuilders, BumpySphereIsDeterministicInItsSeed) {
    TriangleMesh a = makeBumpySphere("a", {0, 0, 0}, 1.0f, 2, 0.1f, 6.0f, 8, 3, 0);
    TriangleMesh b = makeBumpySphere("b", {0, 0, 0}, 1.0f, 2, 0.1f, 6.0f, 8, 3, 0);
    TriangleMesh c = makeBumpySphere("c", {0, 0, 0}, 1.0f, 2, 0.1f, 6.0f, 8, 4, 0);
    EXPECT_EQ(a.positions[17].x, b.positions[17].x);
    EXPECT_NE(a.positions[17].x, c.positions[17].x);
}

TEST(MeshBuilders, WaterSurfaceFollowsItsWaves) {
    SurfaceWave w{0.2f, 2.0f, 1.0f, 0.0f, 0.0f};
    TriangleMesh m = makeWaterVolume("w", {0, 0, 0}, 4.0f, 4.0f, 1.0f, 8, 8, {w}, 0);
    // Top grid vertex (i, j) sits at x = -2 + 0.5 i; height 0.2 sin(pi x).
    for (int i = 0; i <= 8; ++i) {
        const Vec3& p = m.positions[size_t(i)];
        EXPECT_NEAR(p.y, 0.2f * std::sin(kPi * p.x), 1e-5f);
    }
}

TEST(MeshBuilders, ParaboloidReflectsAxialRaysThroughTheFocus) {
    const Vec3 apex{1, 2, 3}, axis = normalize(Vec3(0.3f, 0.2f, 1.0f));
    const float f = 0.25f;
    TriangleMesh m = makeParaboloid("p", apex, axis, f, 0.05f, 0.6f, 12, 24, 0);
    EXPECT_FALSE(m.isClosed());
    EXPECT_TRUE(normalsAgreeWithWinding(m));
    const Vec3 focus = apex + axis * f;
    for (size_t i = 0; i < m.positions.size(); i += 7) {
        // A ray coming in along -axis reflects off the surface normal toward the focus.
        Vec3 wo = axis;  // towards where the light came from
        Vec3 d = reflect(wo, m.normals[i]);
        Vec3 toFocus = focus - m.positions[i];
        EXPECT_NEAR(length(cross(d, normalize(toFocus))), 0.0f, 1e-4f) << "vertex " << i;
        EXPECT_GT(dot(d, toFocus), 0.0f);
    }
}

/// Closest hit of o + t d (t > 1e-6) with the mesh; the interpolated shading normal in *n.
bool intersectMesh(const TriangleMesh& m, const Vec3& o, const Vec3& d, Vec3* p, Vec3* n) {
    float best = kInfinity;
    for (size_t t = 0; t < m.triangleCount(); ++t) {  // Moller-Trumbore
        Vec3 a = m.vertex(t, 0), e1 = m.vertex(t, 1) - a, e2 = m.vertex(t, 2) - a;
        Vec3 q = cross(d, e2);
        float det = dot(e1, q);
        if (std::abs(det) < 1e-12f) continue;
        Vec3 s = o - a;
        float u = dot(s, q) / det;
        Vec3 r = cross(s, e1);
        float v = dot(d, r) / det, dist = dot(e2, r) / det;
        if (u < 0 || v < 0 || u + v > 1 || dist <= 1e-6f || dist >= best) continue;
        best = dist;
        const uint32_t* i = &m.indices[3 * t];
        *n = normalize(m.normals[i[0]] * (1 - u - v) + m.normals[i[1]] * u + m.normals[i[2]] * v);
    }
    *p = o + d * best;
    return best < kInfinity;
}

TEST(MeshBuilders, LensFocusesWhereTheThickLensFormulaSays) {
    const float n = 1.5f, R = 2.0f, thickness = 0.1f;
    TriangleMesh lens = makeLens("l", {0, 0, 0}, {0, 0, 1}, 0.5f, thickness, R, 32, 96, 0);
    // Thick biconvex lens, R1 = R, R2 = -R: 1/f = (n-1) (2/R - (n-1) d / (n R^2)); the back focal
    // distance is f (1 - (n-1) d / (n R)) from the back vertex.
    float f = 1.0f / ((n - 1) * (2 / R - (n - 1) * thickness / (n * R * R)));
    float backFocus = 0.5f * thickness + f * (1 - (n - 1) * thickness / (n * R));
    for (float h : {0.02f, 0.05f}) {
        Vec3 o{h, 0, -1}, d{0, 0, 1}, p, nrm, t;
        ASSERT_TRUE(intersectMesh(lens, o, d, &p, &nrm));
        ASSERT_TRUE(refract(-d, nrm, n, &t));  // into the glass (the normal points out)
        ASSERT_TRUE(intersectMesh(lens, p, t, &p, &nrm));
        ASSERT_TRUE(refract(-t, nrm, n, &d));       // out again
        float crossing = p.z + (-p.x / d.x) * d.z;  // where the ray meets the axis
        EXPECT_NEAR(crossing, backFocus, 0.02f * f) << "ray height " << h;
    }
}

TEST(MeshBuilders, PerforatedSphereHasItsHoles) {
    TriangleMesh whole = makePerforatedSphere("w", {0, 0, 0}, 1.0f, 3, 0, 0.1f, 0);
    TriangleMesh holed = makePerforatedSphere("h", {0, 0, 0}, 1.0f, 3, 12, 0.15f, 0);
    EXPECT_TRUE(whole.isClosed());
    EXPECT_TRUE(whole.normals.empty());  // facets: flat shading
    EXPECT_EQ(whole.triangleCount(), 1280u);
    EXPECT_FALSE(holed.isClosed());
    // 12 caps of angular radius 0.15 cover 12 (1 - cos 0.15) / 2 = 6.7% of the sphere.
    double removed = 1.0 - double(holed.triangleCount()) / 1280.0;
    EXPECT_NEAR(removed, 6.0 * (1.0 - std::cos(0.15)), 0.025);
}

TEST(MeshBuilders, MirroringTransformKeepsTheOutside) {
    TriangleMesh m = makeBox("b", {0, 0, 0}, {1, 1, 1}, 0);
    transformMesh(m, Affine::scaling(-2, 1, 1));
    EXPECT_TRUE(m.isClosed());
    EXPECT_NEAR(signedVolume(m), 2.0, 1e-5);
    TriangleMesh s = makeSphere("s", {0, 0, 0}, 1.0f, 1, 0);
    transformMesh(s, Affine::scaling(1, -3, 1));
    EXPECT_TRUE(normalsAgreeWithWinding(s));
    EXPECT_GT(signedVolume(s), 0.0);
}

}  // namespace
}  // namespace tyndall
