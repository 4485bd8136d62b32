#pragma once
// A BVH over photon-beam cylinders for the CPU gather of secondary camera segments: finds every
// beam whose axis passes within its radius of a ray segment, with the exact beam x ray closest
// approach of beam_estimator.h. Two Embree representations, chosen at construction, so that
// `tyndall bench` can measure both (see docs/performance.md for which is faster):
//   UserGeometry: one user primitive per beam (AABB of the cylinder, our own intersector);
//   FlatCurves:   Embree flat linear curves (ray-facing ribbons of half-width r) with a filter that
//                 applies the exact test and rejects the hit so traversal continues.
// Thread-safe queries after construction.
#include <embree3/rtcore.h>

#include <vector>

#include "core/beam_estimator.h"
#include "cpu/embree_scene.h"

namespace tyndall {

struct BeamHitRecord {
    uint32_t beam = 0;
    BeamRayHit hit;
};

class BeamBvh {
public:
    enum class Kind { UserGeometry, FlatCurves };

    /// Keeps a reference to `beams`: they must outlive the BVH.
    BeamBvh(const EmbreeDevice& device, const std::vector<PhotonBeam>& beams, Kind kind = Kind::UserGeometry);
    ~BeamBvh();
    BeamBvh(const BeamBvh&) = delete;
    BeamBvh& operator=(const BeamBvh&) = delete;

    /// Appends every beam within its radius of segment o + s d, s in [0, sMax] (d unit), sorted by
    /// beam index (so sums over them are deterministic). `hits` is cleared first.
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const;

    Kind kind() const { return m_kind; }
    const std::vector<PhotonBeam>& beams() const { return m_beams; }

private:
    const std::vector<PhotonBeam>& m_beams;
    Kind m_kind;
    float m_maxRadius = 0;
    RTCScene m_scene = nullptr;
};

}  // namespace tyndall
