// The surface kernel at edges (cpu/surface_boundary.h, docs/algorithm.md "The surface kernel at
// edges").
//
// 1. massBeyondSegment against quadrature of the 2D Epanechnikov kernel over a polar grid, and
//    its half-plane values (1/2 through the centre, 0 at the radius).
// 2. coverage() in a closed room: 1 in the middle of the floor and across the diagonal of its
//    quad (no false edge there, nor between two unwelded copies of a floor), the half-plane mass
//    at a distance from one wall, 1/4 in a corner; 1 in a scene without edges.
// 3. The bias it removes, end to end: a diffuse floor in a room of black walls lit by a point
//    light, photons only (--direct-light off: the floor's light is I cos / d^2 exactly, nothing
//    bounces back). Against the kernels' exact means (the closed form integrated over the floor
//    part of the disc) within 2%, in the band within r/2 of the walls and in the middle: the plain
//    kernel reads ~0.77 of the closed form in the band, the renormalised one ~1.03 (the
//    first-order blur of the light's slope, which renormalising does not remove).
// 4. The pre-check's clearance grid is a lower bound of the distance to the nearest half-edge
//    (brute force), and a useful one (within sqrt(3) and ~2 cells).
// 5. Layered surfaces: a rug 0.1 r above a floor, its rim's band against the closed form and the
//    kernels' exact means (plain, boundary without the layer probe: over-counted ~1.4x, with it).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "core/accumulator.h"
#include "core/rng.h"
#include "cpu/embree_scene.h"
#include "cpu/pass_renderer.h"
#include "cpu/surface_boundary.h"
#include "cpu/surface_boundary_clearance.h"
#include "loading/mesh_builders.h"

namespace tyndall {
namespace {

/// The kernel mass beyond the segment's line within the angle it subtends, by a polar grid.
double quadratureBeyond(double ax, double ay, double bx, double by, double r) {
    const int nr = 800, nt = 1600;
    double sum = 0;
    const double dx = bx - ax, dy = by - ay;
    for (int it = 0; it < nt; ++it) {
        const double th = (it + 0.5) * 2 * M_PI / nt;
        const double cx = std::cos(th), cy = std::sin(th);
        // Where the ray from the centre along th meets the segment (if it does).
        const double den = cx * dy - cy * dx;
        if (std::abs(den) < 1e-15) continue;
        const double s = (ax * dy - ay * dx) / den;   // distance along the ray
        const double u = (ax * cy - ay * cx) / den;   // position on the segment, 0..1
        if (s <= 0 || u < 0 || u > 1) continue;
        for (int ir = 0; ir < nr; ++ir) {
            const double rho = (ir + 0.5) * r / nr;
            if (rho < s) continue;
            sum += 2 / (M_PI * r * r) * (1 - rho * rho / (r * r)) * rho * (r / nr) * (2 * M_PI / nt);
        }
    }
    return sum;
}

TEST(SurfaceBoundary, MassBeyondSegmentMatchesQuadrature) {
    EXPECT_NEAR(SurfaceBoundary::massBeyondSegment(0, -5, 0, 5, 1), 0.5, 1e-12);   // through the centre
    EXPECT_NEAR(SurfaceBoundary::massBeyondSegment(1, -5, 1, 5, 1), 0.0, 1e-12);   // at the radius
    EXPECT_NEAR(SurfaceBoundary::massBeyondSegment(2, -5, 2, 5, 1), 0.0, 1e-12);   // beyond it
    // Half-plane at distance h: (8 / 3 pi) int_h^1 (1 - x^2)^(3/2) dx (the kernel's marginal).
    for (double h : {0.1, 0.3, 0.6, 0.9}) {
        const double closed = 8 / (3 * M_PI) *
                              (3 * M_PI / 16 - (h / 8 * (5 - 2 * h * h) * std::sqrt(1 - h * h) + 3.0 / 8 * std::asin(h)));
        EXPECT_NEAR(SurfaceBoundary::massBeyondSegment(h, -3, h, 3, 1), closed, 1e-9) << "h " << h;
        EXPECT_NEAR(SurfaceBoundary::massBeyondSegment(2 * h, -6, 2 * h, 6, 2), closed, 1e-9) << "scaled, h " << h;
    }
    // Segments that end inside the disc, straddle the foot or not, in either orientation.
    const double segs[][4] = {{0.3, -0.2, 0.3, 0.5}, {0.2, 0.1, -0.4, 0.5}, {-0.5, 0.6, 0.5, 0.6},
                              {0.05, 0.05, 0.9, -0.1}, {0.4, 0.3, 0.4, -0.9}, {-0.1, -0.7, 0.6, -0.2}};
    for (const auto& s : segs) {
        const double a = SurfaceBoundary::massBeyondSegment(s[0], s[1], s[2], s[3], 1);
        const double b = SurfaceBoundary::massBeyondSegment(s[2], s[3], s[0], s[1], 1);
        const double q = quadratureBeyond(s[0], s[1], s[2], s[3], 1);
        EXPECT_NEAR(a, q, 2e-3) << s[0] << " " << s[1] << " " << s[2] << " " << s[3];
        EXPECT_NEAR(a, b, 1e-12);
    }
}

double segmentDistance(const Vec3& x, const Vec3& a, const Vec3& b) {
    const double abx = b.x - a.x, aby = b.y - a.y, abz = b.z - a.z;
    const double ab2 = abx * abx + aby * aby + abz * abz;
    double s = ab2 > 0 ? ((x.x - a.x) * abx + (x.y - a.y) * aby + (x.z - a.z) * abz) / ab2 : 0;
    s = std::clamp(s, 0.0, 1.0);
    const double dx = a.x + s * abx - x.x, dy = a.y + s * aby - x.y, dz = a.z + s * abz - x.z;
    return std::sqrt(dx * dx + dy * dy + dz * dz);
}

// The pre-check is exact only if its clearance never exceeds the true distance to the nearest
// segment: random segments (long diagonal ones, short ones), random points in the domain (half on
// a thin slab, where most gather points are), in and far from the origin and at two scales,
// against the brute-force distance. And it must be useful: within sqrt(3) (its chessboard metric)
// and ~2 cells of the truth. Then segments outside the domain (marked in its border cells).
TEST(SurfaceBoundary, ClearanceIsALowerBoundOfTheEdgeDistance) {
    auto nearest = [](const Vec3& x, const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
        double d = 1e30;
        for (size_t i = 0; i < a.size(); ++i) d = std::min(d, segmentDistance(x, a[i], b[i]));
        return d;
    };
    for (int trial = 0; trial < 6; ++trial) {
        Rng rng(17 + trial, 5);
        auto in = [&](float lo, float hi) { return lo + (hi - lo) * rng.uniform(); };
        const float scale = trial % 2 ? 1000.0f : 0.01f;  // the unit of length does not matter
        const Vec3 shift = trial >= 4 ? Vec3(3000.0f, -20.0f, 0.0f) * scale : Vec3(0.0f);
        Bounds3 domain;
        domain.extend(shift + Vec3(-2, -0.5f, -1) * scale);
        domain.extend(shift + Vec3(2, 0.5f, 1) * scale);
        auto inside = [&](const Vec3& p) { return vmin(vmax(p, domain.lo), domain.hi); };
        std::vector<Vec3> a, b;
        const int n = trial % 3 == 0 ? 3 : 40;
        for (int i = 0; i < n; ++i) {
            const Vec3 p = shift + Vec3(in(-2, 2), in(-0.5f, 0.5f), in(-1, 1)) * scale;
            const float len = i % 4 == 0 ? 3.0f : 0.05f;
            a.push_back(p);
            b.push_back(inside(p + Vec3(in(-len, len), in(-len, len) * 0.3f, in(-len, len)) * scale));
        }
        const EdgeClearanceGrid grid(a, b, domain);
        ASSERT_GT(grid.cellCount(), 0u);
        const float cell = grid.cellSize();
        int positive = 0;
        for (int q = 0; q < 20000; ++q) {
            const float y = q % 2 ? in(-0.5f, 0.5f) : in(-1e-3f, 1e-3f);
            const Vec3 x = shift + Vec3(in(-2, 2), y, in(-1, 1)) * scale;
            const double truth = nearest(x, a, b);
            const float c = grid.clearance(x);
            ASSERT_LE(c, truth) << "trial " << trial << " point " << x.x << " " << x.y << " " << x.z;
            ASSERT_GE(c, truth / std::sqrt(3.0) - 2.2 * cell) << "trial " << trial;
            positive += c > 0;
        }
        EXPECT_GT(positive, 10000) << "trial " << trial;

        // Segments beyond the domain's faces and corners: still bounded, from inside and outside.
        std::vector<Vec3> oa, ob;
        for (int i = 0; i < 8; ++i) {
            const Vec3 p = shift + Vec3(i & 1 ? 2.2f : -2.4f, i & 2 ? 0.6f : in(-0.5f, 0.5f), i & 4 ? 1.3f : in(-1, 1)) * scale;
            oa.push_back(p);
            ob.push_back(p + Vec3(in(-0.3f, 0.3f), 0.0f, in(-0.3f, 0.3f)) * scale);
        }
        const EdgeClearanceGrid outer(oa, ob, domain);
        for (int q = 0; q < 5000; ++q) {
            const Vec3 x = shift + Vec3(in(-2.6f, 2.6f), in(-0.7f, 0.7f), in(-1.4f, 1.4f)) * scale;
            ASSERT_LE(outer.clearance(x), nearest(x, oa, ob)) << "trial " << trial;
        }
    }
    // No segments: nothing is near; no domain: nothing is known.
    EXPECT_EQ(EdgeClearanceGrid({}, {}, Bounds3{}).clearance(Vec3(0.0f)), kInfinity);
    EXPECT_EQ(EdgeClearanceGrid({Vec3(0.0f)}, {Vec3(1.0f)}, Bounds3{}).clearance(Vec3(5.0f)), 0.0f);
}

/// A room [-1, 1]^3 of diffuse walls (one inward box), or a floor made of two unwelded quads.
Scene roomScene(bool floorOnly) {
    Scene s;
    s.name = "room";
    s.source = "<test>";
    Material white;
    white.name = "white";
    white.albedo = Rgb(0.5f);
    s.materials.push_back(white);
    if (floorOnly) {
        s.meshes.push_back(makeQuad("floor-a", {-1, -1, 1}, {1, 0, 0}, {0, 0, -2}, 0));
        s.meshes.push_back(makeQuad("floor-b", {0, -1, 1}, {1, 0, 0}, {0, 0, -2}, 0));
    } else {
        s.meshes.push_back(makeBox("room", Vec3(-1.0f), Vec3(1.0f), 0, true));
    }
    Light l;
    l.name = "bulb";
    l.position = {0, 0.5f, 0};
    l.intensity = Rgb(1.0f);
    s.lights.push_back(l);
    s.camera = Camera::lookAt({0, 0, 0.9f}, {0, 0, -1}, {0, 1, 0}, 1.0f);
    s.finalize();
    return s;
}

/// coverage() at the floor point (x, -1, z), with the normal of the hit found there.
float floorCoverage(const EmbreeScene& rt, const SurfaceBoundary& b, float x, float z, float r) {
    SurfaceHit hit;
    EXPECT_TRUE(rt.intersect(Ray{{x, 0.0f, z}, {0, -1, 0}}, &hit));
    return b.coverage(hit.p, hit.ng, r);
}

TEST(SurfaceBoundary, CoverageInARoom) {
    Scene room = roomScene(false);
    EmbreeScene rt(room);
    SurfaceBoundary b(room, rt);
    EXPECT_EQ(b.featureEdgeCount(), 24u);  // 12 box edges, each bounding two faces
    const float r = 0.2f;
    EXPECT_FLOAT_EQ(floorCoverage(rt, b, 0.1f, 0.2f, r), 1.0f);
    // The floor quad's diagonal runs from corner to corner: no edge there.
    EXPECT_FLOAT_EQ(floorCoverage(rt, b, 0.3f, 0.3f, r), 1.0f);
    EXPECT_FLOAT_EQ(floorCoverage(rt, b, -0.5f, 0.5f, r), 1.0f);
    for (float h : {0.0f, 0.05f, 0.1f, 0.15f}) {
        const double expect = 1 - SurfaceBoundary::massBeyondSegment(h, -5, h, 5, r);
        EXPECT_NEAR(floorCoverage(rt, b, 1.0f - h, 0.1f, r), expect, 1e-4) << "h " << h;
        EXPECT_NEAR(floorCoverage(rt, b, 0.1f, -1.0f + h, r), expect, 1e-4) << "h " << h;
    }
    EXPECT_NEAR(floorCoverage(rt, b, 0.9999f, 0.9999f, r), 0.25, 2e-3);  // a corner
    EXPECT_FLOAT_EQ(floorCoverage(rt, b, 0.5f, 0.5f, 0.0f), 1.0f);

    // Two unwelded quads that meet: no edge between them; their outer rims are open edges.
    Scene floor = roomScene(true);
    EmbreeScene frt(floor);
    SurfaceBoundary fb(floor, frt);
    EXPECT_FLOAT_EQ(floorCoverage(frt, fb, 0.0f, 0.0f, r), 1.0f);
    EXPECT_FLOAT_EQ(floorCoverage(frt, fb, 0.05f, 0.3f, r), 1.0f);
    EXPECT_NEAR(floorCoverage(frt, fb, 0.95f, 0.3f, r), 1 - SurfaceBoundary::massBeyondSegment(0.05, -5, 0.05, 5, r),
                1e-4);
}

TEST(SurfaceBoundary, HalfOctaveKeyIsFrexpAndLdexpBitForBit) {
    auto definition = [](float r) {
        int e;
        const float m = std::frexp(r, &e);
        return std::ldexp(m < 0.70710677f ? 0.70710683f : 1.0f, e);
    };
    std::vector<float> radii = {1e-45f, 1e-39f, 1.1754942e-38f, 1.1754944e-38f, 0.5f, 0.70710677f, 0.70710683f,
                                std::nextafter(0.70710677f, 0.0f), 1.0f, 3.0e38f, 1.7e38f, 8.5e37f, kInfinity};
    Rng rng(5, 5);
    for (int i = 0; i < 20000; ++i) radii.push_back(std::ldexp(0.5f + 0.5f * rng.uniform(), int(rng.uniform() * 260) - 140));
    for (float r : radii) {
        const float a = SurfaceBoundary::halfOctaveAbove(r), b = definition(r);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << r << ": " << a << " vs " << b;
    }
}

TEST(SurfaceBoundary, CellCandidatesServeEveryNormalAsAFreshQuery) {
    // A corner of the room: the floor's and two walls' points share pre-check cells, and the
    // per-thread candidate lists keep the half-edges facing the last normal asked for. Asked in
    // turn with each normal, the coverage must equal what a boundary with empty caches gives.
    Scene room = roomScene(false);
    EmbreeScene rt(room);
    const Vec3 points[3][2] = {{{0.93f, -1.0f, 0.91f}, {0, 1, 0}},    // floor
                               {{1.0f, -0.95f, 0.9f}, {-1, 0, 0}},    // wall x = 1
                               {{0.92f, -0.94f, 1.0f}, {0, 0, -1}}};  // wall z = 1
    float fresh[3][2];
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 2; ++j) {
            SurfaceBoundary b(room, rt);  // a new owner: nothing cached for it
            fresh[k][j] = b.coverage(points[k][0], points[k][1], j ? 0.3f : 0.12f);
            EXPECT_LT(fresh[k][j], 0.99f) << "the point is near edges";
        }
    SurfaceBoundary b(room, rt);
    for (int round = 0; round < 3; ++round)
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 2; ++j)
                EXPECT_EQ(b.coverage(points[k][0], points[k][1], j ? 0.3f : 0.12f), fresh[k][j]) << k << " " << j;
}

/// massBeyondSegment as first written, every angle and tangent per call: the definition the kept
/// angles (PlaneSegment) must reproduce bit for bit.
double massBeyondSegmentDefinition(double ax, double ay, double bx, double by, double r) {
    const double dx = bx - ax, dy = by - ay;
    const double len = std::sqrt(dx * dx + dy * dy);
    if (!(len > 0) || !(r > 0)) return 0.0;
    const double ux = dx / len, uy = dy / len;
    const double h = std::abs(ax * uy - ay * ux);
    if (h >= r) return 0.0;
    const double ta = ax * ux + ay * uy, tb = bx * ux + by * uy;
    const double kInv2Pi = 0.5 / M_PI;
    if (h < 1e-9 * r) {
        const double lo = ta < 0 ? -0.5 * M_PI : 0.0, hi = tb > 0 ? 0.5 * M_PI : 0.0;
        return hi > lo ? (hi - lo) * kInv2Pi : 0.0;
    }
    const double eta = h / r, phiC = std::acos(eta);
    const double lo = std::max(std::atan(ta / h), -phiC), hi = std::min(std::atan(tb / h), phiC);
    if (!(hi > lo)) return 0.0;
    const double e2 = eta * eta, e4 = e2 * e2;
    auto F = [&](double phi) {
        const double t = std::tan(phi);
        return phi * kInv2Pi - (e2 * t - 0.5 * e4 * (t + t * t * t / 3.0)) / M_PI;
    };
    return std::max(0.0, F(hi) - F(lo));
}

// The per-gather evaluation (AtPoint: the facing half-edges kept once for the largest radius asked
// so far, each segment's angles and tangents computed once) must give coverage() at the radius
// bucket's middle bit for bit, whatever order the radii come in: points near the room's edges and
// corners (on the floor, walls and ceiling), 40 radii over three octaves each, ascending,
// descending or shuffled. And a PlaneSegment evaluated at a run of radii must give the
// definition's double at each (massBeyondSegment as first written), for segments of every kind
// (through the centre, ending inside the disc, reaching past it on one side or both).
TEST(SurfaceBoundary, PerGatherCoverageIsCoverageAtTheBucketMiddleBitForBit) {
    auto bitsOf = [](auto v) {
        uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof v);
        return bits;
    };
    auto bucketMiddle = [](float r) {
        uint32_t bits;
        std::memcpy(&bits, &r, sizeof bits);
        bits = ((bits >> 18) << 18) | (1u << 17);
        float rq;
        std::memcpy(&rq, &bits, sizeof rq);
        return rq;
    };
    Scene room = roomScene(false);
    EmbreeScene rt(room);
    SurfaceBoundary b(room, rt);
    Rng rng(23, 7);
    int cut = 0, evaluations = 0;
    for (int q = 0; q < 240; ++q) {
        // From the middle toward a point with every coordinate 0.6 to 1 from the centre: the
        // hit lies near an edge or a corner of the face it meets.
        Vec3 target;
        for (int k = 0; k < 3; ++k) target[k] = (rng.uniform() < 0.5f ? -1.0f : 1.0f) * (0.6f + 0.4f * rng.uniform());
        SurfaceHit hit;
        ASSERT_TRUE(rt.intersect(Ray{Vec3(0.0f), normalize(target)}, &hit));
        std::vector<float> radii;
        for (int i = 0; i < 40; ++i) radii.push_back(0.05f * std::exp2(3.0f * rng.uniform()));
        if (q % 3 == 0) std::sort(radii.begin(), radii.end());
        if (q % 3 == 1) std::sort(radii.rbegin(), radii.rend());
        SurfaceBoundary::AtPoint at(b, hit.p, hit.ng);
        for (float r : radii) {
            const float got = at(r), want = b.coverage(hit.p, hit.ng, bucketMiddle(r));
            ASSERT_EQ(bitsOf(got), bitsOf(want)) << "point " << q << " r " << r << ": " << got << " vs " << want;
            cut += got < 1.0f;
            ++evaluations;
        }
    }
    EXPECT_GT(cut, evaluations / 3) << "most points are near an edge";

    int nonzero = 0;
    for (int q = 0; q < 2000; ++q) {
        auto in = [&] { return 3.0 * rng.uniform() - 1.5; };
        double s[4] = {in(), in(), in(), in()};
        if (q % 10 == 0) s[2] = -s[0] * 0.7, s[3] = -s[1] * 0.7;  // through the centre
        SurfaceBoundary::PlaneSegment segment(s[0], s[1], s[2], s[3]);
        for (int i = 0; i < 12; ++i) {
            const double r = 0.1 + 2.0 * rng.uniform();
            ASSERT_EQ(bitsOf(segment.mass(r)), bitsOf(massBeyondSegmentDefinition(s[0], s[1], s[2], s[3], r)))
                << s[0] << " " << s[1] << " " << s[2] << " " << s[3] << " r " << r;
            nonzero += segment.mass(r) > 0;
        }
    }
    EXPECT_GT(nonzero, 8000);
}

/// A diffuse (or `floorType`) floor x, z in [-1, 1] at y = 0 in a room of black walls 1 high,
/// open at the top, a point light above the floor, seen from straight above.
Scene blackWallRoom(MaterialType floorType = MaterialType::Diffuse) {
    Scene s;
    s.name = "black-wall-room";
    s.source = "<test>";
    Material floor, black;
    floor.name = "floor";
    floor.type = floorType;
    floor.roughness = 0.5f;
    floor.albedo = Rgb(0.5f);
    black.name = "black";
    black.albedo = Rgb(0.0f);
    s.materials = {floor, black};
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    s.meshes.push_back(makeQuad("wall-x0", {-1, 0, 1}, {0, 0, -2}, {0, 1, 0}, 1));
    s.meshes.push_back(makeQuad("wall-x1", {1, 0, -1}, {0, 0, 2}, {0, 1, 0}, 1));
    s.meshes.push_back(makeQuad("wall-z0", {1, 0, -1}, {0, 1, 0}, {-2, 0, 0}, 1));
    s.meshes.push_back(makeQuad("wall-z1", {-1, 0, 1}, {0, 1, 0}, {2, 0, 0}, 1));
    Light l;
    l.name = "bulb";
    l.position = {0.2f, 0.7f, -0.1f};
    l.intensity = Rgb(1.0f);
    s.lights.push_back(l);
    s.camera = Camera::lookAt({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 2.0f * std::atan(1.0f / 3.0f));
    s.finalize();
    return s;
}

/// The mean of `passes` passes' surface layer (photons only, no shadow rays) at n x n, the surface
/// radius fixed at r (schedule offset 2^40), 20000 photon paths a pass, seed 3.
Image renderSurfaceLayer(const Scene& scene, int n, float r, uint64_t passes, bool boundary) {
    RenderSettings s;
    s.width = s.height = n;
    s.photonsPerPass = 20000;
    s.passes = passes;
    s.seed = 3;
    s.radius = 0.01f;
    s.surfaceRadius = r;
    s.radiusOffset = uint64_t(1) << 40;  // the radius stays r
    s.photonAngle = 0;
    s.directLight = false;
    s.surfaceBoundary = boundary;
    s.gpu = GpuMode::Off;
    PassRenderer renderer(scene, s, BeamBvh::Kind::FlatCurves, true);
    Accumulator acc(n, n);
    for (uint64_t pass = 0; pass < s.passes; ++pass) acc.addPass(renderer.renderPassLayers(pass).surface);
    return acc.mean();
}

TEST(SurfaceBoundary, FloorAgainstTheClosedFormAtTheWalls) {
    const Scene scene = blackWallRoom();
    const int n = 32;
    const double r = 0.1;
    const Vec3 light = scene.lights[0].position;
    auto E = [&](double x, double z) {  // outgoing radiance rho/pi I cos / d^2
        const double dx = light.x - x, dy = light.y, dz = light.z - z, d2 = dx * dx + dy * dy + dz * dz;
        return 0.5 / M_PI * dy / std::sqrt(d2) / d2;
    };
    // Per pixel, over a 4x4 grid of floor points in it (seen straight down the image maps the
    // floor affinely: project and bin): the closed form, and the means of the plain and the
    // renormalised kernel estimates, the kernel integrated over the floor part of its disc by a
    // polar grid (plain = int E K, renormalised = plain / int K).
    std::vector<double> closed(n * n, 0.0), plain(n * n, 0.0), renorm(n * n, 0.0), count(n * n, 0.0);
    std::vector<double> wallDistance(n * n, 1e9);
    const int sub = 4, nr = 24, nt = 64;
    for (int i = 0; i < n * sub; ++i)
        for (int j = 0; j < n * sub; ++j) {
            const double x = -1 + 2 * (i + 0.5) / (n * sub), z = -1 + 2 * (j + 0.5) / (n * sub);
            float px, py, depth;
            if (!scene.camera.project(Vec3(float(x), 0.0f, float(z)), n, n, &px, &py, &depth)) continue;
            const int k = int(py) * n + int(px);
            if (px < 0 || py < 0 || px >= n || py >= n) continue;
            double sum = 0, mass = 0;
            for (int ir = 0; ir < nr; ++ir)
                for (int it = 0; it < nt; ++it) {
                    const double rho = (ir + 0.5) * r / nr, th = (it + 0.5) * 2 * M_PI / nt;
                    const double qx = x + rho * std::cos(th), qz = z + rho * std::sin(th);
                    if (std::abs(qx) > 1 || std::abs(qz) > 1) continue;
                    const double w = 2 / (M_PI * r * r) * (1 - rho * rho / (r * r)) * rho * (r / nr) * (2 * M_PI / nt);
                    sum += w * E(qx, qz);
                    mass += w;
                }
            closed[k] += E(x, z);
            plain[k] += sum;
            renorm[k] += sum / std::max(mass, 0.25);
            count[k] += 1;
            wallDistance[k] = std::min(wallDistance[k], 1 - std::max(std::abs(x), std::abs(z)));
        }

    struct Band {
        double render = 0, closed = 0, expected = 0;
    };
    auto bands = [&](const std::string& boundary, Band* edge, Band* middle) {
        const Image img = renderSurfaceLayer(scene, n, float(r), 8, boundary == "on");
        for (int k = 0; k < n * n; ++k) {
            if (count[k] < sub * sub) continue;  // pixels wholly on the floor
            Band* b = wallDistance[k] < 0.5 * r ? edge : wallDistance[k] > 1.5 * r ? middle : nullptr;
            if (!b) continue;  // within r/2 of a wall, or no disc reaches one
            b->render += img.at(k % n, k / n).g;
            b->closed += closed[k] / count[k];
            b->expected += (boundary == "on" ? renorm[k] : plain[k]) / count[k];
        }
        std::printf("surface boundary %-3s  render / closed form: band at the walls %.4f, middle %.4f; "
                    "render / kernel's mean: %.4f, %.4f\n",
                    boundary.c_str(), edge->render / edge->closed, middle->render / middle->closed,
                    edge->render / edge->expected, middle->render / middle->expected);
    };
    Band edgeOff, middleOff, edgeOn, middleOn;
    bands("off", &edgeOff, &middleOff);
    bands("on", &edgeOn, &middleOn);
    // Each estimator's mean (the band's noise is ~0.5%).
    EXPECT_NEAR(edgeOff.render / edgeOff.expected, 1.0, 0.02);
    EXPECT_NEAR(middleOff.render / middleOff.expected, 1.0, 0.02);
    EXPECT_NEAR(edgeOn.render / edgeOn.expected, 1.0, 0.02);
    EXPECT_NEAR(middleOn.render / middleOn.expected, 1.0, 0.02);
    // The plain kernel loses ~1/4 of the light in the band (its disc reaches past the walls);
    // renormalised, what is left is the first-order blur of the light's slope (+3% here: the disc's
    // floor part lies toward the light).
    EXPECT_LT(edgeOff.render / edgeOff.closed, 0.85);
    EXPECT_NEAR(edgeOn.render / edgeOn.closed, 1.0, 0.06);
    EXPECT_NEAR(middleOn.render / middleOn.closed, 1.0, 0.02);
}

// A plastic floor (glTF's non-metals): its gather, both parts, is renormalised like the diffuse
// end's. Same photons and camera paths on and off, so per pixel on = off / coverage: in the band at
// the walls the ratio of the sums is the kernel's lost mass, in the middle exactly 1.
TEST(SurfaceBoundary, PlasticFloorIsRenormalisedLikeADiffuseOne) {
    const Scene scene = blackWallRoom(MaterialType::Plastic);
    const int n = 32;
    const float r = 0.1f;
    const Image off = renderSurfaceLayer(scene, n, r, 2, false), on = renderSurfaceLayer(scene, n, r, 2, true);
    // Pixels by the floor distance of their centre to the nearest wall (the floor fills the image).
    double edgeOn = 0, edgeOff = 0, middleOn = 0, middleOff = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double fx = -1 + 2 * (x + 0.5) / n, fz = -1 + 2 * (y + 0.5) / n;
            const double wall = 1 - std::max(std::abs(fx), std::abs(fz));
            if (wall < 0.5 * r) {  // the outermost ring of pixels: 0 to 0.625 r from a wall
                edgeOn += on.at(x, y).g;
                edgeOff += off.at(x, y).g;
            } else if (wall > 1.5 * r) {
                middleOn += on.at(x, y).g;
                middleOff += off.at(x, y).g;
            }
        }
    ASSERT_GT(edgeOff, 0.0);
    ASSERT_GT(middleOff, 0.0);
    std::printf("plastic floor, boundary on / off: band at the walls %.4f, middle %.6f\n", edgeOn / edgeOff,
                middleOn / middleOff);
    // Over 0 to 0.625 r from a wall the disc loses 50% to 4% of its mass (more in the corners):
    // on / off ~ 1.3 there, 1 in the middle.
    EXPECT_GT(edgeOn / edgeOff, 1.15);
    EXPECT_LT(edgeOn / edgeOff, 2.0);
    EXPECT_NEAR(middleOn / middleOff, 1.0, 1e-4);
}

// Layered surfaces: a rug (a diffuse quad [-0.5, 0.5]^2) lying 0.1 r above a larger diffuse floor
// ([-1, 1]^2), lit by a point light, photons only, seen from straight above. Past the rug's rim
// the gather's slab (r/4) takes the floor's photons, so the plain kernel loses nothing there, and
// dividing by the rug's coverage (what the boundary did before the layer probe) over-counts: by
// the kernel means below, ~1.4x in the band within r/2 of the rim. With the probe the rim's edges
// find the floor 0.1 r below and remove nothing at this radius; at 0.3 r (slab 0.075 r < 0.1 r)
// they do again. Means per pixel: the closed form E, and each estimator's exact mean, the kernel
// integrated over its disc by a polar grid (rug part at the rug's height; floor part past the rim
// with the floor's light, the rug's shadow included, and the kernel at the 3D distance).
TEST(SurfaceBoundary, RugOnAFloorIsNotOverCounted) {
    const float r = 0.1f, h = 0.1f * r;
    Scene scene;
    scene.name = "rug";
    scene.source = "<test>";
    Material white;
    white.name = "white";
    white.albedo = Rgb(0.5f);
    scene.materials = {white};
    scene.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, 0));
    scene.meshes.push_back(makeQuad("rug", {-0.5f, h, 0.5f}, {1, 0, 0}, {0, 0, -1}, 0));
    Light light;
    light.name = "bulb";
    light.position = {0.2f, 0.7f, -0.1f};
    light.intensity = Rgb(1.0f);
    scene.lights.push_back(light);
    scene.camera = Camera::lookAt({0, 3, 0}, {0, 0, 0}, {0, 0, -1}, 2.0f * std::atan(0.6f / 3.0f));
    scene.finalize();

    // The coverage itself at a point r/4 inside the rim.
    {
        EmbreeScene rt(scene);
        const SurfaceBoundary probe(scene, rt), ignore(scene, rt, SurfaceBoundary::Layers::Ignore);
        const Vec3 x(0.5f - 0.25f * r, h, 0.1f), n(0, 1, 0);
        const double lost = SurfaceBoundary::massBeyondSegment(0.25 * r, -5, 0.25 * r, 5, r);
        EXPECT_NEAR(ignore.coverage(x, n, r), 1 - lost, 1e-4);
        EXPECT_EQ(probe.coverage(x, n, r), 1.0f);  // the floor, 0.1 r below, is in the slab
        EXPECT_NEAR(probe.coverage(x, n, 0.3f * r), 1 - SurfaceBoundary::massBeyondSegment(0.25 * r, -5, 0.25 * r, 5, 0.3 * r),
                    1e-4);  // at 0.3 r it is not
        EXPECT_EQ(probe.coverage(Vec3(0.5f + 0.25f * r, 0.0f, 0.1f), n, r), 1.0f);  // the floor past the rim
    }

    const Vec3 L = light.position;
    auto E = [&](double x, double y, double z) {  // outgoing radiance rho/pi I cos / d^2 at height y
        const double dx = L.x - x, dy = L.y - y, dz = L.z - z, d2 = dx * dx + dy * dy + dz * dz;
        return 0.5 / M_PI * dy / std::sqrt(d2) / d2;
    };
    auto onRug = [](double x, double z) { return std::abs(x) <= 0.5 && std::abs(z) <= 0.5; };
    auto floorLight = [&](double x, double z) {  // the floor's: none under the rug or in its shadow
        const double s = h / L.y;
        return onRug(x, z) || onRug(x + (L.x - x) * s, z + (L.z - z) * s) ? 0.0 : E(x, 0, z);
    };
    const int n = 48, sub = 4, nr = 32, nt = 96;
    std::vector<double> closed(n * n, 0.0), plain(n * n, 0.0), old(n * n, 0.0), count(n * n, 0.0);
    std::vector<double> rim(n * n, 1e9);
    for (int i = 0; i < n * sub; ++i)
        for (int j = 0; j < n * sub; ++j) {
            const double x = -0.6 + 1.2 * (i + 0.5) / (n * sub), z = -0.6 + 1.2 * (j + 0.5) / (n * sub);
            if (!onRug(x, z)) continue;
            float px, py, depth;
            if (!scene.camera.project(Vec3(float(x), h, float(z)), n, n, &px, &py, &depth)) continue;
            if (px < 0 || py < 0 || px >= n || py >= n) continue;
            const int k = int(py) * n + int(px);
            double sum = 0, mass = 0;
            for (int ir = 0; ir < nr; ++ir)
                for (int it = 0; it < nt; ++it) {
                    const double rho = (ir + 0.5) * r / nr, th = (it + 0.5) * 2 * M_PI / nt;
                    const double qx = x + rho * std::cos(th), qz = z + rho * std::sin(th), area = rho * (r / nr) * (2 * M_PI / nt);
                    const double k2 = 2 / (M_PI * r * r);
                    if (onRug(qx, qz)) {
                        const double w = k2 * (1 - rho * rho / (r * r)) * area;
                        sum += w * E(qx, h, qz);
                        mass += w;
                    } else if (rho * rho + h * h < r * r) {
                        sum += k2 * (1 - (rho * rho + h * h) / (r * r)) * area * floorLight(qx, qz);
                    }
                }
            closed[k] += E(x, h, z);
            plain[k] += sum;
            old[k] += sum / std::max(mass, 0.25);
            count[k] += 1;
            rim[k] = std::min(rim[k], 0.5 - std::max(std::abs(x), std::abs(z)));
        }

    struct Band {
        double render = 0, closed = 0, plain = 0, old = 0;
    };
    auto bands = [&](const Image& img, Band* edge, Band* middle) {
        for (int k = 0; k < n * n; ++k) {
            if (count[k] < sub * sub) continue;  // pixels wholly on the rug
            Band* b = rim[k] < 0.5 * r ? edge : rim[k] > 1.5 * r ? middle : nullptr;
            if (!b) continue;
            b->render += img.at(k % n, k / n).g;
            b->closed += closed[k] / count[k];
            b->plain += plain[k] / count[k];
            b->old += old[k] / count[k];
        }
    };
    Band edgeOff, middleOff, edgeOn, middleOn;
    bands(renderSurfaceLayer(scene, n, r, 8, false), &edgeOff, &middleOff);
    bands(renderSurfaceLayer(scene, n, r, 8, true), &edgeOn, &middleOn);
    std::printf("rug 0.1 r above the floor, band within r/2 of its rim / closed form: plain kernel's mean %.4f, "
                "boundary without the layer probe %.4f; render off %.4f, on %.4f (middle: %.4f, %.4f)\n",
                edgeOff.plain / edgeOff.closed, edgeOff.old / edgeOff.closed, edgeOff.render / edgeOff.closed,
                edgeOn.render / edgeOn.closed, middleOff.render / middleOff.closed, middleOn.render / middleOn.closed);
    // What the probe is for: the plain kernel's mean is close to the light here (the floor fills
    // the disc past the rim; 0.94: the rug's shadow on it, and the kernel at the 3D distance), and
    // dividing it by the rug's coverage over-counts by ~40%.
    EXPECT_NEAR(edgeOff.plain / edgeOff.closed, 0.95, 0.03);
    EXPECT_GT(edgeOff.old / edgeOff.closed, 1.25);
    // Both renders against the plain kernel's mean (the band's noise is ~0.5%): with the probe the
    // coverage is 1 at the rim (without it, on / plain would be the ~1.5 above).
    EXPECT_NEAR(edgeOff.render / edgeOff.plain, 1.0, 0.02);
    EXPECT_NEAR(edgeOn.render / edgeOn.plain, 1.0, 0.02);
    EXPECT_NEAR(middleOn.render / middleOn.closed, 1.0, 0.02);
    EXPECT_NEAR(middleOff.render / middleOff.closed, 1.0, 0.02);
}

}  // namespace
}  // namespace tyndall
