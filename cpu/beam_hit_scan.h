#pragma once
// The beam x ray test of a secondary gather (BeamBvh::query) over a candidate list, with Google
// Highway: 16 (AVX-512), 8 (AVX2) or 4 candidates at a time, runtime dispatch. It performs
// intersectBeamRay's float operations (core/beam_estimator.h) in the same order with no fused
// multiply-adds (compiled with -ffp-contract=off), so it accepts exactly the beams the scalar test
// accepts, with the same BeamRayHit bits (BeamHitScan.SimdHitsAreTheScalarTestsBitForBit in
// tests/cpu/beam_bvh_test.cpp).
//
// The candidates are copied once into a structure of arrays (BeamCandidates::assign, when an
// Embree traversal finds them) and scanned by every query that reuses them (BeamQueryCache).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/beam_estimator.h"
#include "core/photon_beam.h"

namespace tyndall {

/// A beam the exact test accepted: its index in the pass's beams and the closest approach.
struct BeamHitRecord {
    uint32_t beam = 0;
    BeamRayHit hit;
};

/// Candidate beams as a structure of arrays, padded for the widest vectors (the padding lanes are
/// never accepted).
struct BeamCandidates {
    static constexpr size_t kPadding = 16;
    std::vector<uint32_t> beam;  ///< beam indices, ascending; its size is the candidate count
    std::vector<float> ox, oy, oz, dx, dy, dz, tMax, r2;  ///< origin, direction, length, radius^2

    /// Copies beams[i] for every i of `indices` (ascending), in that order.
    void assign(const std::vector<PhotonBeam>& beams, const std::vector<uint32_t>& indices);
    size_t size() const { return beam.size(); }
};

/// Appends to `hits`, in candidate order, every candidate that intersectBeamRay(o, d, sMax, beam)
/// accepts, with the hit it gives, bit for bit. d unit.
void scanBeamHits(const BeamCandidates& candidates, const Vec3& o, const Vec3& d, float sMax,
                  std::vector<BeamHitRecord>& hits);

/// The same, candidate by candidate with intersectBeamRay itself (the definition, for tests).
void scanBeamHitsScalar(const BeamCandidates& candidates, const std::vector<PhotonBeam>& beams, const Vec3& o,
                        const Vec3& d, float sMax, std::vector<BeamHitRecord>& hits);

}  // namespace tyndall
