#include "cpu/plane_bvh.h"

#include <algorithm>

namespace tyndall {

namespace {

// Records each plane the ray meets in the query's list (CandidateQuery) and rejects the hit, so
// that the ray goes on.
void recordPlaneCandidate(const RTCFilterFunctionNArguments* args) {
    if (!args->valid[0]) return;
    CandidateQuery::of(args->context).found->push_back(RTCHitN_primID(args->hit, args->N, 0));
    args->valid[0] = 0;
}

}  // namespace

PlaneBvh::PlaneBvh(const EmbreeDevice& device, const std::vector<PhotonPlane>& planes) : m_planes(planes) {
    RTCDevice dev = device.get();
    m_scene = rtcNewScene(dev);
    if (!planes.empty()) {
        RTCGeometry geom = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_QUAD);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), 4 * planes.size()));
        auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                                                   4 * sizeof(unsigned), planes.size()));
        for (size_t i = 0; i < planes.size(); ++i) {
            const PhotonPlane& p = planes[i];
            const Vec3 e1 = p.dir1 * p.len1, e2 = p.dir2 * p.len2;
            const Vec3 corners[4] = {p.origin, p.origin + e1, p.origin + e1 + e2, p.origin + e2};
            for (int k = 0; k < 4; ++k) {
                float* c = v + 3 * (4 * i + size_t(k));
                c[0] = corners[k].x, c[1] = corners[k].y, c[2] = corners[k].z;
                idx[4 * i + size_t(k)] = unsigned(4 * i + size_t(k));
            }
        }
        rtcSetGeometryIntersectFilterFunction(geom, recordPlaneCandidate);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(m_scene, geom);
        rtcReleaseGeometry(geom);
    }
    rtcCommitScene(m_scene);
    device.check("building the photon-plane BVH");
}

PlaneBvh::~PlaneBvh() { rtcReleaseScene(m_scene); }

void PlaneBvh::query(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found) const {
    if (m_planes.empty()) {
        found.clear();
        return;
    }
    queryCandidates(m_scene, o, d, sMax, found);
}

Rgb gatherPlanes(const EmbreeScene& rt, const PlaneBvh& bvh, MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                 int maxPlaneSegment, std::vector<uint32_t>& scratch) {
    bvh.query(o, d, sMax, scratch);
    const Medium& med = rt.scene().media[medium];
    Rgb sum;
    for (uint32_t i : scratch) {
        const PhotonPlane& plane = bvh.planes()[i];
        if (plane.medium != medium || (maxPlaneSegment > 0 && plane.segment > maxPlaneSegment)) continue;
        PlaneRayHit hit;
        if (!intersectPlaneRay(o, d, sMax, plane, &hit)) continue;
        const Rgb value = planeRadiance(hit, plane, med);
        if (value.isBlack()) continue;
        // Back from x_2 along -w_2 to just short of x_1 (which may lie on the surface a beam left).
        if (hit.b > 0 && rt.occluded(Ray{o + d * hit.s, -plane.dir2, 0.0f, hit.b * 0.9999f})) continue;
        sum += value;
    }
    return sum;
}

}  // namespace tyndall
