// SurfacePhotonGrid's density() and gather() must sum exactly the photons brute force finds
// (within the radius, near the plane, normal agreeing), each once, whatever the cell layout:
// photons on planes in all orientations and scattered in space, radii varying per photon (the
// schedule), queries on, near and far from the photons, with and without hash collisions.
#include "cpu/surface_photon_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/rng.h"
#include "core/sampling.h"

using namespace tyndall;

namespace {

Rgb bruteDensity(const std::vector<SurfacePhoton>& photons, const Vec3& x, const Vec3& n, bool eitherSide) {
    Rgb sum;
    for (const SurfacePhoton& p : photons) {
        Vec3 diff = p.position - x;
        float d2 = dot(diff, diff);
        if (d2 >= p.radius * p.radius || std::abs(dot(diff, n)) > 0.25f * p.radius) continue;
        float agree = dot(p.normal, n);
        if ((eitherSide ? std::abs(agree) : agree) < 0.7f) continue;
        sum += p.power * SurfacePhotonGrid::kernel(d2, p.radius) * (eitherSide ? p.wi.x + 2.0f : 1.0f);
    }
    return sum;
}

// Photons on a few planes (axis-aligned and tilted, both sides) plus a scatter in space, with
// radii spread over a factor 4 round `radius`, around a centre far from the origin.
std::vector<SurfacePhoton> makePhotons(int n, float radius, const Vec3& centre, uint64_t seed) {
    Rng rng(seed, 5);
    const Vec3 normals[] = {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}, normalize(Vec3(1, 2, 3)), normalize(Vec3(-0.3f, 1, 0.1f))};
    std::vector<SurfacePhoton> photons;
    for (int i = 0; i < n; ++i) {
        SurfacePhoton p;
        const int plane = i % 6;
        Vec3 q = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(1.0f);
        if (plane < 5) {
            const Vec3 nn = normals[plane];
            q = q - nn * dot(q, nn) + nn * (0.1f * float(plane) - 0.2f);  // onto the plane
            p.normal = rng.uniform() < 0.8f ? nn : -nn;
        } else {
            p.normal = sampleUniformSphere(rng.uniform(), rng.uniform());
        }
        p.position = centre + q;
        p.radius = radius * (0.25f + 0.75f * rng.uniform());
        p.wi = sampleUniformSphere(rng.uniform(), rng.uniform());
        p.power = Rgb(rng.uniform(), rng.uniform(), 1.0f);
        photons.push_back(p);
    }
    return photons;
}

void expectMatchesBruteForce(const std::vector<SurfacePhoton>& photons, const Vec3& centre, uint64_t seed) {
    SurfacePhotonGrid grid(photons);
    Rng rng(seed, 9);
    int nonZero = 0;
    for (int q = 0; q < 3000; ++q) {
        Vec3 x, n;
        if (q % 3 == 0) {  // exactly at a photon's position and normal
            const SurfacePhoton& p = photons[std::min(photons.size() - 1, size_t(rng.uniform() * float(photons.size())))];
            x = p.position;
            n = p.normal;
        } else if (q % 3 == 1) {  // near a photon, off its plane, any normal
            const SurfacePhoton& p = photons[std::min(photons.size() - 1, size_t(rng.uniform() * float(photons.size())))];
            x = p.position + sampleUniformSphere(rng.uniform(), rng.uniform()) * (p.radius * rng.uniform());
            n = rng.uniform() < 0.5f ? p.normal : sampleUniformSphere(rng.uniform(), rng.uniform());
        } else {  // anywhere, also well outside the photons' bounds
            x = centre + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3(1.0f)) * 1.5f;
            n = sampleUniformSphere(rng.uniform(), rng.uniform());
        }
        const Rgb want = bruteDensity(photons, x, n, false);
        const Rgb got = grid.density(x, n);
        const Rgb wantGather = bruteDensity(photons, x, n, true);
        const Rgb gotGather = grid.gather(x, n, [](const SurfacePhoton& p) { return Rgb(p.wi.x + 2.0f); });
        nonZero += want.b > 0;
        // Summation order differs from brute force: rounding only.
        ASSERT_NEAR(got.r, want.r, 1e-5f * want.b + 1e-30f) << "query " << q;
        ASSERT_NEAR(got.b, want.b, 1e-5f * want.b + 1e-30f) << "query " << q;
        ASSERT_NEAR(gotGather.g, wantGather.g, 1e-5f * wantGather.b + 1e-30f) << "query " << q;
        ASSERT_NEAR(gotGather.b, wantGather.b, 1e-5f * wantGather.b + 1e-30f) << "query " << q;
    }
    EXPECT_GT(nonZero, 1000);  // the queries do find photons
}

}  // namespace

TEST(SurfacePhotonGrid, DensityAndGatherMatchBruteForce) {
    const Vec3 centre(3.0f, -1.0f, 0.5f);
    expectMatchesBruteForce(makePhotons(6000, 0.05f, centre, 1), centre, 2);
}

TEST(SurfacePhotonGrid, MatchesBruteForceFarFromTheOriginWithTinyRadii) {
    // Coordinates ~1000 with radii ~1e-3: cell indices near 1e6, where float rounding of a
    // photon's cell matters.
    const Vec3 centre(1000.0f, 700.0f, -900.0f);
    expectMatchesBruteForce(makePhotons(4000, 0.002f, centre, 3), centre, 4);
}

TEST(SurfacePhotonGrid, OnePhotonAndNone) {
    std::vector<SurfacePhoton> none;
    SurfacePhotonGrid empty(none);
    EXPECT_EQ(empty.density(Vec3(0.0f), Vec3(0, 1, 0)).b, 0.0f);
    std::vector<SurfacePhoton> one(1);
    one[0].position = Vec3(1, 2, 3);
    one[0].normal = Vec3(0, 1, 0);
    one[0].radius = 0.1f;
    one[0].power = Rgb(1.0f);
    SurfacePhotonGrid grid(one);
    EXPECT_FLOAT_EQ(grid.density(Vec3(1, 2, 3), Vec3(0, 1, 0)).b, SurfacePhotonGrid::kernel(0.0f, 0.1f));
    EXPECT_EQ(grid.density(Vec3(1.2f, 2, 3), Vec3(0, 1, 0)).b, 0.0f);
    EXPECT_EQ(grid.density(Vec3(1, 2, 3), Vec3(0, -1, 0)).b, 0.0f);  // the other side
    EXPECT_EQ(grid.density(Vec3(kInfinity, 0, 0), Vec3(0, 1, 0)).b, 0.0f);
}

// Lookups along short walks (neighbouring pixels) are answered from the per-thread cached
// regions: they must visit the same photons, in the same order, with the same d^2 bits, as the
// uncached query, and the set brute force finds.
TEST(SurfacePhotonGrid, CachedRegionsVisitExactlyWhatTheUncachedQueryVisits) {
    const Vec3 centre(3.0f, -1.0f, 0.5f);
    const std::vector<SurfacePhoton> photons = makePhotons(6000, 0.05f, centre, 5);
    SurfacePhotonGrid grid(photons);
    Rng rng(11, 9);
    int nonEmpty = 0;
    for (int walk = 0; walk < 200; ++walk) {
        const SurfacePhoton& start = photons[std::min(photons.size() - 1, size_t(rng.uniform() * float(photons.size())))];
        Vec3 x = start.position;
        const Vec3 n = walk % 4 == 0 ? sampleUniformSphere(rng.uniform(), rng.uniform()) : start.normal;
        const Vec3 step = sampleUniformSphere(rng.uniform(), rng.uniform()) * (0.004f * rng.uniform());
        for (int i = 0; i < 40; ++i, x = x + step) {
            std::vector<std::pair<const SurfacePhoton*, float>> cached, uncached;
            grid.forEachNear(x, n, [&](const SurfacePhoton& p, float d2) { cached.push_back({&p, d2}); });
            grid.forEachNearUncached(x, n, [&](const SurfacePhoton& p, float d2) { uncached.push_back({&p, d2}); });
            ASSERT_EQ(cached.size(), uncached.size()) << "walk " << walk << " step " << i;
            for (size_t k = 0; k < cached.size(); ++k) {
                ASSERT_EQ(cached[k].first, uncached[k].first) << "walk " << walk << " step " << i;
                ASSERT_EQ(cached[k].second, uncached[k].second);
            }
            size_t brute = 0;
            for (const SurfacePhoton& p : photons) {
                const Vec3 diff = p.position - x;
                const float d2 = dot(diff, diff);
                brute += d2 < p.radius * p.radius && std::abs(dot(diff, n)) <= 0.25f * p.radius;
            }
            ASSERT_EQ(cached.size(), brute) << "walk " << walk << " step " << i;
            nonEmpty += !cached.empty();
        }
    }
    EXPECT_GT(nonEmpty, 3000);
}

static uint32_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

// The Highway candidate scan the cached lookups use must accept exactly what the scalar test
// accepts, in the same order, with the same d2 bits: random candidates round random points and
// normals (every count from 0 to 70, so every tail length of 4-, 8- and 16-lane vectors), plus the
// boundaries (d2 == r^2 rejected, plane distance == r/4 accepted, one float past it rejected) and
// a NaN position (accepted by the scalar test's `continue`s).
TEST(SurfacePhotonScan, SimdAcceptsExactlyWhatTheScalarTestAccepts) {
    Rng rng = Rng::forKey(31, 0, 0, StreamPurpose::Test);
    size_t acceptedTotal = 0, candidatesTotal = 0;
    for (int round = 0; round < 400; ++round) {
        const size_t count = size_t(round % 71);
        const Vec3 p(rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, rng.uniform() * 4 - 2);
        const Vec3 n = sampleUniformSphere(rng.uniform(), rng.uniform());
        std::vector<float> x(count + kPhotonScanPadding), y(x.size()), z(x.size()), r(x.size());
        for (size_t i = 0; i < count; ++i) {
            // Mostly near the plane through p, some off it; radii 0.05-0.3, offsets up to 0.4.
            const Vec3 off = sampleUniformSphere(rng.uniform(), rng.uniform()) * (0.4f * rng.uniform());
            const Vec3 c = p + off - n * (i % 3 == 0 ? 0.0f : dot(off, n) * 0.9f);
            x[i] = c.x, y[i] = c.y, z[i] = c.z, r[i] = 0.05f + 0.25f * rng.uniform();
        }
        std::vector<uint32_t> aScalar(count + kPhotonScanPadding), aSimd(aScalar.size());
        std::vector<float> dScalar(count + kPhotonScanPadding), dSimd(dScalar.size());
        const size_t nScalar = scanPhotonCandidatesScalar(x.data(), y.data(), z.data(), r.data(), count, p, n,
                                                          aScalar.data(), dScalar.data());
        const size_t nSimd =
            scanPhotonCandidates(x.data(), y.data(), z.data(), r.data(), count, p, n, aSimd.data(), dSimd.data());
        ASSERT_EQ(nSimd, nScalar) << "round " << round;
        for (size_t k = 0; k < nScalar; ++k) {
            ASSERT_EQ(aSimd[k], aScalar[k]) << "round " << round << " k " << k;
            ASSERT_EQ(floatBits(dSimd[k]), floatBits(dScalar[k])) << "round " << round;
        }
        acceptedTotal += nScalar;
        candidatesTotal += count;
    }
    // Not blind: both outcomes occur often.
    EXPECT_GT(acceptedTotal, candidatesTotal / 10);
    EXPECT_LT(acceptedTotal, candidatesTotal * 9 / 10);

    // Boundaries, exact in float: p = 0, n = +z, r = 0.5.
    const float past = std::nextafter(0.125f, 1.0f);
    //                     inside  d2==r2  on plane edge  past the plane edge  NaN
    std::vector<float> x = {0.1f, 0.5f, 0.0f, 0.0f, std::nanf("")}, y = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f},
                       z = {0.0f, 0.0f, 0.125f, past, 0.0f}, r = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    for (std::vector<float>* v : {&x, &y, &z, &r}) v->resize(v->size() + kPhotonScanPadding, 0.0f);
    std::vector<uint32_t> accepted(5 + kPhotonScanPadding);
    std::vector<float> d2(accepted.size());
    for (bool simd : {false, true}) {
        auto scan = simd ? scanPhotonCandidates : scanPhotonCandidatesScalar;
        const size_t found = scan(x.data(), y.data(), z.data(), r.data(), 5, Vec3(0.0f), Vec3(0, 0, 1),
                                  accepted.data(), d2.data());
        ASSERT_EQ(found, 3u) << (simd ? "SIMD" : "scalar");
        EXPECT_EQ(accepted[0], 0u);
        EXPECT_EQ(accepted[1], 2u);
        EXPECT_EQ(accepted[2], 4u);
        EXPECT_EQ(d2[1], 0.125f * 0.125f);
        EXPECT_TRUE(std::isnan(d2[2]));
    }
}

// gather and gatherFacing sum in their own loop: bit for bit what the visitor form summed before
// them (forEachNear, the normal test |n_p . n| >= 0.7, zero weights skipped), and gatherFacing
// bit for bit gather with a weight that is 0 where n_p . n < 0.7 (the diffuse end's lambdas), with
// float and Rgb weights, photons on both sides of their planes, queries on and off them.
TEST(SurfacePhotonGrid, GatherFacingIsTheOneSidedGatherBitForBit) {
    const Vec3 centre(3.0f, -1.0f, 0.5f);
    const std::vector<SurfacePhoton> photons = makePhotons(6000, 0.05f, centre, 7);
    SurfacePhotonGrid grid(photons);
    auto visitorGather = [&](const Vec3& x, const Vec3& n, auto weight) {
        Rgb sum;
        grid.forEachNear(x, n, [&](const SurfacePhoton& p, float d2) {
            if (std::abs(dot(p.normal, n)) < kSurfaceNormalAgreement) return;
            const auto w = weight(p);
            if (Rgb(w).isBlack()) return;
            sum += w * p.power * SurfacePhotonGrid::kernel(d2, p.radius);
        });
        return sum;
    };
    auto same = [](const Rgb& a, const Rgb& b) {
        return floatBits(a.r) == floatBits(b.r) && floatBits(a.g) == floatBits(b.g) && floatBits(a.b) == floatBits(b.b);
    };
    Rng rng(13, 9);
    int facingOnly = 0, nonZero = 0;
    for (int q = 0; q < 3000; ++q) {
        const SurfacePhoton& p0 = photons[std::min(photons.size() - 1, size_t(rng.uniform() * float(photons.size())))];
        const Vec3 x = p0.position + sampleUniformSphere(rng.uniform(), rng.uniform()) * (p0.radius * 0.5f * rng.uniform());
        const Vec3 n = q % 5 == 0 ? sampleUniformSphere(rng.uniform(), rng.uniform()) : (q % 2 ? p0.normal : -p0.normal);
        auto scalar = [](const SurfacePhoton& p) { return p.wi.x > -0.5f ? 0.5f + p.wi.y : 0.0f; };
        auto colour = [](const SurfacePhoton& p) { return Rgb(1.0f + p.wi.x, 0.25f, p.wi.z > 0 ? 2.0f : 0.0f); };
        auto oneSided = [&](auto weight) {
            return [&, weight](const SurfacePhoton& p) { return dot(p.normal, n) < kSurfaceNormalAgreement ? decltype(weight(p))(0.0f) : weight(p); };
        };
        ASSERT_TRUE(same(grid.gather(x, n, scalar), visitorGather(x, n, scalar))) << q;
        ASSERT_TRUE(same(grid.gather(x, n, colour), visitorGather(x, n, colour))) << q;
        const Rgb facing = grid.gatherFacing(x, n, scalar);
        ASSERT_TRUE(same(facing, grid.gather(x, n, oneSided(scalar)))) << q;
        ASSERT_TRUE(same(facing, visitorGather(x, n, oneSided(scalar)))) << q;
        ASSERT_TRUE(same(grid.gatherFacing(x, n, colour), visitorGather(x, n, oneSided(colour)))) << q;
        facingOnly += !same(facing, grid.gather(x, n, scalar));
        nonZero += facing.b > 0;
    }
    // Not blind: the other side's photons are often there, and the sums often non-zero.
    EXPECT_GT(facingOnly, 300);
    EXPECT_GT(nonZero, 500);
}
