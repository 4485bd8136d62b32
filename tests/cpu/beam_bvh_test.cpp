// BeamBvh (both Embree representations, with beams split into pieces) must return exactly the
// beams brute force finds for a ray segment, each once, sorted by index, with intersectBeamRay's
// hits bit for bit (the flat curves' exact test is the SIMD scan of cpu/beam_hit_scan.h).
#include "cpu/beam_bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/rng.h"
#include "core/sampling.h"

using namespace tyndall;

namespace {
std::vector<PhotonBeam> randomBeams(int n, uint64_t seed) {
    Rng rng(seed, 1);
    std::vector<PhotonBeam> beams;
    for (int i = 0; i < n; ++i) {
        PhotonBeam b;
        b.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - Vec3(2.0f);
        b.dir = sampleUniformSphere(rng.uniform(), rng.uniform());
        b.tMax = i % 10 == 0 ? 0.01f : rng.uniform() * 5.0f;  // some very short, some long
        b.radius = 0.005f + 0.1f * rng.uniform();
        b.power = Rgb(1.0f);
        b.medium = 0;
        beams.push_back(b);
    }
    return beams;
}

// The same bits in every field of the hit.
void expectSameHit(const BeamRayHit& a, const BeamRayHit& b) {
    ASSERT_EQ(std::memcmp(&a.u, &b.u, sizeof(float)), 0) << a.u << " vs " << b.u;
    ASSERT_EQ(std::memcmp(&a.s, &b.s, sizeof(float)), 0) << a.s << " vs " << b.s;
    ASSERT_EQ(std::memcmp(&a.t, &b.t, sizeof(float)), 0) << a.t << " vs " << b.t;
    ASSERT_EQ(std::memcmp(&a.cosTheta, &b.cosTheta, sizeof(float)), 0) << a.cosTheta << " vs " << b.cosTheta;
    ASSERT_EQ(std::memcmp(&a.invSinTheta, &b.invSinTheta, sizeof(float)), 0) << a.invSinTheta << " vs " << b.invSinTheta;
}
}  // namespace

TEST(BeamBvh, BothKindsFindExactlyTheBruteForceSet) {
    EmbreeDevice device;
    std::vector<PhotonBeam> beams = randomBeams(3000, 42);
    for (BeamBvh::Kind kind : {BeamBvh::Kind::UserGeometry, BeamBvh::Kind::FlatCurves}) {
        for (float piece : {0.0f, 0.05f, 100.0f}) {
            BeamBvh bvh(device, beams, kind, piece);
            Rng rng(7, 3);
            std::vector<BeamHitRecord> hits;
            size_t total = 0;
            for (int q = 0; q < 400; ++q) {
                Vec3 o = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - Vec3(2.0f);
                Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
                float sMax = q % 3 == 0 ? kInfinity : rng.uniform() * 3.0f;
                bvh.query(o, d, sMax, hits);
                std::vector<BeamHitRecord> expected;
                for (uint32_t i = 0; i < beams.size(); ++i) {
                    BeamRayHit h;
                    if (intersectBeamRay(o, d, sMax, beams[i], &h)) expected.push_back({i, h});
                }
                ASSERT_EQ(hits.size(), expected.size()) << "kind " << int(kind) << " piece " << piece << " query " << q;
                for (size_t k = 0; k < hits.size(); ++k) {
                    ASSERT_EQ(hits[k].beam, expected[k].beam);
                    expectSameHit(hits[k].hit, expected[k].hit);
                }
                total += hits.size();
            }
            EXPECT_GT(total, 400u) << "queries should meet beams";
        }
    }
}

// The piece cap (BeamBvh::piecesFor, per pass) bounds the pieces and changes nothing a query finds.
TEST(BeamBvh, PieceCapBoundsThePiecesAndFindsTheSameBeams) {
    EmbreeDevice device;
    const std::vector<PhotonBeam> beams = randomBeams(2000, 9);
    std::vector<std::vector<uint32_t>> found[3];
    const int caps[3] = {1, 3, 8};
    for (int c = 0; c < 3; ++c) {
        BeamBvh bvh(device, beams, BeamBvh::Kind::FlatCurves, 0.05f, caps[c]);
        EXPECT_LE(bvh.pieces().size(), beams.size() * size_t(caps[c]));
        EXPECT_GT(bvh.pieces().size(), beams.size() * size_t(caps[c]) / 2) << "long beams use the cap";
        Rng rng(5, 3);
        std::vector<BeamHitRecord> hits;
        for (int q = 0; q < 300; ++q) {
            const Vec3 o = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - Vec3(2.0f);
            const Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
            bvh.query(o, d, rng.uniform() * 3.0f, hits);
            found[c].emplace_back();
            for (const BeamHitRecord& h : hits) found[c].back().push_back(h.beam);
        }
    }
    EXPECT_EQ(found[0], found[2]);
    EXPECT_EQ(found[1], found[2]);
    // The cap per pass: 2.5 queries a beam, within 1..8.
    EXPECT_EQ(BeamBvh::piecesFor(1100, 2650), 1);   // the fog-balls at 128x128
    EXPECT_EQ(BeamBvh::piecesFor(35500, 10455), 8);  // the default scene at 960x540
    EXPECT_EQ(BeamBvh::piecesFor(2000, 1000), 5);
    EXPECT_EQ(BeamBvh::piecesFor(0, 1000), 1);
    EXPECT_EQ(BeamBvh::piecesFor(10, 0), 1);
}

// Neighbouring segments (a tile's paths through a mirror) share cached candidate lists: every
// query, answered from the cache or not, must still be exactly the brute-force set.
TEST(BeamBvh, CachedQueriesOfNeighbouringSegmentsFindExactlyTheBruteForceSet) {
    EmbreeDevice device;
    std::vector<PhotonBeam> beams = randomBeams(3000, 43);
    BeamBvh bvh(device, beams);
    ASSERT_GT(bvh.reach(), 0.0f);
    Rng rng(8, 3);
    BeamQueryCache cache;
    std::vector<BeamHitRecord> hits;
    size_t total = 0;
    for (int bundle = 0; bundle < 60; ++bundle) {
        cache.reset();
        const Vec3 o0 = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - Vec3(2.0f);
        const Vec3 d0 = sampleUniformSphere(rng.uniform(), rng.uniform());
        const float s0 = 0.5f + rng.uniform() * 3.0f;
        for (int q = 0; q < 30; ++q) {
            // Origins and ends moved by up to ~1.5 reach: some inside the cached segment's reach, some not.
            const float spread = 1.5f * bvh.reach() * rng.uniform();
            const Vec3 o = o0 + sampleUniformSphere(rng.uniform(), rng.uniform()) * spread;
            const Vec3 e = o0 + d0 * s0 + sampleUniformSphere(rng.uniform(), rng.uniform()) * spread;
            const Vec3 d = normalize(e - o);
            const float sMax = length(e - o) * (q % 5 == 0 ? 0.5f : 1.0f);
            bvh.query(o, d, sMax, hits, cache);
            std::vector<BeamHitRecord> expected;
            for (uint32_t i = 0; i < beams.size(); ++i) {
                BeamRayHit h;
                if (intersectBeamRay(o, d, sMax, beams[i], &h)) expected.push_back({i, h});
            }
            ASSERT_EQ(hits.size(), expected.size()) << "bundle " << bundle << " query " << q;
            for (size_t k = 0; k < hits.size(); ++k) {
                ASSERT_EQ(hits[k].beam, expected[k].beam);
                expectSameHit(hits[k].hit, expected[k].hit);
            }
            total += hits.size();
        }
    }
    EXPECT_GT(total, 1000u) << "queries should meet beams";
    EXPECT_GT(cache.reused(), 300u) << "most neighbouring queries should reuse a cached candidate list";
    EXPECT_LT(cache.reused(), 1700u) << "some should be too far to reuse one";
}

// The SIMD scan against intersectBeamRay on the cases its rejections separate: near-parallel
// lines (sin^2 around 1e-12), closest points at the ends of both segments, u at the radius, and
// 1/sin clamped; every candidate count modulo the vector width.
TEST(BeamHitScan, SimdHitsAreTheScalarTestsBitForBit) {
    std::vector<PhotonBeam> beams = randomBeams(600, 44);
    Rng rng(9, 5);
    for (size_t i = 0; i < beams.size(); i += 7) {
        // Crossing the odd queries' line (the x axis) at a small angle, some within the clamp of
        // 1/sin (angles below 1e-3), some below the parallel test's 1e-12 on sin^2.
        const float tilt = std::pow(10.0f, -1.0f - 4.0f * rng.uniform());
        beams[i].dir = normalize(Vec3(1.0f, tilt, tilt * rng.uniform()));
        beams[i].origin = Vec3(0.5f * rng.uniform(), 0.0f, 0.0f) - beams[i].dir * 0.5f;
        beams[i].tMax = 1.0f;
    }
    size_t accepted = 0, clamped = 0;
    for (int q = 0; q < 300; ++q) {
        const Vec3 o = q % 2 ? Vec3(-1.5f, 0.0f, 0.0f)
                             : Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 4.0f - Vec3(2.0f);
        const Vec3 d = q % 2 ? Vec3(1.0f, 0.0f, 0.0f) : sampleUniformSphere(rng.uniform(), rng.uniform());
        const float sMax = q % 3 == 0 ? kInfinity : rng.uniform() * 3.0f;
        std::vector<uint32_t> indices;
        const size_t count = size_t(q) % beams.size();
        for (uint32_t i = 0; i < count; ++i) indices.push_back((i * 7 + uint32_t(q)) % uint32_t(beams.size()));
        std::sort(indices.begin(), indices.end());
        indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
        BeamCandidates candidates;
        candidates.assign(beams, indices);
        std::vector<BeamHitRecord> simd, scalar;
        scanBeamHits(candidates, o, d, sMax, simd);
        scanBeamHitsScalar(candidates, beams, o, d, sMax, scalar);
        ASSERT_EQ(simd.size(), scalar.size()) << "query " << q;
        for (size_t k = 0; k < simd.size(); ++k) {
            ASSERT_EQ(simd[k].beam, scalar[k].beam) << "query " << q;
            expectSameHit(simd[k].hit, scalar[k].hit);
            clamped += scalar[k].hit.invSinTheta == 1.0f / kMinSinTheta;
        }
        accepted += simd.size();
    }
    EXPECT_GT(accepted, 300u) << "the queries should meet beams";
    EXPECT_GT(clamped, 0u) << "some hits should have 1/sin clamped";
}
