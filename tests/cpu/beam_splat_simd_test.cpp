// The SIMD beam splat (cpu/beam_splat_simd.h) against the scalar estimator, its definition: the
// same beam x pixel pairs (coverage identical, pixel by pixel) and the same radiance within 1e-5
// relative per pixel, on random beams including near-parallel ones (the 1/sin clamp and the
// parallel cut-off), beams that end inside a row span, chromatic and grey media, g of both signs,
// and grid media with heterogeneous stored distances on rays and beams. And the SIMD splat is bit
// for bit the same with 1 and 2 threads; a band's pixel columns, found for its rows at once, are
// exactly the scalar row spans'.
#include "cpu/beam_splat_simd.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <memory>

#include "core/rng.h"
#include "core/sampling.h"
#include "cpu/beam_rasterizer.h"
#include "loading/default_scene.h"
#include "cpu/pass_renderer.h"
#include "tests/test_util.h"

using namespace tyndall;

namespace {

// A density field that varies within a beam's footprint, so sigma_s(x_w) is a real lookup.
class WavyDensity : public DensityGrid {
public:
    float density(const Vec3& p) const override { return 0.6f + 0.4f * std::sin(3.0f * p.x) * std::cos(2.0f * p.z); }
    float maxDensity() const override { return 1.0f; }
    float meanDensity() const override { return 0.6f; }
    Bounds3 bounds() const override { return Bounds3{{-10, -10, -10}, {10, 10, 10}}; }
};

Scene fogScene(const Camera& camera, bool grey, float g) {
    Scene s;
    s.name = "simd-test";
    s.source = "<test>";
    Medium fog;
    fog.sigmaS = grey ? Rgb(0.3f) : Rgb(0.3f, 0.45f, 0.6f);
    fog.sigmaA = grey ? Rgb(0.1f) : Rgb(0.05f, 0.02f, 0.1f);
    fog.g = g;
    s.media.push_back(fog);
    s.globalMedium = 0;
    s.camera = camera;
    return s;
}

PrimarySegments primaryRays(const Camera& cam, int w, int h, uint64_t seed) {
    PrimarySegments p;
    p.width = w;
    p.height = h;
    Rng rng(seed, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Ray r = cam.generateRay(float(x) + rng.uniform(), float(y) + rng.uniform(), w, h,
                                    Vec2{rng.uniform(), rng.uniform()});
            // Segment lengths vary so that many beams end or start inside a span.
            p.rays.push_back(PrimaryRay{r.o, 1.0f + 7.0f * rng.uniform(), r.d, (x + y) % 17 == 0 ? kVacuum : 0});
        }
    return p;
}

PhotonBeam makeBeam(Vec3 o, Vec3 d, float tMax, float r, Rgb power) {
    PhotonBeam b;
    b.origin = o;
    b.dir = normalize(d);
    b.tMax = tMax;
    b.radius = r;
    b.power = power;
    b.medium = 0;
    return b;
}

/// Random beams in front of the camera, short beams ending inside spans, and beams nearly parallel
/// to some pixel's ray (sin theta from 1e-7 to 1e-2: both the parallel cut-off and the clamp).
PhotonMap randomBeams(const Camera& cam, const PrimarySegments& primary, uint64_t seed, int count) {
    PhotonMap photons;
    Rng rng(seed, 7);
    const Vec3 e = cam.position;
    for (int i = 0; i < count; ++i) {
        Rgb power(rng.uniform(), rng.uniform(), rng.uniform());
        if (i % 4 == 3) {
            // Near-parallel: along a random pixel's ray, tilted by a tiny angle, offset by < r.
            const PrimaryRay& ray = primary.rays[size_t(rng.uniform() * float(primary.rays.size() - 1))];
            Frame f(ray.dir);
            float angle = std::pow(10.0f, -7.0f + 5.0f * rng.uniform());
            float r = 0.02f + 0.1f * rng.uniform();
            Vec3 o = ray.origin + ray.dir * (0.5f + 2.0f * rng.uniform()) + f.s * (0.5f * r * rng.uniform());
            Vec3 d = ray.dir + f.t * angle;
            photons.beams.push_back(makeBeam(o, rng.uniform() < 0.5f ? d : d * -1.0f, 0.2f + 3.0f * rng.uniform(), r, power));
            continue;
        }
        Vec3 o = e + cam.forward * (6.0f * rng.uniform() + 0.3f) + cam.right * (4.0f * rng.uniform() - 2.0f) +
                 cam.up * (3.0f * rng.uniform() - 1.5f);
        Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
        float tMax = i % 3 == 0 ? 0.05f + 0.3f * rng.uniform() : 4.0f * rng.uniform();  // short: ends in a span
        photons.beams.push_back(makeBeam(o, d, tMax, 0.01f + 0.3f * rng.uniform(), power));
    }
    return photons;
}

/// Per pixel and channel: zero exactly where the scalar splat is zero, else within `rel` of it.
void expectAgreement(const Image& simd, const Image& scalar, double rel, const std::string& what) {
    ASSERT_EQ(simd.pixels.size(), scalar.pixels.size());
    int coverage = 0, outside = 0, lit = 0;
    double maxRel = 0;
    for (size_t p = 0; p < scalar.pixels.size(); ++p) {
        lit += !scalar.pixels[p].isBlack();
        for (int c = 0; c < 3; ++c) {
            double a = simd.pixels[p][c], b = scalar.pixels[p][c];
            if ((a == 0) != (b == 0)) {
                ++coverage;
                continue;
            }
            if (b == 0) continue;
            double e = std::abs(a - b) / std::abs(b);
            maxRel = std::max(maxRel, e);
            outside += !(e <= rel);
        }
    }
    EXPECT_EQ(coverage, 0) << what << ": pixels lit by one kernel only";
    EXPECT_EQ(outside, 0) << what << ": max relative difference " << maxRel;
    EXPECT_GT(lit, int(scalar.pixels.size()) / 4) << what << ": too few lit pixels to compare";
    std::printf("%s: %d lit pixels, max relative difference SIMD vs scalar %.3g\n", what.c_str(), lit, maxRel);
}

}  // namespace

TEST(BeamSplatSimd, MatchesTheScalarEstimatorOnRandomBeams) {
    std::printf("SIMD target: %s\n", splatSimdTarget());
    int variant = 0;
    for (bool grey : {false, true})
        for (float g : {0.6f, -0.4f}) {
            Camera cam = Camera::lookAt({0.2f, 1.0f, 3.0f}, {0.0f, 0.9f, 0.0f}, {0, 1, 0}, 1.0f);
            cam.lensRadius = variant == 3 ? 0.1f : 0.0f;
            cam.focusDistance = 3.0f;
            Scene scene = fogScene(cam, grey, g);
            const int w = 83, h = 37;  // not a multiple of any vector width
            PrimarySegments primary = primaryRays(cam, w, h, 11 + variant);
            PhotonMap photons = randomBeams(cam, primary, 5 + variant, 400);
            Image simd = BeamRasterizer(scene, SplatKernel::Simd).rasterize(primary, photons);
            Image scalar = BeamRasterizer(scene, SplatKernel::Scalar).rasterize(primary, photons);
            expectAgreement(simd, scalar, 1e-5, std::string(grey ? "grey" : "chromatic") + " g=" + std::to_string(g));
            // And the scalar splat is exactly its brute-force definition.
            EXPECT_TRUE(tyndall::test::identicalImages(scalar, BeamRasterizer(scene).bruteForce(primary, photons)));
            ++variant;
        }
}

TEST(BeamSplatSimd, NearParallelBeamsAreCutAndClampedAsInTheScalarEstimator) {
    // Only near-parallel beams: coverage must agree exactly where sin^2(theta) crosses 1e-12 and
    // the clamp at sin(theta) = 1e-3 must scale both kernels the same way.
    Camera cam = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 0.8f);
    Scene scene = fogScene(cam, false, 0.3f);
    const int w = 61, h = 45;
    PrimarySegments primary = primaryRays(cam, w, h, 3);
    PhotonMap photons;
    Rng rng(9, 9);
    int clamped = 0;
    for (int i = 0; i < 600; ++i) {
        const PrimaryRay& ray = primary.rays[size_t(rng.uniform() * float(primary.rays.size() - 1))];
        Frame f(ray.dir);
        float angle = std::pow(10.0f, -7.0f + 4.5f * rng.uniform());
        clamped += angle < kMinSinTheta;
        float r = 0.03f + 0.1f * rng.uniform();
        Vec3 o = ray.origin + ray.dir * (0.3f + 2.0f * rng.uniform()) + f.s * (0.8f * r * rng.uniform());
        photons.beams.push_back(makeBeam(o, ray.dir + f.t * angle, 0.1f + 2.0f * rng.uniform(), r, Rgb(1.0f)));
    }
    ASSERT_GT(clamped, 300);
    Image simd = BeamRasterizer(scene, SplatKernel::Simd).rasterize(primary, photons);
    Image scalar = BeamRasterizer(scene, SplatKernel::Scalar).rasterize(primary, photons);
    int lit = 0;
    for (const Rgb& p : scalar.pixels) lit += !p.isBlack();
    EXPECT_GT(lit, 50);
    // Fewer lit pixels than the random case: compare them all, without the lit-fraction floor.
    double maxRel = 0;
    int coverage = 0;
    for (size_t p = 0; p < scalar.pixels.size(); ++p)
        for (int c = 0; c < 3; ++c) {
            double a = simd.pixels[p][c], b = scalar.pixels[p][c];
            if ((a == 0) != (b == 0)) ++coverage;
            else if (b != 0) maxRel = std::max(maxRel, std::abs(a - b) / b);
        }
    EXPECT_EQ(coverage, 0);
    EXPECT_LE(maxRel, 1e-5);
    std::printf("near-parallel: %d lit pixels, max relative difference %.3g\n", lit, maxRel);
}

TEST(BeamSplatSimd, GridMediumWithStoredDistancesMatchesTheScalarEstimator) {
    Camera cam = Camera::lookAt({0.2f, 1.0f, 3.0f}, {0.0f, 0.9f, 0.0f}, {0, 1, 0}, 1.0f);
    Scene scene = fogScene(cam, false, 0.5f);
    scene.media[0].density = std::make_shared<WavyDensity>();
    const int w = 70, h = 41;
    PrimarySegments primary = primaryRays(cam, w, h, 17);
    PhotonMap photons = randomBeams(cam, primary, 23, 300);
    // Heterogeneous stored distances: n differs between rays and beams, some pass the whole segment.
    Rng rng(4, 4);
    primary.freeFlightsPerRay = 4;
    for (size_t i = 0; i < primary.rays.size(); ++i)
        for (int k = 0; k < 4; ++k) primary.freeFlights.push_back(k == 3 && i % 5 == 0 ? kInfinity : 6.0f * rng.uniform());
    photons.freeFlightsPerBeam = 3;
    for (const PhotonBeam& b : photons.beams)
        for (int k = 0; k < 3; ++k) photons.freeFlights.push_back(1.3f * b.tMax * rng.uniform());
    Image simd = BeamRasterizer(scene, SplatKernel::Simd).rasterize(primary, photons);
    Image scalar = BeamRasterizer(scene, SplatKernel::Scalar).rasterize(primary, photons);
    expectAgreement(simd, scalar, 1e-5, "grid medium");
    // No exp on this path: the SIMD kernel does the scalar arithmetic exactly.
    EXPECT_TRUE(tyndall::test::identicalImages(simd, scalar));
    // The stored distances really enter: with every distance at infinity the image changes.
    PrimarySegments clear = primary;
    std::fill(clear.freeFlights.begin(), clear.freeFlights.end(), kInfinity);
    Image unoccluded = BeamRasterizer(scene, SplatKernel::Simd).rasterize(clear, photons);
    EXPECT_FALSE(tyndall::test::identicalImages(unoccluded, simd));
}

TEST(BeamSplatSimd, DefaultScenePassIsIndependentOfTheThreadCount) {
    Scene scene = makeDefaultScene();
    RenderSettings settings;
    settings.width = 120;
    settings.height = 90;
    settings.photonsPerPass = 500;
    PassRenderer renderer(scene, settings);
    ASSERT_TRUE(renderer.settings().simd);
    PhotonMap photons = renderer.tracePhotons(3);
    CameraPassResult camera = renderer.traceCamera(3, photons);
    auto splat = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return renderer.splatPrimary(camera.primary, photons);
    };
    Image one = splat(1), two = splat(2);
    EXPECT_TRUE(tyndall::test::identicalImages(one, two));
    Image scalar = BeamRasterizer(scene, SplatKernel::Scalar).rasterize(camera.primary, photons);
    expectAgreement(one, scalar, 1e-5, "default scene pass");
}

TEST(BeamSplatSimd, EveryInstructionSetThisCpuRunsMatchesTheScalarEstimator) {
    // Runtime dispatch picks the widest set; the narrower ones (AVX2's 8 lanes, SSE4's 4, the
    // emulated fallback) are what other machines of a farm run.
    Camera cam = Camera::lookAt({0.2f, 1.0f, 3.0f}, {0.0f, 0.9f, 0.0f}, {0, 1, 0}, 1.0f);
    Scene scene = fogScene(cam, false, 0.5f);
    PrimarySegments primary = primaryRays(cam, 53, 29, 31);
    PhotonMap photons = randomBeams(cam, primary, 37, 300);
    Image scalar = BeamRasterizer(scene, SplatKernel::Scalar).rasterize(primary, photons);
    int tried = 0;
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        ASSERT_STREQ(splatSimdTarget(), hwy::TargetName(target));
        Image simd = BeamRasterizer(scene, SplatKernel::Simd).rasterize(primary, photons);
        expectAgreement(simd, scalar, 1e-5, hwy::TargetName(target));
        ++tried;
    }
    hwy::SetSupportedTargetsForTest(0);
    EXPECT_GE(tried, 2);
}

TEST(BeamSplatSimd, BandColumnsAreTheRowSpansOfTheScalarDefinition) {
    // footprintBandColumns finds a band's rows at once; each row must be exactly footprintRowSpan's
    // span rounded to pixel centres and clamped as the rasterizer clamps it, on every instruction
    // set. Footprint coordinates on a quarter-pixel grid put span ends exactly on pixel centres,
    // and equal ends make horizontal sides.
    Rng rng(17, 3);
    const int width = 61;
    auto quarter = [&](float lo, float hi) { return std::round((lo + (hi - lo) * rng.uniform()) * 4.0f) / 4.0f; };
    int tried = 0, rowsSeen = 0;
    for (int64_t target : hwy::SupportedAndGeneratedTargets()) {
        hwy::SetSupportedTargetsForTest(target);
        for (int trial = 0; trial < 400; ++trial) {
            BeamFootprint fp;
            fp.visible = true;
            fp.ax = quarter(-20, 80), fp.ay = quarter(-10, 50), fp.ra = quarter(0, 12);
            fp.bx = quarter(-20, 80), fp.by = quarter(-10, 50), fp.rb = quarter(0, 12);
            if (trial % 5 == 1) fp.by = fp.ay, fp.rb = fp.ra;         // horizontal sides
            if (trial % 5 == 2) fp.bx = fp.ax + 0.25f, fp.by = fp.ay;  // one disc holds the other
            fp.fullScreen = trial % 23 == 0;
            const FootprintSides sides = footprintSides(fp);
            const int y0 = 8 * int(rng.uniform() * 6), rowBegin = y0 + (trial % 3 == 0 ? 3 : 0);
            const int rowEnd = y0 + (trial % 4 == 0 ? 5 : 8);
            const int colMin = trial % 3 == 1 ? 7 : 0, colMax = trial % 3 == 1 ? 40 : width - 1;
            SplatRows rows;
            footprintBandColumns(fp, sides, y0, rowBegin, rowEnd, colMin, colMax, width, &rows);
            ASSERT_EQ(rows.rows, rowEnd - y0);
            for (int i = 0; i < rows.rows; ++i) {
                const int y = y0 + i;
                float sx0, sx1;
                bool hit = y >= rowBegin && footprintRowSpan(fp, float(y) + 0.5f, &sx0, &sx1);
                int x0 = 0, x1 = -1;
                if (hit) {
                    x0 = int(std::max(float(colMin), std::ceil(std::max(sx0, -1.0f) - 0.5f)));
                    x1 = int(std::min(float(colMax), std::floor(std::min(sx1, float(width) + 1.0f) - 0.5f)));
                }
                if (x1 < x0) {
                    EXPECT_GT(rows.x0[i], rows.x1[i]) << hwy::TargetName(target) << " trial " << trial << " row " << y;
                    continue;
                }
                ++rowsSeen;
                EXPECT_EQ(rows.x0[i], x0) << hwy::TargetName(target) << " trial " << trial << " row " << y;
                EXPECT_EQ(rows.x1[i], x1) << hwy::TargetName(target) << " trial " << trial << " row " << y;
            }
        }
        ++tried;
    }
    hwy::SetSupportedTargetsForTest(0);
    EXPECT_GE(tried, 2);
    EXPECT_GT(rowsSeen, 1000);
}
