// The beam BVH's two Embree representations find exactly the beams that the brute-force beam x ray
// test finds, including for query segments that start right next to a beam (secondary camera
// segments start on the mirror or glass surface where photon beams end and begin; Embree's flat
// curves drop hits within about two radii of the ray origin unless the query starts earlier).
#include "cpu/beam_bvh.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "core/sampling.h"

namespace tyndall {
namespace {

std::vector<uint32_t> bruteForce(const std::vector<PhotonBeam>& beams, const Vec3& o, const Vec3& d, float sMax) {
    std::vector<uint32_t> ids;
    BeamRayHit hit;
    for (uint32_t i = 0; i < beams.size(); ++i)
        if (intersectBeamRay(o, d, sMax, beams[i], &hit)) ids.push_back(i);
    return ids;
}

TEST(BeamBvh, BothKindsFindExactlyTheBruteForceBeams) {
    Rng rng = Rng::forKey(5, 0, 0, StreamPurpose::Test);
    std::vector<PhotonBeam> beams(3000);
    for (PhotonBeam& b : beams) {
        b.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(1.0f);
        b.dir = sampleUniformSphere(rng.uniform(), rng.uniform());
        b.tMax = 0.05f + 0.6f * rng.uniform();
        b.radius = 0.005f + 0.03f * rng.uniform();
        b.power = Rgb(1.0f);
        b.medium = 0;
    }
    EmbreeDevice device;
    BeamBvh user(device, beams, BeamBvh::Kind::UserGeometry), curves(device, beams, BeamBvh::Kind::FlatCurves);
    std::vector<BeamHitRecord> hitsUser, hitsCurves;
    size_t total = 0;
    for (int q = 0; q < 4000; ++q) {
        Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
        Vec3 o;
        if (q % 2 == 0) {
            o = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(1.0f);
        } else {  // start where a beam ends (or next to it)
            const PhotonBeam& b = beams[rng.nextUInt() % beams.size()];
            o = b.origin + b.dir * (b.tMax * (0.9f + 0.1f * rng.uniform())) + sampleUniformSphere(rng.uniform(), rng.uniform()) * (0.5f * b.radius * rng.uniform());
        }
        float sMax = 0.1f + 1.5f * rng.uniform();
        std::vector<uint32_t> expected = bruteForce(beams, o, d, sMax);
        user.query(o, d, sMax, hitsUser);
        curves.query(o, d, sMax, hitsCurves);
        std::vector<uint32_t> gotUser, gotCurves;
        for (const BeamHitRecord& h : hitsUser) gotUser.push_back(h.beam);
        for (const BeamHitRecord& h : hitsCurves) gotCurves.push_back(h.beam);
        ASSERT_EQ(gotUser, expected) << "user geometry, query " << q;
        ASSERT_EQ(gotCurves, expected) << "flat curves, query " << q;
        total += expected.size();
    }
    EXPECT_GT(total, 4000u);  // the queries do find beams
}

}  // namespace
}  // namespace tyndall
