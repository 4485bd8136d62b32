#pragma once
// A BVH over photon-beam cylinders for the CPU gather of secondary camera segments: finds every
// beam whose axis passes within its radius of a ray segment, with the exact beam x ray closest
// approach of beam_estimator.h. Two Embree representations, chosen at construction, so that
// build/bench/tyndall_stages can measure both (see docs/performance.md for which is faster):
//   UserGeometry: one user primitive per beam (AABB of the cylinder, our own intersector);
//   FlatCurves:   Embree flat linear curves (ray-facing ribbons of half-width r) with a filter that
//                 applies the exact test and rejects the hit so traversal continues. The default:
//                 1.3x the user geometry's queries/s on the default scene (docs/performance.md).
// Long beams have huge, mostly empty bounding boxes, so each beam is split along its axis into
// at most `maxPieces` (1-8) pieces no shorter than `pieceLength` (one BVH primitive each); a piece
// reports a beam only when the closest point t_v falls inside the piece, so every beam is found
// once. Pieces make queries cheaper and the build dearer: piecesFor() weighs the two per pass.
// Thread-safe queries after construction.
//
// Neighbouring camera paths' secondary segments (a tile's pixels through a mirror) are nearly the
// same segment, so the flat curves are widened by a margin `reach` (3 times the largest beam radius): one
// Embree traversal along a segment S0 finds every beam within its radius plus `reach` of S0 (the
// candidates), and any segment whose two ends lie within `reach` of S0 (so all of it does) needs
// only the exact beam x ray test against those candidates (BeamQueryCache). Every query, cached or
// not, returns the exact test's beams among an Embree candidate set; the test runs over the
// candidates with SIMD (cpu/beam_hit_scan.h), bit for bit intersectBeamRay.
#include <embree3/rtcore.h>

#include <vector>

#include "core/beam_estimator.h"
#include "cpu/beam_hit_scan.h"
#include "cpu/embree_scene.h"

namespace tyndall {

/// The candidate lists of a thread's recent queries (BeamBvh::query). What a query returns may
/// depend on the cache's content where Embree's ribbon approximation misses a beam by a hair, so
/// a caller that wants results independent of the thread count resets it at fixed points (a
/// camera tile's start). Belongs to one BeamBvh at a time (reset before use with another).
class BeamQueryCache {
public:
    void reset() {
        m_used = 0;
        m_next = 0;
    }
    /// Queries answered from a cached candidate list since construction (a statistic).
    uint64_t reused() const { return m_reused; }

private:
    friend class BeamBvh;
    struct Entry {
        Vec3 a, b;                     ///< the segment S0 the candidates were found along
        std::vector<uint32_t> beams;   ///< beams within radius + reach of S0, ascending, once each
        BeamCandidates scan;           ///< those beams' data for the exact test (cpu/beam_hit_scan.h)
    };
    // 16, not 8: the glass sphere's diverging segments at 1080p need 10% fewer traversals
    // (docs/performance.md, "Where a 1080p pass goes"); a miss checks every entry.
    static constexpr int kEntries = 16;
    Entry m_entries[kEntries];
    int m_used = 0;  ///< entries filled since the reset
    int m_next = 0;  ///< the one replaced next
    uint64_t m_reused = 0;
};

class BeamBvh {
public:
    enum class Kind { UserGeometry, FlatCurves };

    /// Keeps a reference to `beams`: they must outlive the BVH. `pieceLength` <= 0 picks 16x the
    /// largest beam radius; `maxPieces` (clamped to 1..kMaxPieces) caps the pieces of one beam.
    /// `usualRadius` > 0 stands for the largest beam radius in the reach and the default piece
    /// length, where a few beams are much wider than the rest (RenderSettings::scatteredBeamMfp):
    /// the cache's margin and the pieces then follow the usual beams, never what a query finds.
    BeamBvh(const EmbreeDevice& device, const std::vector<PhotonBeam>& beams, Kind kind = Kind::FlatCurves,
            float pieceLength = 0.0f, int maxPieces = kMaxPieces, float usualRadius = 0.0f);

    static constexpr int kMaxPieces = 8;
    /// The piece cap for a pass expected to make `queries` queries (its secondary segments: about
    /// one per pixel whose camera ray first meets a non-diffuse surface) among `beams` beams:
    /// 2.5 queries / beams, within 1..kMaxPieces. Measured with callgrind (docs/performance.md,
    /// "The environment light"): a piece costs about 3 k instructions to build, and cutting the
    /// beams of the fog-balls scene into 8 pieces instead of 1 saves about 14 k a query, so
    /// splitting pays only where a pass makes a good share as many queries as it has beams
    /// (1080p through glass: 3.4 a beam, 8 pieces; the fog-balls at 128x128: 0.4, 1 piece). The
    /// pieces change what a query costs, never what it finds.
    static int piecesFor(uint64_t queries, size_t beams);
    ~BeamBvh();
    BeamBvh(const BeamBvh&) = delete;
    BeamBvh& operator=(const BeamBvh&) = delete;

    /// Appends every beam within its radius of segment o + s d, s in [0, sMax] (d unit), sorted by
    /// beam index (so sums over them are deterministic). `hits` is cleared first.
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const;
    /// The same, reusing a cached candidate list when the segment lies within reach() of its
    /// segment, else tracing one and caching it (flat curves only; user geometry ignores `cache`).
    void query(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits,
               BeamQueryCache& cache) const;
    /// The margin the flat curves are widened by (3 times the largest beam radius, or the usual one).
    float reach() const { return m_reach; }

    Kind kind() const { return m_kind; }

    /// A stretch [t0, t1] of one beam: the BVH primitive.
    struct Piece {
        uint32_t beam;
        float t0, t1;
    };
    const std::vector<Piece>& pieces() const { return m_pieces; }
    const std::vector<PhotonBeam>& beams() const { return m_beams; }

private:
    /// The candidates along o + s d, s in [0, sMax] (flat curves): ascending, once each.
    void candidates(const Vec3& o, const Vec3& d, float sMax, std::vector<uint32_t>& beams) const;
    void traceUserGeometry(const Vec3& o, const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits) const;

    const std::vector<PhotonBeam>& m_beams;
    Kind m_kind;
    std::vector<Piece> m_pieces;
    float m_maxRadius = 0;
    float m_reach = 0;
    RTCScene m_scene = nullptr;
};

}  // namespace tyndall
