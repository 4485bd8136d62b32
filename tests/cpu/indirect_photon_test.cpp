// The kernel radius of the indirect surface photons (RenderSettings::indirectPhotonSpread;
// docs/algorithm.md, "Indirect surface photons").
//
// 1. The factor: clamp(C l / end radius, 1, 8) rounded down to a quarter octave, 1 for l < 0.
// 2. Which photons widen: in the test caustic box (a spot over a glass ball in fog, direct light on),
//    every caustic photon (kPhotonDeltaPath: the spot's light through the glass alone) keeps the
//    schedule's radius, and every other stored photon (after a diffuse bounce or a scattering in the
//    fog) has the schedule's radius times a quarter octave in [1, 8], many of them more than 1.
// 3. Consistency and agreement: the walls box (white room, thin fog, a point light) with constant
//    radii and C 1 (the indirect photons up to 8 times the plain radius): the image mean against the
//    path tracer's falls within 4 standard errors and 1% when the radii are 4 times smaller.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cpu/photon_tracer.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_scenes.h"

namespace tyndall {
namespace {

TEST(IndirectPhotons, TheFactorIsTheClampedPathLengthInQuarterOctaves) {
    const Scene scene = test::causticScene();
    RenderSettings ps = test::constantRadiusSettings(16, 1000, 3, true, 0.05f);
    ps.photonAngle = 0;
    ps.indirectPhotonSpread = 0.1;
    const RadiusSetup radii = RadiusSetup::resolve(ps, scene);
    const double end = 0.05 * radii.schedule.surfaceFactor(plannedPhotonPaths(ps));
    EXPECT_NEAR(radii.indirectPerLength, 0.1 / end, 1e-6 / end);
    EXPECT_EQ(radii.indirectScale(-1.0), 1.0f);
    EXPECT_EQ(radii.indirectScale(0.0), 1.0f);
    EXPECT_EQ(radii.indirectScale(0.5 * end / 0.1), 1.0f);  // C l under the end radius: no widening
    EXPECT_EQ(radii.indirectScale(3.0 * end / 0.1), std::exp2(6.0f / 4.0f));  // 3 rounds down to 2^1.5
    EXPECT_EQ(radii.indirectScale(4.2 * end / 0.1), 4.0f);  // 4.2 rounds down to 4
    EXPECT_EQ(radii.indirectScale(1e6), 8.0f);  // at most 8 times
    RenderSettings off = ps;
    off.indirectPhotonSpread = 0;
    EXPECT_EQ(RadiusSetup::resolve(off, scene).indirectScale(1e6), 1.0f);
}

TEST(IndirectPhotons, CausticPhotonsKeepTheScheduleAndTheOthersWidenInQuarterOctaves) {
    const Scene scene = test::causticScene();
    RenderSettings ps = test::constantRadiusSettings(16, 4000, 3, true, 0.02f);
    ps.photonAngle = 0;
    ps.indirectPhotonSpread = 0.05;  // 2.5 end radii per unit length: the room is 3 wide
    const RadiusSetup radii = RadiusSetup::resolve(ps, scene);
    EmbreeScene rt(scene);
    PhotonTracer tracer(rt, ps, radii);
    const PhotonMap map = tracer.trace(0);
    const double base = radii.surfaceRadiusOf(map.firstPath);
    int caustic = 0, indirect = 0, widened = 0;
    for (const SurfacePhoton& p : map.surfacePhotons) {
        const double ratio = p.radius / base;
        if (p.flags & kPhotonDeltaPath) {
            ++caustic;
            ASSERT_NEAR(ratio, 1.0, 1e-5) << "a caustic photon widened";
            continue;
        }
        ++indirect;
        const double octaves = 4.0 * std::log2(ratio);
        ASSERT_NEAR(octaves, std::round(octaves), 1e-4) << "ratio " << ratio;
        ASSERT_GE(ratio, 1.0 - 1e-5);
        ASSERT_LE(ratio, 8.0 + 1e-5);
        widened += ratio > 1.01;
    }
    std::printf("caustic photons %d, indirect %d, of which widened %d\n", caustic, indirect, widened);
    EXPECT_GT(caustic, 200);
    EXPECT_GT(indirect, 200);
    EXPECT_GT(widened, indirect / 2);
}

/// PPB's image mean over 8 batches of `passes` / 8 passes, constant radii, the indirect photons up to
/// 8 times the surface radius, with its standard error from the batches' spread.
using MeanEstimate = test::RegionEstimate;
MeanEstimate ppbMean(const Scene& scene, float surfaceRadius, int passes) {
    const int size = 16;
    RenderSettings ps = test::constantRadiusSettings(size, 2000, 5, true, surfaceRadius);
    ps.photonAngle = 0;
    ps.indirectPhotonSpread = 1.0;
    PassRenderer renderer(scene, ps);
    return test::ppbImageMean(renderer, size, passes);
}

TEST(IndirectPhotonsPpb, WallsBoxAgreesWithThePathTracerAsTheRadiiShrink) {
    const Scene scene = test::wallsFogBox();
    const test::RegionEstimate ref = test::referenceImageMean(scene, 16, 1024, 17);
    const double reference = ref.mean, seRef = ref.se;
    const double radii[2] = {0.08, 0.02};
    double bias[2], se[2];
    for (int i = 0; i < 2; ++i) {
        const MeanEstimate m = ppbMean(scene, float(radii[i]), i == 0 ? 32 : 64);
        bias[i] = m.mean / reference - 1;
        se[i] = std::hypot(m.se, seRef) / reference;
        std::printf("path tracer %.5f +- %.5f; PPB, surface radius %.3f (indirect up to %.3f): %.5f +- %.5f (%+.2f%%)\n",
                    reference, seRef, radii[i], 8 * radii[i], m.mean, m.se, 100 * bias[i]);
    }
    EXPECT_LT(se[1], 0.01) << "too noisy to test";
    EXPECT_NEAR(bias[1], 0.0, 4 * se[1] + 0.01);
}

}  // namespace
}  // namespace tyndall
