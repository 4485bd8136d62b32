// Photon points in dense media (RenderSettings::mediumPointMfp; docs/algorithm.md, "Photon points in
// dense media").
//
// 1. Which beams become points, and their radius: in a closed room of dense fog round a point light
//    (equiangular sampling off, so the light's own beams are stored), no beam starts at a
//    scattering inside; every stored point lies inside, in the fog, with the schedule's radius
//    times max(1, C mfp / end radius); in a thin fog (C mfp over 16 end radii) nothing changes.
// 2. Each path counted once, and the estimate's mean: dense spheres seen through their
//    index-matched hull (a white one, sigma_a 0, where light scattered twice or more is most of
//    the image; a coloured, absorbing, forward-scattering one): the image mean with points against
//    the path tracer's and against beams alone (a beam kept as well as its point would count the
//    multiple scattering twice: +50% or more in the white sphere).
// 3. The variance law: with constant radii the passes are independent, so the variance of the
//    mean over passes falls as 1 / passes (slope -1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cpu/photon_tracer.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

TEST(MediumPoints, TheBeamsAfterAScatteringInADenseMediumBecomePointsAtTheirScatterings) {
    // sigma_t 4 (mean free path 0.25) in a unit sphere with a diffuse wall, the light at its centre.
    const Medium dense = test::homogeneousMedium(Rgb(3.0f, 2.5f, 2.0f), Rgb(1.0f, 1.5f, 2.0f), 0.3f, "dense");
    const Scene scene = test::litMediumSphere(dense);
    RenderSettings ps = test::litMediumSphereSettings();
    ps.mediumPointMfp = 0.2;
    const RadiusSetup radii = RadiusSetup::resolve(ps, scene);
    const double end = 0.02 * radii.schedule.beamFactor(ps.plannedPaths);
    const double scale = std::max(1.0, 0.2 / 4.0 / end);
    std::printf("end radius %.5f, factor %.3f\n", end, scale);
    ASSERT_GT(scale, 2.0);
    EXPECT_NEAR(radii.pointScale(4.0f), scale, 1e-4 * scale);
    EXPECT_EQ(radii.pointScale(1000.0f), 1.0f);  // a mean free path under the end radius: the schedule's
    EXPECT_EQ(radii.pointScale(0.2f / 17.0f / float(end)), 0.0f);  // C mfp over 16 end radii: beams

    EmbreeScene rt(scene);
    PhotonTracer tracer(rt, ps, radii);
    for (uint64_t pass : {uint64_t(0), uint64_t(1000)}) {
        const PhotonMap map = tracer.trace(pass);
        const double base = radii.beamRadiusOf(map.firstPath);
        int fromScattering = 0;
        for (const PhotonBeam& b : map.beams) {
            const float d = length(b.origin);
            if (d > 1e-4f && d < 0.99f) ++fromScattering;
        }
        EXPECT_EQ(fromScattering, 0) << "beams that start at a scattering inside, pass " << pass;
        for (const MediumPoint& p : map.points) {
            ASSERT_LT(length(p.position), 1.0f);
            ASSERT_EQ(p.medium, 0);
            ASSERT_NEAR(p.radius, base * scale, 2e-3 * base * scale);
            ASSERT_GE(p.segment, 2u);  // a beam after a scattering: the light's first beam is segment 1
        }
        std::printf("pass %llu: %zu beams, %zu points\n", (unsigned long long)pass, map.beams.size(), map.points.size());
        EXPECT_GT(map.points.size(), size_t(2000));
    }

    // A thin fog: its mean free path is long against the radius, it keeps its beams.
    const Medium thin = test::homogeneousMedium(Rgb(0.05f), Rgb(0.01f), 0.3f, "thin");
    const Scene thinScene = test::litMediumSphere(thin);
    EmbreeScene thinRt(thinScene);
    const RadiusSetup thinRadii = RadiusSetup::resolve(ps, thinScene);
    EXPECT_EQ(thinRadii.pointScale(0.06f), 0.0f);
    const PhotonMap thinMap = PhotonTracer(thinRt, ps, thinRadii).trace(0);
    EXPECT_TRUE(thinMap.points.empty());
}

/// A dense sphere: radius 0.5 at the origin, an index-matched hull in vacuum; a spot from the upper
/// left on it, the camera in front.
Scene denseSphere(const Medium& medium, Vec3 camera = {0, 0, 2}) {
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-1.5f, 1.5f, 1.0f};
    spot.direction = normalize(-spot.position);
    spot.cosOuterAngle = std::cos(20.0f * kPi / 180.0f);
    spot.cosInnerAngle = std::cos(15.0f * kPi / 180.0f);
    spot.intensity = Rgb(4.0f);
    return test::makeMediumSphereScene(medium, 0.5f, spot, Camera::lookAt(camera, {0, 0, 0}, {0, 1, 0}, 0.6f));
}

using MeanEstimate = test::RegionEstimate;

/// PPB's image mean (green) over 8 batches of `passes` / 8 passes, constant radii (beams 0.005),
/// with photon points of C mean free paths (0 = beams only), with its standard error.
MeanEstimate ppbMean(const Scene& scene, double pointMfp, int passes) {
    const int size = 16;
    RenderSettings ps = test::constantRadiusSettings(size, 2000, 5, true, 0.05f);
    ps.radius = 0.005f;
    ps.photonAngle = 0;
    ps.mediumPointMfp = pointMfp;
    PassRenderer renderer(scene, ps);
    return test::ppbImageMean(renderer, size, passes);
}

/// The sphere's image mean with points (C 0.1: radius 0.1 mean free paths, a fortieth of the
/// sphere's radius; 256 passes) against the path tracer's and against beams alone (64 passes):
/// within 4 standard errors and 1.5% (the kernels' bias at the sphere's edge).
void expectPointsAgree(const Medium& medium, double minMultipleShare) {
    const Scene scene = denseSphere(medium);
    const test::RegionEstimate ref = test::referenceImageMean(scene, 16, 2048, 17);
    const double reference = ref.mean, seRef = ref.se;

    PassRenderer probe(scene, [] {
        RenderSettings ps = test::constantRadiusSettings(16, 2000, 5, true, 0.05f);
        ps.radius = 0.005f;
        ps.mediumPointMfp = 0.1;
        return ps;
    }());
    ASSERT_GT(probe.radii().pointScale(medium.sigmaT().maxComponent()), 1.0f) << "points wider than the beams";
    const EmbreeScene rt(scene);
    const PhotonMap map = PhotonTracer(rt, probe.settings(), probe.radii()).trace(0);
    ASSERT_GT(map.points.size(), size_t(1000));

    const MeanEstimate points = ppbMean(scene, 0.1, 256);
    const MeanEstimate beams = ppbMean(scene, 0.0, 64);
    // With equiangular single scattering, the beams' share: what a double count would add.
    const MeanEstimate single = [&] {
        RenderSettings ps = test::constantRadiusSettings(16, 2000, 5, true, 0.05f);
        ps.maxPathLength = 2;
        PassRenderer r(scene, ps);
        return MeanEstimate{test::regionMean(test::renderPpbPasses(r, 0, 8), 0, 0, 16, 16), 0};
    }();
    const double multiple = 1.0 - single.mean / reference;
    std::printf("path tracer %.5f +- %.5f (light scattered twice or more: %.0f%%); points %.5f +- %.5f (%+.2f%%), "
                "beams %.5f +- %.5f (%+.2f%%)\n",
                reference, seRef, 100 * multiple, points.mean, points.se, 100 * (points.mean / reference - 1),
                beams.mean, beams.se, 100 * (beams.mean / reference - 1));
    EXPECT_GT(multiple, minMultipleShare) << "the test needs multiple scattering to carry the image";
    EXPECT_NEAR(points.mean / reference, 1.0, 4 * std::hypot(points.se, seRef) / reference + 0.015);
    EXPECT_NEAR(points.mean / beams.mean, 1.0, 4 * std::hypot(points.se, beams.se) / beams.mean + 0.015);
}

TEST(MediumPointsPpb, AWhiteDenseSphereCountsEveryPathOnceAgainstThePathTracerAndTheBeams) {
    // sigma_s 7, no absorption: mean free path 0.14, the sphere 7 mean free paths across.
    expectPointsAgree(test::homogeneousMedium(Rgb(7.0f), Rgb(0.0f), 0.0f, "dense"), 0.5);
}

TEST(MediumPointsPpb, AColouredAbsorbingForwardScatteringSphereAgreesWithThePathTracer) {
    expectPointsAgree(test::homogeneousMedium(Rgb(6.0f, 5.5f, 5.0f), Rgb(1.0f, 1.5f, 2.5f), 0.3f, "dense"), 0.2);
}

TEST(MediumPointsPpb, VarianceFallsAsOneOverPasses) {
    // The camera close enough that the sphere fills the image (no black pixel).
    const Scene scene =
        denseSphere(test::homogeneousMedium(Rgb(6.0f, 5.5f, 5.0f), Rgb(1.0f, 1.5f, 2.5f), 0.3f, "dense"), {0, 0, 1.2f});
    // Points of radius 0.05 (C 0.1 mean free paths is less: the schedule's radius).
    RenderSettings ps = test::constantRadiusSettings(8, 200, 1, true, 0.05f);
    ps.radius = 0.05f;
    ps.photonAngle = 0;
    ps.mediumPointMfp = 0.1;
    // Each variance from 48 seeds is within ~20% (one standard deviation), so the slope over a
    // factor of 4 within ~0.2.
    const double slope = test::varianceSlopeOverPasses(scene, ps, 48, 100);
    EXPECT_NEAR(slope, -1.0, 0.3);
}

}  // namespace
}  // namespace tyndall
