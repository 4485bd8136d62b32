#pragma once
// The surface photon kernel at the edges of surfaces (docs/algorithm.md, "The surface kernel at
// edges"): the part of the 2D kernel disc that lies on a surface which can hold the photons the
// diffuse gather accepts there. The density estimate sum_p Phi_p K(|x - x_p|, r) has the mean
// int_S E(y) K(|x - y|, r) dA(y), which is E(x) x coverage(x) for smooth E: a disc centred near
// a surface's edge (a concave corner of a room, a table's rim, a hole) reaches past it, where no
// photon of this plane can lie, and the estimate is low by that fraction (boundary bias). Dividing
// by the coverage removes that zeroth-order bias (the renormalised kernel of density estimation);
// what is left is the ordinary blur of the light's own variation.
//
// Where a surface ends is found from the scene's triangles once: a **feature half-edge** is an
// edge of a triangle that stores diffuse photons (diffuse or plastic) with no neighbour across it
// that also does and lies within the gather's normal test (|n . n'| >= 0.7): the mesh's open
// boundary, a crease sharper than 45.6 degrees (the walls of a box), or where a non-storing
// material (mirror, glass, interface) begins. Neighbours are matched by vertex position (bit
// for bit, across meshes), so unwelded meshes and meshes that meet do not make false edges.
// The coverage of a disc of radius r at x is 1 minus, for every feature half-edge near x's plane
// with x on its inner side, the kernel mass beyond it within the angle it subtends from x (closed
// form: massBeyondSegment); for a convex patch around x (a wall, the corner of a room) that sum
// is exact.
//
// **Layered surfaces.** A surface lying a little in front of a parallel one (a rug on a floor, a
// picture frame before a wall, a decal) has open edges, but past them the gather's slab test
// (|offset . n| <= r/4) takes the photons of the surface behind: nothing is lost there, and
// dividing by the coverage would over-count. So each feature half-edge is probed once, just past
// it in its plane (three points along it), by rays along its normal both ways, for the nearest
// photon-holding surface within the gather's normal test; the edge stores the largest |offset| of
// the three (infinity when one finds none), and removes kernel mass only at radii whose slab,
// r/4, that offset exceeds: exact for one parallel layer along the whole edge, as the radius
// shrinks past 4x the offset as well.
//
// **Winding.** A half-edge counts for gather points whose geometric normal agrees with its
// triangle's (a thin closed panel's top and bottom are two planes). Real meshes often wind
// neighbouring triangles inconsistently, so the triangles are first joined into sheets across the
// edges the gather continues over (union-find); on a sheet where two neighbours are wound
// opposite ways the normal's sign says nothing, and its half-edges count for either face.
//
// Not seen (the coverage stays 1, as without this): an object resting on a larger surface that
// continues under it (the floor's triangles do not end at the object), alpha cut-outs, and parts of
// a curved surface that leave the gather's slab. Thin features are clamped at kMinCoverage (a
// convex corner of a box, where three faces meet, is exactly 1/4), which bounds the amplified noise.
//
// Deterministic and thread-safe: the candidates of a query are summed in half-edge order,
// whatever order Embree's point query returns them in.
//
// Most gather points are farther than their radius from every feature half-edge, where the
// coverage is exactly 1: a grid of lower bounds on the distance to the nearest one
// (cpu/surface_boundary_clearance.h) answers those without the point query, conservatively, so
// the coverage is bit for bit what the query gives. Near an edge, the half-edges within r of any
// point of the grid cell holding x are found once per cell and radius and kept per thread (the last
// few), with those among them that pass the normal test for the last normal asked for (a wall's
// gather points share it): neighbouring gather points share them. A superset of those within r of
// x, summed in half-edge order after the same tests, so again the same coverage.
#include <embree3/rtcore.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "core/photon_beam.h"
#include "core/scene.h"
#include "cpu/embree_scene.h"
#include "cpu/surface_boundary_clearance.h"

namespace tyndall {

class SurfaceBoundary {
public:
    /// Whether feature half-edges are probed for a parallel surface past them (Layers::Ignore only
    /// to measure what the probe fixes: tests/cpu/surface_boundary_test.cpp).
    enum class Layers { Probe, Ignore };
    /// Finds the scene's feature half-edges (probing past them with rays of `rt`, the scene's
    /// Embree scene) and builds a BVH over them on rt's device.
    SurfaceBoundary(const Scene& scene, const EmbreeScene& rt, Layers layers = Layers::Probe);
    ~SurfaceBoundary();
    SurfaceBoundary(const SurfaceBoundary&) = delete;
    SurfaceBoundary& operator=(const SurfaceBoundary&) = delete;

    /// The fraction in [kMinCoverage, 1] of the normalised 2D Epanechnikov kernel of radius `r`
    /// centred at surface point `x` (unit geometric normal `ng`, SurfaceHit::ng) that lies on
    /// photon-holding surface of x's plane. 1 away from edges (and for r <= 0).
    float coverage(const Vec3& x, const Vec3& ng, float r) const;

    /// In the plane, with the kernel K(d) = 2/(pi r^2) (1 - d^2/r^2) centred at the origin: a
    /// segment a-b, with what its mass beyond (massBeyondSegment) needs that does not depend on r,
    /// the ends' angles and their tangents kept once computed, so that the radii of one gather
    /// share them. massBeyondSegment is PlaneSegment(a, b).mass(r).
    class PlaneSegment {
    public:
        PlaneSegment() = default;  ///< uninitialised (a gather keeps an array of them)
        PlaneSegment(double ax, double ay, double bx, double by);
        double mass(double r);

    private:
        double m_h, m_ta, m_tb;  ///< distance to the line; the ends along it from the foot
        double m_atA, m_atB, m_tanA, m_tanB;
        bool m_line;  ///< a-b has a length
        bool m_atans, m_hasTanA, m_hasTanB;
    };

private:
    struct HalfEdge {
        Vec3 a, b;
        Vec3 normal;  ///< unit geometric normal of the triangle the edge bounds
        Vec3 inward;  ///< unit, in that triangle's plane, perpendicular to a-b, toward its interior
        float layerOffset;  ///< |normal offset| of a photon-holding surface just past it; infinity: none
        bool mixedWinding;  ///< its sheet holds neighbours wound opposite ways: normal's sign unknown
    };
    /// A facing half-edge seen from a gather point x with x on its inner side: what coverage()
    /// tests and sums for it at any radius.
    struct NearEdge {
        float d2;        ///< squared distance from x to the half-edge
        float offPlane;  ///< |(its point nearest x - x) . ng|
        float layerOffset;
        PlaneSegment segment;  ///< in x's tangent frame (Frame(ng)), x at the origin
        /// Whether it removes kernel mass at radius r: near x's plane where it passes within r,
        /// and no parallel surface past it within the slab.
        bool cuts(float r) const { return !(d2 >= r * r || offPlane > 0.25f * r) && !(layerOffset <= 0.25f * r); }
    };
    /// The NearEdge of half-edge e from x (false: x is not on the surface it bounds).
    static bool nearEdge(const HalfEdge& e, const Vec3& x, const Vec3& ng, const Frame& frame, NearEdge* out);

public:

    /// coverage() for the photons of one gather at x, each at its own radius quantised to 1/32
    /// octave (the float's exponent and top 5 mantissa bits, the bucket's middle): one evaluation
    /// per distinct value. A late pass's photons share two or three; an early pass's span more (the
    /// first pass after a radius offset of 1000 paths, 4000 paths, about 19), kept in a table
    /// indexed by the bucket's low bits (two octaves without a collision). Dividing each photon's
    /// term by the coverage at its own radius keeps the estimate a sum of per-photon terms, so a
    /// pass traced in photon batches sums to the whole pass (a coverage from the gathered photons'
    /// mean radius would depend on which photons a batch holds).
    ///
    /// What does not depend on the radius is found once per gather: the half-edges facing x's
    /// normal with x on their inner side, from the candidates for the largest radius asked so far
    /// (a superset serves every smaller radius), with their distances to x and their segments in
    /// x's plane (PlaneSegment). Each radius then sums, in half-edge order, over those its tests
    /// keep, as coverage() does: bit for bit coverage(x, ng, the bucket's middle).
    class AtPoint {
    public:
        AtPoint(const SurfaceBoundary& boundary, const Vec3& x, const Vec3& ng)
            : m_b(boundary), m_x(x), m_ng(ng), m_clear(boundary.m_clearance.clearance(x)) {}
        /// operator()(r) is exactly 1 for every r <= rMax without a half-edge looked at (its
        /// first test: r x 1.02 <= rMax x 1.02, float multiplication being monotonic).
        bool clearUpTo(float rMax) const { return rMax * 1.02f <= m_clear; }
        float operator()(float r) {
            // The quantised radius is at most 1/64 above r: no half-edge within it, coverage 1.
            if (r * 1.02f <= m_clear) return 1.0f;
            uint32_t bits;
            std::memcpy(&bits, &r, sizeof bits);
            const uint32_t key = bits >> 18, slot = key & (kSlots - 1);
            if ((m_filled >> slot & 1) && m_key[slot] == key) return m_value[slot];
            const uint32_t mid = (key << 18) | (1u << 17);
            float rq;
            std::memcpy(&rq, &mid, sizeof rq);
            const float c = at(rq);
            m_filled |= uint64_t(1) << slot, m_key[slot] = key, m_value[slot] = c;
            return c;
        }

    private:
        /// coverage(m_x, m_ng, r) from the kept half-edges.
        float at(float r);
        /// Keeps the half-edges for radii up to r (false: more than kNear, ask coverage()).
        bool prepare(float r);

        static constexpr int kSlots = 64;
        static constexpr int kNear = 24;
        const SurfaceBoundary& m_b;
        Vec3 m_x, m_ng;
        float m_clear;  ///< no feature half-edge is nearer x than this
        uint64_t m_filled = 0;
        uint32_t m_key[kSlots];
        float m_value[kSlots];
        float m_nearRadius = 0;  ///< m_near holds the half-edges that can matter up to this radius
        bool m_overflow = false;
        int m_nearCount = 0;
        NearEdge m_near[kNear];
    };

    /// Number of feature half-edges (0: no surface in the scene ends anywhere a kernel notices).
    size_t featureEdgeCount() const { return m_edges.size(); }
    /// The pre-check's grid (its cell size, cell count and memory: docs/performance.md).
    const EdgeClearanceGrid& clearanceGrid() const { return m_clearance; }
    /// Bytes the boundary keeps besides Embree's BVH: the half-edges and the pre-check's grid.
    size_t memoryBytes() const { return m_edges.capacity() * sizeof(HalfEdge) + m_clearance.memoryBytes(); }

    /// In the plane, with the kernel K(d) = 2/(pi r^2) (1 - d^2/r^2) centred at the origin: its
    /// mass beyond the segment a-b (on the side away from the origin) inside the angle the
    /// segment subtends from the origin. Half-plane at distance h: 1/2 at h = 0, 0 at h >= r.
    static double massBeyondSegment(double ax, double ay, double bx, double by, double r);
    /// The key of the per-cell candidate lists for radius r > 0: ldexp(m < 0.70710677 ? 0.70710683
    /// : 1, e) with r = m 2^e, m in [0.5, 1) (frexp), the half octave at or above r, by bit
    /// operations (frexp and ldexp themselves for subnormal and the largest r).
    static float halfOctaveAbove(float r);

    static constexpr float kMinCoverage = 0.25f;
    /// The diffuse gather's normal test (camera_tracer.cpp): photons whose normal is within this
    /// cosine of the query's count (core/photon_beam.h).
    static constexpr float kNormalAgreement = kSurfaceNormalAgreement;

private:
    /// Appends to `out` the half-edges Embree finds within r of x (a superset of those closer).
    void query(const Vec3& x, float r, std::vector<uint32_t>* out) const;
    /// The candidate half-edges for coverage(x, ng, r) (a superset of those within r of x, in
    /// half-edge order) that pass the normal test for ng, from the thread's cache (nullptr: none);
    /// *reach: the largest radius the list serves at x.
    const std::vector<uint32_t>* facingCandidates(const Vec3& x, const Vec3& ng, float r, float* reach) const;

    std::vector<HalfEdge> m_edges;
    EdgeClearanceGrid m_clearance;
    uint64_t m_id;  ///< unique per instance: keys the per-thread candidate cache
    RTCScene m_rtcScene = nullptr;
};

}  // namespace tyndall
