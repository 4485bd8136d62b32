#pragma once
// A BVH over photon planes (core/photon_plane.h) for the camera segments' gather: finds every
// plane whose parallelogram a segment crosses. Each plane is an Embree quad; an intersection
// filter records the plane and rejects the hit, so one traversal finds them all. Embree's test is
// only the candidate test: the caller decides with intersectPlaneRay (a ray through a quad's
// diagonal may be reported by both of its triangles; each plane is returned once).
// Thread-safe queries after construction.
#include <embree3/rtcore.h>

#include <vector>

#include "core/photon_plane.h"
#include "cpu/embree_scene.h"

namespace tyndall {

class PlaneBvh {
public:
    /// Keeps a reference to `planes`: they must outlive the BVH.
    PlaneBvh(const EmbreeDevice& device, const std::vector<PhotonPlane>& planes);
    ~PlaneBvh();
    PlaneBvh(const PlaneBvh&) = delete;
    PlaneBvh& operator=(const PlaneBvh&) = delete;

    /// The indices of the planes that segment o + s d, s in [0, sMax] (d unit) may cross,
    /// ascending, once each (so sums over them are deterministic). `found` is cleared first.
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& found) const;

    const std::vector<PhotonPlane>& planes() const { return m_planes; }

private:
    const std::vector<PhotonPlane>& m_planes;
    RTCScene m_scene = nullptr;
};

/// The planes' light toward the camera along segment o + s d, s in [0, sMax] (d unit), inside the
/// homogeneous medium `medium`, before the camera path's throughput: the sum of planeRadiance over
/// the planes of that medium the segment crosses, each where no surface lies between its scattering
/// points x_1 and x_2 (a shadow ray). `maxPlaneSegment` > 0 (a capped path length): only planes
/// whose PhotonPlane::segment is at most that. `scratch` holds the candidates.
Rgb gatherPlanes(const EmbreeScene& rt, const PlaneBvh& bvh, MediumId medium, const Vec3& o, const Vec3& d, float sMax,
                 int maxPlaneSegment, std::vector<uint32_t>& scratch);

}  // namespace tyndall
