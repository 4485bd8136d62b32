#include "cpu/surface_boundary.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace tyndall {

namespace {

/// A vertex position as a key: its bits, with -0 made +0 (the same point either way).
std::array<uint32_t, 3> positionKey(const Vec3& p) {
    std::array<uint32_t, 3> k;
    const float c[3] = {p.x + 0.0f, p.y + 0.0f, p.z + 0.0f};
    std::memcpy(k.data(), c, sizeof(c));
    return k;
}

bool storesDiffusePhotons(const Material& m) {
    return m.type == MaterialType::Diffuse || m.type == MaterialType::Plastic;
}

struct EdgeRecord {
    std::array<uint32_t, 6> key;  // the two endpoints' keys, smaller first
    uint32_t mesh, triangle, corner;
    uint32_t face;  // the triangle's index over all photon-holding meshes
    Vec3 normal;
};

/// Union-find over triangles: the sheets of triangles joined across edges the gather continues
/// over, each remembering whether two of its neighbours are wound opposite ways.
class Sheets {
public:
    explicit Sheets(size_t n) : m_parent(n), m_mixed(n, 0) {
        for (size_t i = 0; i < n; ++i) m_parent[i] = uint32_t(i);
    }
    uint32_t find(uint32_t i) {
        while (m_parent[i] != i) i = m_parent[i] = m_parent[m_parent[i]];
        return i;
    }
    void join(uint32_t a, uint32_t b, bool opposite) {
        a = find(a), b = find(b);
        if (a != b) m_parent[b] = a, m_mixed[a] |= m_mixed[b];
        m_mixed[a] |= opposite;
    }
    bool mixed(uint32_t i) { return m_mixed[find(i)] != 0; }

private:
    std::vector<uint32_t> m_parent;
    std::vector<uint8_t> m_mixed;
};

/// The layer probe (surface_boundary.h, "Layered surfaces") at point p of a half-edge's plane,
/// just past the edge: for each side of the plane, the first surface a ray meets going from
/// `lift` in front of p through the plane (glass and interfaces let it on: light reaches what is
/// behind them). When that surface holds diffuse photons and passes the gather's normal test
/// against n, its photons there lie |t - lift| off the plane; the smaller such offset of the two
/// sides, infinity when neither has one.
float layerOffsetAt(const Scene& scene, const EmbreeScene& rt, const Vec3& p, const Vec3& n, float lift) {
    float best = kInfinity;
    for (float side : {1.0f, -1.0f}) {
        Ray ray{p + n * (side * lift), n * -side, 0.0f, kInfinity};
        for (int k = 0; k < 8; ++k) {
            SurfaceHit hit;
            if (!rt.intersect(ray, &hit)) break;
            const Material& m = scene.materials[scene.meshes[size_t(hit.mesh)].material];
            if (m.isTransmissive()) {
                ray.tMin = std::nextafter(hit.t, kInfinity);
                continue;
            }
            if (storesDiffusePhotons(m) && std::abs(dot(hit.ng, n)) >= SurfaceBoundary::kNormalAgreement)
                best = std::min(best, std::abs(hit.t - lift));
            break;
        }
    }
    return best;
}

struct QueryState {
    std::vector<uint32_t>* candidates;
};

bool collectCandidate(RTCPointQueryFunctionArguments* args) {
    static_cast<QueryState*>(args->userPtr)->candidates->push_back(args->primID);
    return false;
}

}  // namespace

SurfaceBoundary::PlaneSegment::PlaneSegment(double ax, double ay, double bx, double by)
    : m_h(0), m_ta(0), m_tb(0), m_atA(0), m_atB(0), m_tanA(0), m_tanB(0), m_atans(false), m_hasTanA(false),
      m_hasTanB(false) {
    const double dx = bx - ax, dy = by - ay;
    const double len = std::sqrt(dx * dx + dy * dy);
    m_line = len > 0;
    if (!m_line) return;
    const double ux = dx / len, uy = dy / len;
    m_h = std::abs(ax * uy - ay * ux);  // distance from the centre to the segment's line
    m_ta = ax * ux + ay * uy, m_tb = bx * ux + by * uy;  // along the line from the foot, ta < tb
}

double SurfaceBoundary::PlaneSegment::mass(double r) {
    if (!m_line || !(r > 0) || m_h >= r) return 0.0;
    const double h = m_h, ta = m_ta, tb = m_tb;
    const double kInv2Pi = 0.5 / M_PI;
    if (h < 1e-9 * r) {
        // The centre on the line: beyond it is the half-disc, of which the segment's angle holds
        // a quarter-turn on each side of the foot it reaches past.
        const double lo = ta < 0 ? -0.5 * M_PI : 0.0, hi = tb > 0 ? 0.5 * M_PI : 0.0;
        return hi > lo ? (hi - lo) * kInv2Pi : 0.0;
    }
    // In polar angle phi from the foot, the line lies at h / cos(phi); beyond it up to r the
    // kernel's mass per radian is 1/(2 pi) - G(h sec phi), G(s) = (s^2/r^2 - s^4/(2 r^4)) / pi,
    // zero past phi_c = acos(h / r). Its antiderivative:
    //   F(phi) = phi/(2 pi) - (eta^2 tan phi - eta^4/2 (tan phi + tan^3 phi / 3)) / pi,  eta = h/r,
    // from lo = max(atan(ta / h), -phi_c) to hi = min(atan(tb / h), phi_c). The ends' angles and
    // tangents do not depend on r (kept); tan(-phi_c) is -tan(phi_c) (libm's tan is odd bit for
    // bit: it reduces |phi| and restores the sign).
    const double eta = h / r, phiC = std::acos(eta);
    if (!m_atans) m_atA = std::atan(ta / h), m_atB = std::atan(tb / h), m_atans = true;
    const bool clipLo = m_atA < -phiC, clipHi = phiC < m_atB;  // std::max's and std::min's tests
    const double lo = clipLo ? -phiC : m_atA, hi = clipHi ? phiC : m_atB;
    if (!(hi > lo)) return 0.0;
    const double tanC = clipLo || clipHi ? std::tan(phiC) : 0.0;
    if (!clipLo && !m_hasTanA) m_tanA = std::tan(m_atA), m_hasTanA = true;
    if (!clipHi && !m_hasTanB) m_tanB = std::tan(m_atB), m_hasTanB = true;
    const double tLo = clipLo ? -tanC : m_tanA, tHi = clipHi ? tanC : m_tanB;
    const double e2 = eta * eta, e4 = e2 * e2;
    auto F = [&](double phi, double t) { return phi * kInv2Pi - (e2 * t - 0.5 * e4 * (t + t * t * t / 3.0)) / M_PI; };
    return std::max(0.0, F(hi, tHi) - F(lo, tLo));
}

double SurfaceBoundary::massBeyondSegment(double ax, double ay, double bx, double by, double r) {
    return PlaneSegment(ax, ay, bx, by).mass(r);
}

SurfaceBoundary::SurfaceBoundary(const Scene& scene, const EmbreeScene& rt, Layers layers) {
    static std::atomic<uint64_t> instances{0};
    m_id = ++instances;
    RTCDevice device = rt.device()->get();
    // Every edge of every photon-holding triangle, keyed by its endpoints' positions.
    std::vector<EdgeRecord> records;
    uint32_t faces = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const TriangleMesh& mesh = scene.meshes[m];
        if (!storesDiffusePhotons(scene.materials[mesh.material])) continue;
        for (size_t t = 0; t < mesh.triangleCount(); ++t) {
            const Vec3 n = mesh.geometricNormal(t);
            const float len = length(n);
            if (!(len > 0) || !std::isfinite(len)) continue;
            const uint32_t face = faces++;
            for (uint32_t k = 0; k < 3; ++k) {
                auto ka = positionKey(mesh.vertex(t, int(k))), kb = positionKey(mesh.vertex(t, int((k + 1) % 3)));
                if (kb < ka) std::swap(ka, kb);
                EdgeRecord& e = records.emplace_back();
                std::copy(ka.begin(), ka.end(), e.key.begin());
                std::copy(kb.begin(), kb.end(), e.key.begin() + 3);
                e.mesh = uint32_t(m), e.triangle = uint32_t(t), e.corner = k, e.face = face;
                e.normal = n / len;
            }
        }
    }
    std::sort(records.begin(), records.end(), [](const EdgeRecord& a, const EdgeRecord& b) {
        if (a.key != b.key) return a.key < b.key;
        if (a.mesh != b.mesh) return a.mesh < b.mesh;
        if (a.triangle != b.triangle) return a.triangle < b.triangle;
        return a.corner < b.corner;
    });
    // Sheets first (an edge's winding is judged over its whole sheet), then the feature half-edges.
    Sheets sheets(faces);
    auto continues = [](const EdgeRecord& a, const EdgeRecord& b) {
        return std::abs(dot(a.normal, b.normal)) >= kNormalAgreement;
    };
    std::vector<std::pair<size_t, size_t>> groups;  // [begin, end) of records sharing an edge
    for (size_t i = 0; i < records.size();) {
        size_t j = i;
        while (j < records.size() && records[j].key == records[i].key) ++j;
        groups.emplace_back(i, j);
        for (size_t a = i; a < j; ++a)
            for (size_t b = a + 1; b < j; ++b)
                if (continues(records[a], records[b]))
                    sheets.join(records[a].face, records[b].face, dot(records[a].normal, records[b].normal) < 0);
        i = j;
    }
    for (auto [i, j] : groups) {
        for (size_t a = i; a < j; ++a) {
            bool continued = false;  // a neighbour across the edge whose photons the gather takes
            for (size_t b = i; b < j && !continued; ++b) continued = b != a && continues(records[a], records[b]);
            if (continued) continue;
            const EdgeRecord& r = records[a];
            const TriangleMesh& mesh = scene.meshes[r.mesh];
            const Vec3 p0 = mesh.vertex(r.triangle, int(r.corner)), p1 = mesh.vertex(r.triangle, int((r.corner + 1) % 3));
            const Vec3 p2 = mesh.vertex(r.triangle, int((r.corner + 2) % 3));
            Vec3 inward = cross(r.normal, p1 - p0);
            const float il = length(inward);
            if (!(il > 0)) continue;
            inward = inward / il;
            if (dot(p2 - p0, inward) < 0) inward = -inward;
            m_edges.push_back({p0, p1, r.normal, inward, kInfinity, sheets.mixed(r.face)});
        }
    }
    // The layer probe, at 1/6, 1/2 and 5/6 along each edge, a ten-thousandth of the scene's
    // diagonal past it (and as far off its plane to start), plus the float error of the points.
    if (layers == Layers::Probe) {
        const Vec3 diag = scene.bounds.diagonal();
        const float sceneScale = std::isfinite(length(diag)) ? length(diag) : 0.0f;
        const float maxAbs = std::max({std::abs(scene.bounds.lo.x), std::abs(scene.bounds.lo.y), std::abs(scene.bounds.lo.z),
                                       std::abs(scene.bounds.hi.x), std::abs(scene.bounds.hi.y), std::abs(scene.bounds.hi.z)});
        const float step = 1e-4f * sceneScale + 256.0f * FLT_EPSILON * (std::isfinite(maxAbs) ? maxAbs : 0.0f);
        for (HalfEdge& e : m_edges) {
            float offset = 0;
            for (float u : {1.0f / 6.0f, 0.5f, 5.0f / 6.0f}) {
                const Vec3 p = e.a + (e.b - e.a) * u - e.inward * step;
                offset = std::max(offset, layerOffsetAt(scene, rt, p, e.normal, step));
            }
            e.layerOffset = offset;
        }
    }

    // The pre-check's grid over where gather points lie: the photon-holding triangles.
    Bounds3 domain;
    for (const TriangleMesh& mesh : scene.meshes)
        if (storesDiffusePhotons(scene.materials[mesh.material]))
            for (size_t t = 0; t < mesh.triangleCount(); ++t)
                for (int k = 0; k < 3; ++k) domain.extend(mesh.vertex(t, k));
    std::vector<Vec3> ends0(m_edges.size()), ends1(m_edges.size());
    for (size_t i = 0; i < m_edges.size(); ++i) ends0[i] = m_edges[i].a, ends1[i] = m_edges[i].b;
    m_clearance = EdgeClearanceGrid(ends0, ends1, domain);
    if (m_edges.empty()) return;

    m_rtcScene = rtcNewScene(device);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(m_edges.size()));
    rtcSetGeometryUserData(geom, this);
    rtcSetGeometryBoundsFunction(
        geom,
        [](const RTCBoundsFunctionArguments* args) {
            const HalfEdge& e = static_cast<const SurfaceBoundary*>(args->geometryUserPtr)->m_edges[args->primID];
            RTCBounds* b = args->bounds_o;
            b->lower_x = std::min(e.a.x, e.b.x), b->lower_y = std::min(e.a.y, e.b.y), b->lower_z = std::min(e.a.z, e.b.z);
            b->upper_x = std::max(e.a.x, e.b.x), b->upper_y = std::max(e.a.y, e.b.y), b->upper_z = std::max(e.a.z, e.b.z);
        },
        nullptr);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m_rtcScene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(m_rtcScene);
}

SurfaceBoundary::~SurfaceBoundary() {
    if (m_rtcScene) rtcReleaseScene(m_rtcScene);
}

void SurfaceBoundary::query(const Vec3& x, float r, std::vector<uint32_t>* out) const {
    RTCPointQuery query;
    query.x = x.x, query.y = x.y, query.z = x.z, query.time = 0.0f, query.radius = r;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    QueryState state{out};
    rtcPointQuery(m_rtcScene, &query, &context, collectCandidate, &state);
    std::sort(out->begin(), out->end());  // Embree's traversal order is not fixed
}

float SurfaceBoundary::halfOctaveAbove(float r) {
    uint32_t bits;
    std::memcpy(&bits, &r, sizeof bits);
    const uint32_t exponent = bits >> 23;  // r > 0: no sign bit
    if (exponent == 0 || exponent >= 254) {  // subnormal, or the top binade, infinity and NaN
        int e;
        const float m = std::frexp(r, &e);  // r = m 2^e, m in [0.5, 1)
        return std::ldexp(m < 0.70710677f ? 0.70710683f : 1.0f, e);
    }
    // frexp's m carries r's mantissa under the exponent of 0.5; ldexp of 0.70710683f (also in
    // [0.5, 1)) or of 1 by e puts r's exponent, or the next, on them.
    constexpr uint32_t kMantissa = (1u << 23) - 1, kHalfExponent = 126u << 23;
    const uint32_t m = (bits & kMantissa) | kHalfExponent;
    uint32_t limit, root;
    const float lo = 0.70710677f, rootHalf = 0.70710683f;
    std::memcpy(&limit, &lo, sizeof limit);
    std::memcpy(&root, &rootHalf, sizeof root);
    const uint32_t key = m < limit ? (exponent << 23) | (root & kMantissa) : (exponent + 1) << 23;
    float out;
    std::memcpy(&out, &key, sizeof out);
    return out;
}

const std::vector<uint32_t>* SurfaceBoundary::facingCandidates(const Vec3& x, const Vec3& ng, float r,
                                                               float* reach) const {
    // The candidates of x's pre-check cell at this radius, cached per thread (surface_boundary.h),
    // with those that pass the normal test for the last normal asked for; outside the grid, x's own.
    struct CellCandidates {
        uint64_t owner = 0;
        size_t cell = 0;
        float r = 0;
        std::vector<uint32_t> list;
        Vec3 ng = Vec3(kInfinity);         ///< the normal `facing` holds list's half-edges for
        std::vector<uint32_t> facing;
    };
    constexpr int kCached = 4;
    thread_local CellCandidates cache[kCached];
    thread_local int nextSlot = 0;
    thread_local CellCandidates own;
    CellCandidates* candidates = nullptr;
    size_t cell;
    Vec3 centre;
    float cellReach;
    if (m_clearance.cellOf(x, &cell, &centre, &cellReach)) {
        // Keyed by the half octave above r (photons with the cone carry many radii): the cell's
        // list holds the half-edges within that radius, a superset of those within r.
        const float rKey = halfOctaveAbove(r);
        for (CellCandidates& c : cache)
            if (c.owner == m_id && c.cell == cell && c.r == rKey) candidates = &c;
        if (!candidates) {
            CellCandidates& c = cache[nextSlot];
            nextSlot = (nextSlot + 1) % kCached;
            c.owner = m_id, c.cell = cell, c.r = rKey;
            c.list.clear();
            c.ng = Vec3(kInfinity);
            query(centre, rKey + cellReach, &c.list);
            candidates = &c;
        }
        *reach = rKey;
    } else {
        own.list.clear();
        own.ng = Vec3(kInfinity);
        query(x, r, &own.list);
        candidates = &own;
        *reach = r;
    }
    if (candidates->list.empty()) return nullptr;
    // Another plane's edge; on a sheet of mixed winding either face of x's plane is x's.
    if (std::memcmp(&candidates->ng, &ng, sizeof ng) != 0) {
        candidates->facing.clear();
        for (uint32_t i : candidates->list) {
            const HalfEdge& e = m_edges[i];
            if ((e.mixedWinding ? std::abs(dot(e.normal, ng)) : dot(e.normal, ng)) >= kNormalAgreement)
                candidates->facing.push_back(i);
        }
        candidates->ng = ng;
    }
    return &candidates->facing;
}

bool SurfaceBoundary::nearEdge(const HalfEdge& e, const Vec3& x, const Vec3& ng, const Frame& frame, NearEdge* out) {
    if (dot(x - e.a, e.inward) < 0) return false;  // x is not on the surface it bounds
    // Where it passes closest to x: near x's plane there, the photons of that surface are in the
    // gather's slab (cuts()).
    const Vec3 ab = e.b - e.a;
    const float s = std::clamp(dot(x - e.a, ab) / dot(ab, ab), 0.0f, 1.0f);
    const Vec3 c = e.a + ab * s - x;
    const Vec3 a = frame.toLocal(e.a - x), b = frame.toLocal(e.b - x);
    *out = {dot(c, c), std::abs(dot(c, ng)), e.layerOffset, PlaneSegment(a.x, a.y, b.x, b.y)};
    return true;
}

float SurfaceBoundary::coverage(const Vec3& x, const Vec3& ng, float r) const {
    if (!m_rtcScene || !(r > 0) || r <= m_clearance.clearance(x)) return 1.0f;
    float reach;
    const std::vector<uint32_t>* facing = facingCandidates(x, ng, r, &reach);
    if (!facing) return 1.0f;
    const Frame frame(ng);
    double missing = 0;
    NearEdge near;
    for (uint32_t i : *facing)
        if (nearEdge(m_edges[i], x, ng, frame, &near) && near.cuts(r)) missing += near.segment.mass(r);
    return float(std::clamp(1.0 - missing, double(kMinCoverage), 1.0));
}

bool SurfaceBoundary::AtPoint::prepare(float r) {
    if (m_nearRadius > 0 && r <= m_nearRadius) return !m_overflow;
    m_nearCount = 0;
    m_overflow = false;
    const std::vector<uint32_t>* facing = m_b.facingCandidates(m_x, m_ng, r, &m_nearRadius);
    if (!facing) return true;
    const Frame frame(m_ng);
    for (uint32_t i : *facing) {
        NearEdge near;
        if (!nearEdge(m_b.m_edges[i], m_x, m_ng, frame, &near)) continue;
        if (m_nearCount == kNear) return !(m_overflow = true);
        m_near[m_nearCount++] = near;
    }
    return true;
}

float SurfaceBoundary::AtPoint::at(float r) {
    if (!m_b.m_rtcScene || !(r > 0) || r <= m_clear) return 1.0f;
    if (!prepare(r)) return m_b.coverage(m_x, m_ng, r);
    double missing = 0;
    for (int k = 0; k < m_nearCount; ++k)
        if (m_near[k].cuts(r)) missing += m_near[k].segment.mass(r);
    return float(std::clamp(1.0 - missing, double(kMinCoverage), 1.0));
}

}  // namespace tyndall
