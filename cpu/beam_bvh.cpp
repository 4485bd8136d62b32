#include "cpu/beam_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tyndall {

namespace {

// The margin the ribbons are widened by, in largest beam radii (BeamQueryCache). Wider ribbons
// let more segments reuse a traversal's list and make each list longer (the exact test runs over
// more candidates): at 1080p (the default scene) 3 halved the traversals of 2 (10.9 k against
// 23 k a pass) and took 11% fewer of the beam queries' instructions; 4 took fewer than 2 and more
// than 3, 6 and 8 more than 2 (docs/performance.md, "Where a 1080p pass goes").
constexpr float kReach = 3.0f;

// Extends Embree's context (first member) with what the callbacks need.
struct GatherContext {
    RTCIntersectContext rtc;
    const std::vector<PhotonBeam>* beams;
    const std::vector<BeamBvh::Piece>* pieces;
    std::vector<BeamHitRecord>* hits;        // user geometry: exact hits
    std::vector<uint32_t>* candidates;       // flat curves: beams whose widened ribbon the ray meets
    Vec3 o, d;
    float sMax;
};

void recordIfHit(GatherContext* ctx, unsigned primID) {
    const BeamBvh::Piece& piece = (*ctx->pieces)[primID];
    const PhotonBeam& beam = (*ctx->beams)[piece.beam];
    BeamRayHit h;
    if (!intersectBeamRay(ctx->o, ctx->d, ctx->sMax, beam, &h)) return;
    // Half-open pieces: the one holding t_v reports the beam (the last one is closed).
    if (h.t < piece.t0 || (h.t >= piece.t1 && piece.t1 < beam.tMax)) return;
    ctx->hits->push_back({piece.beam, h});
}

void beamBounds(const RTCBoundsFunctionArguments* args) {
    const auto* bvh = static_cast<const BeamBvh*>(args->geometryUserPtr);
    const BeamBvh::Piece& piece = bvh->pieces()[args->primID];
    const PhotonBeam& b = bvh->beams()[piece.beam];
    Vec3 s = b.origin + b.dir * piece.t0, e = b.origin + b.dir * piece.t1;
    Vec3 lo = vmin(s, e) - Vec3(b.radius), hi = vmax(s, e) + Vec3(b.radius);
    args->bounds_o->lower_x = lo.x;
    args->bounds_o->lower_y = lo.y;
    args->bounds_o->lower_z = lo.z;
    args->bounds_o->upper_x = hi.x;
    args->bounds_o->upper_y = hi.y;
    args->bounds_o->upper_z = hi.z;
}

// Never reports a hit: records the beam and lets traversal go on to find all of them.
void beamIntersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    recordIfHit(reinterpret_cast<GatherContext*>(args->context), args->primID);
}

void beamOccluded(const RTCOccludedFunctionNArguments*) {}

// Records the piece's beam as a candidate and rejects the hit so traversal goes on.
void curveFilter(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    auto* ctx = reinterpret_cast<GatherContext*>(args->context);
    const uint32_t beam = (*ctx->pieces)[RTCHitN_primID(args->hit, args->N, 0)].beam;
    if (ctx->candidates->empty() || ctx->candidates->back() != beam) ctx->candidates->push_back(beam);
    args->valid[0] = 0;
}

// Sorts `beams` (indices below beamCount) ascending, each once: through a bitmap of the beams where
// it is small beside the list (the sort took ~25 instructions a candidate), else by sorting.
void sortUniqueBeams(std::vector<uint32_t>& beams, size_t beamCount) {
    const size_t words = (beamCount + 63) / 64;
    if (words > 4 * beams.size()) {
        std::sort(beams.begin(), beams.end());
        beams.erase(std::unique(beams.begin(), beams.end()), beams.end());
        return;
    }
    thread_local std::vector<uint64_t> bits;
    bits.assign(words, 0);
    for (uint32_t b : beams) bits[b >> 6] |= uint64_t(1) << (b & 63);
    beams.clear();
    for (size_t w = 0; w < words; ++w)
        for (uint64_t m = bits[w]; m; m &= m - 1) beams.push_back(uint32_t(w * 64 + size_t(__builtin_ctzll(m))));
}

// |p - segment [a, b]|^2.
float distance2ToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
    const Vec3 ab = b - a, ap = p - a;
    const float len2 = dot(ab, ab);
    const float t = len2 > 0.0f ? std::clamp(dot(ap, ab) / len2, 0.0f, 1.0f) : 0.0f;
    const Vec3 q = ap - ab * t;
    return dot(q, q);
}

}  // namespace

int BeamBvh::piecesFor(uint64_t queries, size_t beams) {
    if (beams == 0) return 1;
    return int(std::clamp(2.5 * double(queries) / double(beams), 1.0, double(kMaxPieces)));
}

BeamBvh::BeamBvh(const EmbreeDevice& device, const std::vector<PhotonBeam>& beams, Kind kind, float pieceLength,
                 int maxPieces, float usualRadius)
    : m_beams(beams), m_kind(kind) {
    // Splitting beyond kMaxPieces gains little on queries but makes the per-pass build dominate
    // once the radius (and so the default piece length) has shrunk by orders of magnitude.
    const float cap = float(std::clamp(maxPieces, 1, kMaxPieces));
    for (const PhotonBeam& b : beams) m_maxRadius = std::max(m_maxRadius, b.radius);
    const float usual = usualRadius > 0 ? std::min(usualRadius, m_maxRadius) : m_maxRadius;
    if (kind == Kind::FlatCurves) m_reach = kReach * usual;
    if (pieceLength <= 0) pieceLength = 16.0f * usual;
    for (uint32_t i = 0; i < beams.size(); ++i) {
        const PhotonBeam& b = beams[i];
        uint32_t n = std::isfinite(pieceLength) && pieceLength > 0
                         ? uint32_t(std::min(cap, std::max(1.0f, std::ceil(b.tMax / pieceLength))))
                         : 1u;
        for (uint32_t k = 0; k < n; ++k)
            m_pieces.push_back({i, b.tMax * float(k) / float(n), k + 1 == n ? b.tMax : b.tMax * float(k + 1) / float(n)});
    }
    RTCDevice dev = device.get();
    m_scene = rtcNewScene(dev);
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    if (beams.empty()) {
        rtcCommitScene(m_scene);
        return;
    }
    RTCGeometry geom;
    if (kind == Kind::UserGeometry) {
        geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, unsigned(m_pieces.size()));
        rtcSetGeometryUserData(geom, this);
        rtcSetGeometryBoundsFunction(geom, beamBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, beamIntersect);
        rtcSetGeometryOccludedFunction(geom, beamOccluded);
    } else {
        geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                              4 * sizeof(float), 2 * m_pieces.size()));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), m_pieces.size()));
        for (size_t i = 0; i < m_pieces.size(); ++i) {
            const PhotonBeam& b = beams[m_pieces[i].beam];
            Vec3 s = b.origin + b.dir * m_pieces[i].t0, e = b.origin + b.dir * m_pieces[i].t1;
            float* p = v + 8 * i;
            // The ribbon is approximate: over-cover, filter exactly; widened by the reach so that
            // one traversal serves the segments near its own (BeamQueryCache).
            const float r = 1.1f * b.radius + m_reach;
            p[0] = s.x, p[1] = s.y, p[2] = s.z, p[3] = r;
            p[4] = e.x, p[5] = e.y, p[6] = e.z, p[7] = r;
            idx[i] = unsigned(2 * i);
        }
        rtcSetGeometryIntersectFilterFunction(geom, curveFilter);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometry(m_scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(m_scene);
    device.check("building the photon-beam BVH");
}

BeamBvh::~BeamBvh() { rtcReleaseScene(m_scene); }

void BeamBvh::query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const {
    BeamQueryCache cache;
    query(o, d, sMax, hits, cache);
}

void BeamBvh::query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits,
                    BeamQueryCache& cache) const {
    hits.clear();
    if (m_beams.empty() || !(sMax > 0)) return;
    if (m_kind == Kind::UserGeometry) {
        traceUserGeometry(o, d, sMax, hits);
        return;
    }
    const Vec3 e = o + d * sMax;
    // Within 0.9 reach, not reach: room for the rounding of the distances and of Embree's test.
    const float near2 = (0.9f * m_reach) * (0.9f * m_reach);
    if (std::isfinite(sMax)) {
        for (int i = 0; i < cache.m_used; ++i) {
            const BeamQueryCache::Entry& c = cache.m_entries[i];
            if (distance2ToSegment(o, c.a, c.b) <= near2 && distance2ToSegment(e, c.a, c.b) <= near2) {
                scanBeamHits(c.scan, o, d, sMax, hits);
                cache.m_reused++;
                return;
            }
        }
    }
    BeamQueryCache::Entry& c = cache.m_entries[cache.m_next];
    cache.m_next = (cache.m_next + 1) % BeamQueryCache::kEntries;
    cache.m_used = std::min(cache.m_used + 1, BeamQueryCache::kEntries);
    candidates(o, d, sMax, c.beams);
    c.scan.assign(m_beams, c.beams);
    scanBeamHits(c.scan, o, d, sMax, hits);
    if (std::isfinite(sMax)) {
        c.a = o;
        c.b = e;
    } else {
        c.a = c.b = Vec3(kInfinity);  // never reused
    }
}

namespace {
RTCRayHit traversalRay(const Vec3& o, const Vec3& d, float sMax, float back, float margin) {
    RTCRayHit rh;
    rh.ray.org_x = o.x - d.x * back;
    rh.ray.org_y = o.y - d.y * back;
    rh.ray.org_z = o.z - d.z * back;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::isfinite(sMax) ? back + sMax * 1.0001f + margin + 1e-6f : kInfinity;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
}
}  // namespace

void BeamBvh::candidates(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& beams) const {
    beams.clear();
    GatherContext ctx;
    rtcInitIntersectContext(&ctx.rtc);
    ctx.beams = &m_beams;
    ctx.pieces = &m_pieces;
    ctx.hits = nullptr;
    ctx.candidates = &beams;
    ctx.o = o;
    ctx.d = d;
    ctx.sMax = sMax;
    // Embree's curve intersector ignores hits within about a ribbon width of the ray origin, so
    // the traversal ray starts `back` earlier; curves only report hits up to tfar, and beams reach
    // a little past the segment end through their radius, hence the margin.
    const float width = 1.1f * m_maxRadius + m_reach;
    RTCRayHit rh = traversalRay(o, d, sMax, 4.0f * width, 2.0f * width);
    rtcIntersect1(m_scene, &ctx.rtc, &rh);
    sortUniqueBeams(beams, m_beams.size());
}

void BeamBvh::traceUserGeometry(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const {
    GatherContext ctx;
    rtcInitIntersectContext(&ctx.rtc);
    ctx.beams = &m_beams;
    ctx.pieces = &m_pieces;
    ctx.hits = &hits;
    ctx.candidates = nullptr;
    ctx.o = o;
    ctx.d = d;
    ctx.sMax = sMax;
    // User primitives test s <= sMax themselves.
    RTCRayHit rh = traversalRay(o, d, sMax, 0.0f, 2.0f * m_maxRadius);
    rtcIntersect1(m_scene, &ctx.rtc, &rh);
    std::sort(hits.begin(), hits.end(), [](const BeamHitRecord& a, const BeamHitRecord& b) { return a.beam < b.beam; });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const BeamHitRecord& a, const BeamHitRecord& b) { return a.beam == b.beam; }),
               hits.end());
}

}  // namespace tyndall
