#include "cpu/beam_bvh.h"

#include <algorithm>

namespace tyndall {

namespace {

// Extends Embree's context (first member) with what the callbacks need.
struct GatherContext {
    RTCIntersectContext rtc;
    const std::vector<PhotonBeam>* beams;
    std::vector<BeamHitRecord>* hits;
    Vec3 o, d;
    float sMax;
};

void recordIfHit(GatherContext* ctx, unsigned primID) {
    BeamRayHit h;
    if (intersectBeamRay(ctx->o, ctx->d, ctx->sMax, (*ctx->beams)[primID], &h)) ctx->hits->push_back({primID, h});
}

void beamBounds(const RTCBoundsFunctionArguments* args) {
    const auto& beams = *static_cast<const std::vector<PhotonBeam>*>(args->geometryUserPtr);
    const PhotonBeam& b = beams[args->primID];
    Vec3 e = b.origin + b.dir * b.tMax;
    Vec3 lo = vmin(b.origin, e) - Vec3(b.radius), hi = vmax(b.origin, e) + Vec3(b.radius);
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

void curveFilter(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    recordIfHit(reinterpret_cast<GatherContext*>(args->context), RTCHitN_primID(args->hit, args->N, 0));
    args->valid[0] = 0;
}

}  // namespace

BeamBvh::BeamBvh(const EmbreeDevice& device, const std::vector<PhotonBeam>& beams, Kind kind)
    : m_beams(beams), m_kind(kind) {
    RTCDevice dev = device.get();
    m_scene = rtcNewScene(dev);
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    if (beams.empty()) {
        rtcCommitScene(m_scene);
        return;
    }
    for (const PhotonBeam& b : beams) m_maxRadius = std::max(m_maxRadius, b.radius);
    RTCGeometry geom;
    if (kind == Kind::UserGeometry) {
        geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, unsigned(beams.size()));
        rtcSetGeometryUserData(geom, const_cast<std::vector<PhotonBeam>*>(&beams));
        rtcSetGeometryBoundsFunction(geom, beamBounds, const_cast<std::vector<PhotonBeam>*>(&beams));
        rtcSetGeometryIntersectFunction(geom, beamIntersect);
        rtcSetGeometryOccludedFunction(geom, beamOccluded);
    } else {
        geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_FLAT_LINEAR_CURVE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                              4 * sizeof(float), 2 * beams.size()));
        auto* idx = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), beams.size()));
        for (size_t i = 0; i < beams.size(); ++i) {
            const PhotonBeam& b = beams[i];
            Vec3 e = b.origin + b.dir * b.tMax;
            float* p = v + 8 * i;
            p[0] = b.origin.x, p[1] = b.origin.y, p[2] = b.origin.z, p[3] = b.radius;
            p[4] = e.x, p[5] = e.y, p[6] = e.z, p[7] = b.radius;
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
    hits.clear();
    if (m_beams.empty() || !(sMax > 0)) return;
    GatherContext ctx;
    rtcInitIntersectContext(&ctx.rtc);
    ctx.beams = &m_beams;
    ctx.hits = &hits;
    ctx.o = o;
    ctx.d = d;
    ctx.sMax = sMax;
    // Embree's flat-curve intersector never reports a curve whose hit lies within about two radii
    // of the ray origin, so the curve query starts `lead` before o (the filter's exact test still
    // measures from o, so nothing outside [0, sMax] gets in). User primitives need no lead.
    const float lead = m_kind == Kind::FlatCurves ? 4.0f * m_maxRadius : 0.0f;
    const Vec3 start = o - d * lead;
    RTCRayHit rh;
    rh.ray.org_x = start.x;
    rh.ray.org_y = start.y;
    rh.ray.org_z = start.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    // Curves only report hits up to tfar; user primitives test s <= sMax themselves. Beams reach
    // a little past the segment end through their radius, hence the margin.
    rh.ray.tfar = std::isfinite(sMax) ? lead + sMax * 1.0001f + 1e-6f : kInfinity;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.flags = 0;
    rh.ray.time = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &ctx.rtc, &rh);
    std::sort(hits.begin(), hits.end(), [](const BeamHitRecord& a, const BeamHitRecord& b) { return a.beam < b.beam; });
    hits.erase(std::unique(hits.begin(), hits.end(),
                           [](const BeamHitRecord& a, const BeamHitRecord& b) { return a.beam == b.beam; }),
               hits.end());
}

}  // namespace tyndall
