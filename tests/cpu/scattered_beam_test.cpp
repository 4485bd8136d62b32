// The kernel radius of beams after a scattering (RenderSettings::scatteredBeamMfp; docs/algorithm.md,
// "Beams after a scattering").
//
// 1. Which beams widen, and by how much: in a closed room of dense fog round a point light (equiangular
//    sampling off, so the light's own beams are stored), every beam that starts at a scattering
//    inside has the schedule's radius times max(1, C mfp / end radius) (at most 8), at the start of
//    the render and 1000 passes later (the factor rides on the shrinking schedule), and every beam
//    that starts at the light or leaves the wall has the schedule's radius.
// 2. Consistency and agreement: a dense sphere (mean free path 0.13, a fifth of its radius) lit by a
//    spot, seen through its index-matched hull (the camera segments through it gather the beams,
//    BeamBvh::query). With the widened beams 8 times the schedule's radius, the image mean
//    against the path tracer's: the kernel's bias (light lost where the kernel reaches past the
//    sphere's edge) must fall when every radius is 4 times smaller, and the smaller radii must
//    agree with the path tracer.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "core/density_grid.h"
#include "cpu/photon_tracer.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

TEST(ScatteredBeams, OnlyTheBeamsThatStartAtAScatteringWidenAndTheyShrinkWithTheSchedule) {
    // sigma_t 4 (mean free path 0.25) in a unit sphere with a diffuse wall, the light at its centre.
    const Medium fog = test::homogeneousMedium(Rgb(3.0f, 2.5f, 2.0f), Rgb(1.0f, 1.2f, 1.5f), 0.3f, "dense");
    const Scene scene = test::litMediumSphere(fog);
    RenderSettings ps = test::litMediumSphereSettings();
    ps.scatteredBeamMfp = 0.2;
    const RadiusSetup radii = RadiusSetup::resolve(ps, scene);
    // The factor: C mfp over the plan's end radius, with the shortest mean free path (sigma_t's largest
    // channel: 4 in red).
    const double end = 0.02 * radii.schedule.beamFactor(ps.plannedPaths);
    const double scale = std::min(8.0, 0.2 / 4.0 / end);
    std::printf("end radius %.5f, factor %.3f\n", end, scale);
    ASSERT_GT(scale, 2.0);
    EXPECT_NEAR(radii.scatteredScale(4.0f), scale, 1e-4 * scale);
    EXPECT_EQ(radii.scatteredScale(1000.0f), 1.0f);  // a mean free path under the end radius: no widening
    EXPECT_EQ(radii.scatteredScale(1e-6f), 8.0f);    // at most 8 times

    EmbreeScene rt(scene);
    PhotonTracer tracer(rt, ps, radii);
    for (uint64_t pass : {uint64_t(0), uint64_t(1000)}) {
        const PhotonMap map = tracer.trace(pass);
        // The pass's paths span a 1e-3 relative change of the schedule's radius.
        const double base = radii.beamRadiusOf(map.firstPath);
        int fromLight = 0, fromWall = 0, fromScattering = 0;
        for (const PhotonBeam& b : map.beams) {
            const float d = length(b.origin);
            // On the wall: the wall within 1e-4 straight outward.
            SurfaceHit hit;
            const bool wall = d > 0.99f && rt.intersect(Ray{b.origin, b.origin / d, 0.0f, 1e-4f}, &hit);
            const double want = d < 1e-4f ? base : wall ? base : d < 0.99f ? base * scale : -1;
            if (want < 0) continue;  // within 1% of the wall but not on it: left out
            (d < 1e-4f ? fromLight : wall ? fromWall : fromScattering)++;
            ASSERT_NEAR(b.radius, want, 2e-3 * want)
                << "pass " << pass << ", beam from " << b.origin.x << "," << b.origin.y << "," << b.origin.z;
        }
        std::printf("pass %llu: base radius %.5f, beams from the light %d, the wall %d, scatterings %d\n",
                    (unsigned long long)pass, base, fromLight, fromWall, fromScattering);
        EXPECT_GT(fromLight, 1000);
        EXPECT_GT(fromWall, 200);
        EXPECT_GT(fromScattering, 2000);
    }
}

/// A density of 1 everywhere in the unit sphere's box: a grid medium that traces as its homogeneous twin.
class UnitDensity : public DensityGrid {
public:
    float density(const Vec3& p) const override { return bounds().contains(p) ? 1.0f : 0.0f; }
    Bounds3 bounds() const override { return Bounds3{Vec3(-1.01f), Vec3(1.01f)}; }
    float maxDensity() const override { return 1.0f; }
    float meanDensity() const override { return 1.0f; }
};

TEST(ScatteredBeams, BeamsAfterAScatteringInAGridMediumKeepTheScheduleRadius) {
    // The room of the test above with its fog as a grid of density 1 (sigma_t 4 in every channel, the
    // mean free path of the test above): the beams after a scattering are not widened there (a wide
    // beam in a grid costs its gather a transmittance estimate through the grid for every camera
    // segment it overlaps).
    Medium fog = test::homogeneousMedium(Rgb(3.0f, 2.5f, 2.0f), Rgb(1.0f, 1.5f, 2.0f), 0.3f, "dense grid");
    fog.density = std::make_shared<UnitDensity>();
    ASSERT_FALSE(fog.homogeneous());
    const Scene scene = test::litMediumSphere(fog);
    RenderSettings ps = test::litMediumSphereSettings();
    ps.scatteredBeamMfp = 0.2;
    const RadiusSetup radii = RadiusSetup::resolve(ps, scene);
    ASSERT_GT(radii.scatteredScale(4.0f), 2.0f);  // the homogeneous twin's beams would widen
    EmbreeScene rt(scene);
    const PhotonMap map = PhotonTracer(rt, ps, radii).trace(0);
    const double base = radii.beamRadiusOf(map.firstPath);
    int fromScattering = 0;
    for (const PhotonBeam& b : map.beams) {
        const float d = length(b.origin);
        if (d > 1e-4f && d < 0.99f) ++fromScattering;
        ASSERT_NEAR(b.radius, base, 2e-3 * base)
            << "beam from " << b.origin.x << "," << b.origin.y << "," << b.origin.z;
    }
    std::printf("base radius %.5f, beams from scatterings %d\n", base, fromScattering);
    EXPECT_GT(fromScattering, 2000);
}

/// The dense sphere: radius 0.5 at the origin, sigma_s (6, 5.5, 5), sigma_a (1, 1.5, 2.5), g 0.3, an
/// index-matched hull in vacuum; a spot from the upper left on it, the camera in front.
Scene denseSphere() {
    const Medium amber = test::homogeneousMedium(Rgb(6.0f, 5.5f, 5.0f), Rgb(1.0f, 1.5f, 2.5f), 0.3f, "dense");
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-1.5f, 1.5f, 1.0f};
    spot.direction = normalize(-spot.position);
    spot.cosOuterAngle = std::cos(20.0f * kPi / 180.0f);
    spot.cosInnerAngle = std::cos(15.0f * kPi / 180.0f);
    spot.intensity = Rgb(4.0f);
    return test::makeMediumSphereScene(amber, 0.5f, spot, Camera::lookAt({0, 0, 2}, {0, 0, 0}, {0, 1, 0}, 0.6f));
}

using MeanEstimate = test::RegionEstimate;

/// PPB's image mean over 8 batches of `passes` / 8 passes, constant radii (beam `radius`), the
/// beams after a scattering C = 2 mean free paths (so 8 times `radius`, the most, for radii up to
/// 0.033), with its standard error from the batches' spread.
MeanEstimate ppbMean(const Scene& scene, float radius, int passes) {
    const int size = 16;
    RenderSettings ps = test::constantRadiusSettings(size, 2000, 5, true, 0.05f);
    ps.radius = radius;
    ps.photonAngle = 0;
    ps.scatteredBeamMfp = 2.0;
    PassRenderer renderer(scene, ps);
    EXPECT_NEAR(renderer.radii().scatteredScale(7.5f), 8.0f, 1e-4f);
    return test::ppbImageMean(renderer, size, passes);
}

TEST(ScatteredBeamsPpb, DenseSphereBiasFallsAsTheRadiiShrinkAndAgreesWithThePathTracer) {
    const Scene scene = denseSphere();
    const test::RegionEstimate ref = test::referenceImageMean(scene, 16, 2048, 17);
    const double reference = ref.mean, seRef = ref.se;

    // Widened beams of radius 0.16 (1.2 mean free paths, a third of the sphere's radius), 0.04, 0.01.
    const double radii[3] = {0.02, 0.005, 0.00125};
    double bias[3], se[3];
    for (int i = 0; i < 3; ++i) {
        const MeanEstimate m = ppbMean(scene, float(radii[i]), i < 2 ? 64 : 128);
        bias[i] = m.mean / reference - 1;
        se[i] = std::hypot(m.se, seRef) / reference;
        std::printf("path tracer %.5f +- %.5f; PPB, beams after a scattering %.3f wide: %.5f +- %.5f (%+.2f%%)\n",
                    reference, seRef, 8 * radii[i], m.mean, m.se, 100 * bias[i]);
    }
    // The wide kernel's bias is resolved (beyond 4 standard errors), and 4x smaller radii at least halve it.
    EXPECT_GT(std::abs(bias[0]), 4 * se[0]);
    EXPECT_LT(std::abs(bias[1]), 0.5 * std::abs(bias[0]));
    // The narrowest agree with the path tracer within 4 standard errors and 1% of kernel bias.
    EXPECT_LT(se[2], 0.01) << "too noisy to test";
    EXPECT_NEAR(bias[2], 0.0, 4 * se[2] + 0.01);
}

}  // namespace
}  // namespace tyndall
