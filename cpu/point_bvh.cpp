#include "cpu/point_bvh.h"

#include <algorithm>
#include <cmath>

#include "core/phase.h"

namespace tyndall {

namespace {

// A point's sphere of its radius: the ray records (CandidateQuery) each it passes within reach of,
// reporting no hit.
void pointBounds(const RTCBoundsFunctionArguments* args) {
    const auto* points = static_cast<const std::vector<MediumPoint>*>(args->geometryUserPtr);
    const MediumPoint& p = (*points)[args->primID];
    RTCBounds* b = args->bounds_o;
    b->lower_x = p.position.x - p.radius, b->lower_y = p.position.y - p.radius, b->lower_z = p.position.z - p.radius;
    b->upper_x = p.position.x + p.radius, b->upper_y = p.position.y + p.radius, b->upper_z = p.position.z + p.radius;
}

void pointIntersect(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    const auto* points = static_cast<const std::vector<MediumPoint>*>(args->geometryUserPtr);
    const MediumPoint& p = (*points)[args->primID];
    const RTCRay& ray = reinterpret_cast<RTCRayHit*>(args->rayhit)->ray;  // rtcIntersect1: N == 1
    const Vec3 w(p.position.x - ray.org_x, p.position.y - ray.org_y, p.position.z - ray.org_z);
    const Vec3 d(ray.dir_x, ray.dir_y, ray.dir_z);
    const float s = dot(w, d);
    if (!(s >= 0.0f && s <= ray.tfar)) return;
    const float u2 = dot(w, w) - s * s;
    if (!(u2 < p.radius * p.radius)) return;
    CandidateQuery::of(args->context).found->push_back(args->primID);
}

void pointOccluded(const RTCOccludedFunctionNArguments*) {}

}  // namespace

PointBvh::PointBvh(const EmbreeDevice& device, const std::vector<MediumPoint>& points) : m_points(points) {
    RTCDevice dev = device.get();
    m_scene = rtcNewScene(dev);
    for (const MediumPoint& p : points) m_maxRadius = std::max(m_maxRadius, p.radius);
    if (!points.empty()) {
        RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(geom, unsigned(points.size()));
        rtcSetGeometryUserData(geom, const_cast<std::vector<MediumPoint>*>(&m_points));
        rtcSetGeometryBoundsFunction(geom, pointBounds, nullptr);
        rtcSetGeometryIntersectFunction(geom, pointIntersect);
        rtcSetGeometryOccludedFunction(geom, pointOccluded);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(m_scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(m_scene);
    device.check("building the photon-point BVH");
}

PointBvh::~PointBvh() { rtcReleaseScene(m_scene); }

void PointBvh::query(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found) const {
    if (m_points.empty()) {
        found.clear();
        return;
    }
    queryCandidates(m_scene, o, d, sMax, found);
}

Rgb gatherPoints(const Scene& scene, const PointBvh& bvh, MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                 int maxSegment, float tanStart, float tanEnd, std::vector<uint32_t>& scratch) {
    // The query reaches past a bounded end by the widest point's reach; each point by its own.
    const float before = tanStart * bvh.maxRadius(), after = tanEnd * bvh.maxRadius();
    bvh.query(o - d * before, d, sMax + before + after, scratch);
    const Medium& med = scene.media[medium];
    const Rgb st = med.sigmaT();
    Rgb sum;
    for (uint32_t i : scratch) {
        const MediumPoint& p = bvh.points()[i];
        if (p.medium != medium || (maxSegment > 0 && int(p.segment) > maxSegment)) continue;
        const Vec3 w = p.position - o;
        const float s = dot(w, d);
        if (s < -tanStart * p.radius || s > sMax + tanEnd * p.radius) continue;
        const float u2 = std::max(0.0f, dot(w, w) - s * s);
        const float k = pointKernel(u2, p.radius) * hgPhase(-dot(d, p.dir), med.g);
        const float at = std::clamp(s, 0.0f, sMax);
        const Rgb tr(std::exp(-st.r * at), std::exp(-st.g * at), std::exp(-st.b * at));
        sum += p.power * tr * k;
    }
    return sum;
}

}  // namespace tyndall
