#pragma once
// Embree 3 ray queries over a Scene's triangle meshes. One Embree geometry per mesh, with the
// geometry ID equal to the mesh index. Thread-safe for concurrent queries after construction.
#include <embree3/rtcore.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "core/scene.h"
#include "core/surface_hit.h"

namespace tyndall {

/// A candidate query's context: Embree's intersect context followed by the list that the queried
/// geometry's intersect or filter callbacks append primitive ids to (of() from their
/// args->context). For BVHs of user primitives whose estimate is evaluated after the query.
struct CandidateQuery {
    RTCIntersectContext rtc;
    std::vector<uint32_t>* found = nullptr;
    static CandidateQuery& of(RTCIntersectContext* context) { return *reinterpret_cast<CandidateQuery*>(context); }
};

/// Traces o + t d, t in [0, sMax], through `scene` with a CandidateQuery; `found` ends sorted, each
/// id once. Empty when sMax is not positive.
void queryCandidates(RTCScene scene, const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found);

/// Owns an RTCDevice; reports Embree errors by throwing Error from the failing call's thread.
class EmbreeDevice {
public:
    EmbreeDevice();
    ~EmbreeDevice();
    EmbreeDevice(const EmbreeDevice&) = delete;
    EmbreeDevice& operator=(const EmbreeDevice&) = delete;
    RTCDevice get() const { return m_device; }
    /// Throws Error when Embree recorded an error since the last call (message names `what`).
    void check(const char* what) const;

private:
    RTCDevice m_device = nullptr;
};

/// Fills `rh` for a closest-hit query along o + t d, t in (tMin, tMax). Origin and direction go in
/// with 16-byte stores, the way Embree loads them (scalar stores there stall the loads).
inline void initRayHit(RTCRayHit& rh, const Vec3& o, const Vec3& d, float tMin = 0.0f, float tMax = kInfinity) {
#if defined(__SSE__)
    _mm_store_ps(&rh.ray.org_x, _mm_setr_ps(o.x, o.y, o.z, tMin));
    _mm_store_ps(&rh.ray.dir_x, _mm_setr_ps(d.x, d.y, d.z, 0.0f));  // time = 0
#else
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z, rh.ray.tnear = tMin;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z, rh.ray.time = 0.0f;
#endif
    rh.ray.tfar = tMax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

class EmbreeScene {
public:
    EmbreeScene(const Scene& scene, std::shared_ptr<EmbreeDevice> device = nullptr);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// Closest hit with t in (ray.tMin, ray.tMax).
    bool intersect(const Ray& ray, SurfaceHit* hit) const;
    /// The closest hits of up to kPacket coherent rays (neighbouring camera rays) at once, through
    /// Embree's packet traversal: found[i] and hits[i] as intersect(rays[i], &hits[i]) gives them,
    /// for i < n (tests/cpu/embree_scene_test.cpp compares the two bit for bit).
    static constexpr int kPacket = 8;
    void intersectCoherent(const Ray* rays, int n, SurfaceHit* hits, bool* found) const;
    /// Any hit with t in (ray.tMin, ray.tMax).
    bool occluded(const Ray& ray) const;
    /// Every surface stops a shadow ray: no mesh has an Interface material or an alpha mode other
    /// than Opaque (materials as they were at construction, like the alpha filters). Then whether
    /// anything lies between two points is one occluded() query (shadowTransmittance).
    bool everySurfaceBlocks() const { return m_everySurfaceBlocks; }
    /// Embree's raw closest hit for `rh` (set up by initRayHit): no hit record, for the photon
    /// tracer's lean loop. True when something was hit.
    bool intersectRaw(RTCRayHit& rh) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        rtcIntersect1(m_rtcScene, &ctx, &rh);
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    /// Starts fetching what shadingNormal(mesh, tri, ...) reads, so that work in between hides
    /// the cache miss (the normals are not where Embree's traversal just was). Always inlined:
    /// GCC finds an out-of-line prefetch-only function pure and deletes its calls.
    [[gnu::always_inline]] void prefetchShadingNormal(int mesh, uint32_t tri) const {
        const std::vector<TriangleNormals>& normals = m_shadingNormals[size_t(mesh)];
        if (normals.empty()) return;
        const char* at = reinterpret_cast<const char*>(&normals[tri]);
        __builtin_prefetch(at);
        __builtin_prefetch(at + sizeof(TriangleNormals) - 1);
    }
    /// SurfaceHit::ns for a hit at barycentrics (b1, b2) of triangle `tri` of mesh `mesh` with unit
    /// geometric normal `ng`: the interpolated vertex normal on specular meshes with normals, else ng.
    Vec3 shadingNormal(int mesh, uint32_t tri, float b1, float b2, const Vec3& ng) const {
        const std::vector<TriangleNormals>& normals = m_shadingNormals[size_t(mesh)];
        if (normals.empty()) return ng;
        const TriangleNormals& v = normals[tri];
        Vec3 n = v.n[0] * (1.0f - b1 - b2) + v.n[1] * b1 + v.n[2] * b2;
        float len = length(n);
        if (!(len > 0 && std::isfinite(len))) return ng;
        n = n / len;
        return dot(n, ng) < 0 ? -n : n;
    }

    /// The medium containing point `p`: found by casting a ray to the first medium-bounding surface
    /// (a mesh whose interior and exterior media differ) and reading which side it is on.
    MediumId mediumAt(const Vec3& p) const;
    /// Ray-parameter interval [t0, t1] where the global medium exists: the scene bounds, so that a
    /// ray escaping into an unbounded fog stops at the scene's edge. Returns false if none.
    bool globalMediumInterval(const Ray& ray, float* t0, float* t1) const {
        if (m_mediumBounds.empty()) return false;
        float lo = ray.tMin, hi = ray.tMax;
        const Bounds3& b = m_mediumBounds;
        if (!clipSlab(ray.o.x, ray.d.x, b.lo.x, b.hi.x, &lo, &hi) ||
            !clipSlab(ray.o.y, ray.d.y, b.lo.y, b.hi.y, &lo, &hi) ||
            !clipSlab(ray.o.z, ray.d.z, b.lo.z, b.hi.z, &lo, &hi))
            return false;
        *t0 = lo;
        *t1 = hi;
        return true;
    }
    /// The stretch of o + t d, t in [0, tEnd] (tEnd: the next surface, or infinity), that lies in
    /// the medium the ray is in, as a segment with its own origin: {o + t0 d, d, 0, t1 - t0}.
    /// False when it is empty. Every stage that walks media starts here.
    bool mediumSegment(const Vec3& o, const Vec3& d, float tEnd, Ray* segment) const {
        float t0, t1;
        if (!globalMediumInterval(Ray{o, d, 0.0f, tEnd}, &t0, &t1) || !(t1 > t0)) return false;
        *segment = Ray{o + d * t0, d, 0.0f, t1 - t0};
        return true;
    }

    /// Origin for a ray leaving surface point `p` (normal `ng`) in direction `d`: `p` pushed to the
    /// side `d` goes by more than the rounding error of `p`, so the ray cannot hit the surface it
    /// starts on. pbrt-v4's OffsetRayOrigin: the push is the error bound projected on the normal,
    /// then each coordinate is rounded one float further away. `p` is a hit o + t dir computed in
    /// float: its error is bounded by hitPointError(p, t) (Embree's t and the product round on the
    /// scale of |o| <= |p| + t). Relative to the coordinates only: a scene scaled or moved gets
    /// the same offsets relative to its size, and no absolute length enters.
    Vec3 offsetOrigin(const Vec3& p, float tHit, const Vec3& ng, const Vec3& d) const {
        const float err = hitPointError(p, tHit);
        Vec3 offset = ng * (err * (std::abs(ng.x) + std::abs(ng.y) + std::abs(ng.z)));
        if (dot(d, ng) < 0) offset = -offset;
        Vec3 o = p + offset;
        o.x = roundAway(o.x, offset.x);
        o.y = roundAway(o.y, offset.y);
        o.z = roundAway(o.z, offset.z);
        return o;
    }
    /// offsetOrigin for a point reached by a ray of unknown length (the reference tracer's hits,
    /// points on lights): the longest ray inside the scene, its diagonal, stands for t.
    Vec3 offsetOrigin(const Vec3& p, const Vec3& ng, const Vec3& d) const {
        return offsetOrigin(p, m_sceneDiagonal, ng, d);
    }
    /// Per-coordinate bound on the float error of a hit point p = o + t dir (unit dir, t >= 0):
    /// kHitErrorUlps units in the last place of max(|p_i|) + t, the largest magnitude the
    /// intersection arithmetic saw. The worst error measured over scales 1e-3..1e6, boxes up to
    /// 1000 sizes from the origin and cameras outside them is 2.3 ulps (tests/cpu/scale_test.cpp);
    /// 64 leaves room for long thin triangles and matches the old offset at scale 1.
    static float hitPointError(const Vec3& p, float t) {
        return kHitErrorUlps * 0x1p-24f * (std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))) + t);
    }
    static constexpr float kHitErrorUlps = 64.0f;
    /// std::nextafter(v, +infinity) and std::nextafter(v, -infinity) by the float's bits, inline
    /// (the library call costs some 40 instructions): the same value for every input, zeros,
    /// infinities, subnormals and NaN included (pbrt-v4's NextFloatUp/Down, NaN passed through).
    static float nextFloatUp(float v) {
        if (std::isnan(v) || v == kInfinity) return v;
        if (v == 0.0f) return std::numeric_limits<float>::denorm_min();
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        bits = v > 0 ? bits + 1 : bits - 1;
        std::memcpy(&v, &bits, sizeof bits);
        return v;
    }
    static float nextFloatDown(float v) {
        if (std::isnan(v) || v == -kInfinity) return v;
        if (v == 0.0f) return -std::numeric_limits<float>::denorm_min();
        uint32_t bits;
        std::memcpy(&bits, &v, sizeof bits);
        bits = v > 0 ? bits - 1 : bits + 1;
        std::memcpy(&v, &bits, sizeof bits);
        return v;
    }

    const Scene& scene() const { return m_scene; }
    /// The Embree scene, for raw-throughput baselines in build/bench/tyndall_stages.
    RTCScene rtcScene() const { return m_rtcScene; }
    const std::shared_ptr<EmbreeDevice>& device() const { return m_device; }

private:
    /// One axis of globalMediumInterval: narrows [*lo, *hi] to the slab [slabLo, slabHi] of o + t d.
    /// `v` moved one float further in the direction of `offset` (pbrt-v4 NextFloatUp/Down).
    static float roundAway(float v, float offset) {
        if (offset > 0) return nextFloatUp(v);
        if (offset < 0) return nextFloatDown(v);
        return v;
    }
    static bool clipSlab(float o, float d, float slabLo, float slabHi, float* lo, float* hi) {
        float inv = 1.0f / d;
        float tn = (slabLo - o) * inv;
        float tf = (slabHi - o) * inv;
        if (tn > tf) std::swap(tn, tf);
        if (std::isnan(tn) || std::isnan(tf)) return !(o < slabLo || o > slabHi);  // parallel, inside
        *lo = std::max(*lo, tn);
        *hi = std::min(*hi, tf * 1.0000001f);
        return !(*lo > *hi);
    }

    struct TriangleNormals {
        Vec3 n[3];
    };
    /// Geometry user data of a mesh with alphaMode Mask or Blend (the filter's context).
    struct AlphaGeometry {
        const Scene* scene;
        int mesh;
    };
    static void alphaFilter(const RTCFilterFunctionNArguments* args);
    /// The hit record of `ray` from Embree's answer (t, ids, barycentrics, unnormalised Ng).
    void fillHit(const Ray& ray, float t, unsigned geomID, unsigned primID, float u, float v, const Vec3& ng,
                 SurfaceHit* hit) const {
        hit->t = t;
        hit->mesh = int(geomID);
        hit->triangle = primID;
        hit->b1 = u;
        hit->b2 = v;
        hit->p = ray.at(t);
        // Embree's Ng is cross(v1 - v0, v2 - v0): the same orientation as Scene's CCW convention.
        hit->ng = normalize(ng);
        hit->ns = shadingNormal(hit->mesh, hit->triangle, hit->b1, hit->b2, hit->ng);
    }

    const Scene& m_scene;
    std::shared_ptr<EmbreeDevice> m_device;
    RTCScene m_rtcScene = nullptr;
    float m_sceneDiagonal = 1.0f;
    bool m_everySurfaceBlocks = true;
    Bounds3 m_mediumBounds;
    /// Per mesh: the vertex normals of each triangle, packed (one cache line, no index fetch), for
    /// specular meshes with normals; empty for every other mesh.
    std::vector<std::vector<TriangleNormals>> m_shadingNormals;
    std::vector<AlphaGeometry> m_alpha;  ///< one per mesh, addressed by Embree's user pointers
};

}  // namespace tyndall
