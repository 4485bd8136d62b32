// BeamBvh (both Embree representations, with beams split into pieces) must return exactly the
// beams brute force finds for a ray segment, each once, sorted by index.
#include "cpu/beam_bvh.h"

#include <gtest/gtest.h>

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
                std::vector<uint32_t> expected;
                for (uint32_t i = 0; i < beams.size(); ++i) {
                    BeamRayHit h;
                    if (intersectBeamRay(o, d, sMax, beams[i], &h)) expected.push_back(i);
                }
                ASSERT_EQ(hits.size(), expected.size()) << "kind " << int(kind) << " piece " << piece << " query " << q;
                for (size_t k = 0; k < hits.size(); ++k) ASSERT_EQ(hits[k].beam, expected[k]);
                total += hits.size();
            }
            EXPECT_GT(total, 400u) << "queries should meet beams";
        }
    }
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
            std::vector<uint32_t> expected;
            for (uint32_t i = 0; i < beams.size(); ++i) {
                BeamRayHit h;
                if (intersectBeamRay(o, d, sMax, beams[i], &h)) expected.push_back(i);
            }
            ASSERT_EQ(hits.size(), expected.size()) << "bundle " << bundle << " query " << q;
            for (size_t k = 0; k < hits.size(); ++k) ASSERT_EQ(hits[k].beam, expected[k]);
            total += hits.size();
        }
    }
    EXPECT_GT(total, 1000u) << "queries should meet beams";
    EXPECT_GT(cache.reused(), 300u) << "most neighbouring queries should reuse a cached candidate list";
    EXPECT_LT(cache.reused(), 1700u) << "some should be too far to reuse one";
}
