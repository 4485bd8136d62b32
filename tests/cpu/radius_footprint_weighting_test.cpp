// The automatic radii where the existing tests are blind (tests/cpu/radius_defaults_test.cpp uses a
// fog tunnel in which every ray sees the same depths, so how the samples are weighted never shows):
//   - the media footprint is the median of depths weighted by the ray length each sample stands
//     for: half the image sees fog to depth 1, half to depth 9, and the closed-form weighted median
//     is depth 4 (an unweighted median of the samples would be ~0.9);
//   - an explicit --radius with the automatic offset: the schedule shrinks that radius to the
//     planned end radius (half a media footprint) over the planned paths, its factors are the PPB
//     sequence (Gamma-function closed form written here), and a radius already below the end stays.
#include <gtest/gtest.h>

#include <cmath>

#include "cpu/pass_renderer.h"
#include "cpu/pixel_footprint.h"
#include "cpu/radius_defaults.h"
#include "loading/mesh_builders.h"

namespace tyndall {
namespace {

constexpr float kFov = 0.3f;

/// Fog everywhere; the camera at the origin looks down -z; a wall at depth 1 covers the left half
/// of the view (x < 0), the back wall at depth 9 the rest.
Scene twoDepths() {
    Scene s;
    s.name = "two-depths";
    s.source = "<test>";
    Material wall;
    wall.name = "wall";
    wall.albedo = Rgb(0.5f);
    s.materials = {wall};
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.1f);
    s.media.push_back(fog);
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("room", Vec3(-10, -10, -9), Vec3(10, 10, 1), 0, /*inward=*/true));
    s.meshes.push_back(makeQuad("near", {-5, -5, -1}, {5, 0, 0}, {0, 10, 0}, 0));
    Light l;
    l.name = "bulb";
    l.type = LightType::Point;
    l.position = {3, 3, -5};
    s.lights.push_back(l);
    s.camera = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, kFov);
    s.finalize();
    s.validate();
    return s;
}

double footprintAt(double depth, int height) { return depth * 2.0 * std::tan(0.5 * kFov) / height; }

TEST(RadiusFootprintWeighting, MediaFootprintIsTheLengthWeightedMedianDepth) {
    Scene s = twoDepths();
    EmbreeScene rt(s);
    for (int height : {48, 64}) {
        PixelFootprint f = measurePixelFootprint(rt, s.camera, 64, height);
        // Each ray's fog is uniform in depth with weight 1 per unit depth: the near half holds
        // [0, 1], the far half [0, 9]. Cumulative weight up to depth z >= 1: 1 + z (per pair of
        // rays) of 10 in all; half of it at z = 4. The samples are 9/32 apart on the far rays and
        // the view's cosines (>= 0.98) spread them: within 6%.
        EXPECT_NEAR(f.media / footprintAt(4.0, height), 1.0, 0.06) << "height " << height;
        EXPECT_DOUBLE_EQ(f.mediaFraction, 1.0);
    }
}

/// R(j + n0) / R(n0) of the PPB sequence R(n+1)/R(n) = (n + alpha)/(n + 1), from Gamma functions.
double ppbFactor(double alpha, uint64_t offset, uint64_t j) {
    const double n0 = double(offset) + 1, n = n0 + double(j);
    return std::exp(std::lgamma(n + alpha) - std::lgamma(n + 1) - std::lgamma(n0 + alpha) + std::lgamma(n0 + 1));
}

TEST(RadiusFootprintWeighting, AnExplicitRadiusWithTheAutomaticOffsetShrinksToThePlannedEnd) {
    Scene s = twoDepths();
    EmbreeScene rt(s);
    RenderSettings in;
    in.width = 64;
    in.height = 48;
    in.photonsPerPass = 1000;
    in.passes = 200;
    in.alpha = 0.6;
    const double media = measurePixelFootprint(rt, s.camera, in.width, in.height).media;
    const double end = RadiusDefaults::kBeamEndFootprints * media;
    for (double startOverEnd : {12.0, 1.7}) {
        in.radius = float(startOverEnd * end);
        PassRenderer r(s, in);
        const RenderSettings& out = r.settings();
        const uint64_t planned = out.plannedPaths;
        SCOPED_TRACE("radius " + std::to_string(startOverEnd) + " end radii");
        ASSERT_EQ(planned, 200000u);
        EXPECT_EQ(out.radius, in.radius) << "an explicit radius keeps its value";
        EXPECT_NE(out.radiusOffset, RenderSettings::kAutoRadiusOffset);
        EXPECT_FLOAT_EQ(r.radii().beamRadiusOf(0), in.radius);
        // The end of the plan: half a footprint (the offset is a whole path count: within 1%).
        EXPECT_NEAR(r.radii().beamRadiusOf(planned) / end, 1.0, 0.01);
        // In between, the PPB sequence from the resolved offset.
        for (uint64_t j : {uint64_t(1000), planned / 3, planned})
            EXPECT_NEAR(r.radii().beamRadiusOf(j) / in.radius, ppbFactor(in.alpha, out.radiusOffset, j), 1e-5);
    }
    // A radius already below the end radius stays (nearly) constant over the plan.
    in.radius = float(0.5 * end);
    PassRenderer r(s, in);
    EXPECT_GT(r.radii().beamRadiusOf(r.settings().plannedPaths) / in.radius, 0.99);
}

}  // namespace
}  // namespace tyndall
