#pragma once
// A BVH over photon-beam cylinders for the CPU gather of secondary camera segments: finds every
// beam whose axis passes within its radius of a ray segment, with the exact beam x ray closest
// approach of beam_estimator.h. Two Embree representations, chosen at construction, so that
// `tyndall bench` can measure both (see docs/performance.md for which is faster):
//   UserGeometry: one user primitive per beam (AABB of the cylinder, our own intersector);
//   FlatCurves:   Embree flat linear curves (ray-facing ribbons of half-width r) with a filter that
//                 applies the exact test and rejects the hit so traversal continues. The default:
//                 1.3x the user geometry's queries/s on the default scene (docs/performance.md).
// Long beams have huge, mostly empty bounding boxes, so each beam is split along its axis into
// at most 8 pieces no shorter than `pieceLength` (one BVH primitive each); a piece reports a beam
// only when the closest point t_v falls inside the piece, so every beam is found once.
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

    /// Keeps a reference to `beams`: they must outlive the BVH. `pieceLength` <= 0 picks 16x the
    /// largest beam radius.
    BeamBvh(const EmbreeDevice& device, const std::vector<PhotonBeam>& beams, Kind kind = Kind::FlatCurves,
            float pieceLength = 0.0f);
    ~BeamBvh();
    BeamBvh(const BeamBvh&) = delete;
    BeamBvh& operator=(const BeamBvh&) = delete;

    /// Appends every beam within its radius of segment o + s d, s in [0, sMax] (d unit), sorted by
    /// beam index (so sums over them are deterministic). `hits` is cleared first.
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const;

    Kind kind() const { return m_kind; }

    /// A stretch [t0, t1] of one beam: the BVH primitive.
    struct Piece {
        uint32_t beam;
        float t0, t1;
    };
    const std::vector<Piece>& pieces() const { return m_pieces; }
    const std::vector<PhotonBeam>& beams() const { return m_beams; }

private:
    const std::vector<PhotonBeam>& m_beams;
    Kind m_kind;
    std::vector<Piece> m_pieces;
    float m_maxRadius = 0;
    RTCScene m_scene = nullptr;
};

}  // namespace tyndall
