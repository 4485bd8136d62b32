// Glossy vertices (docs/algorithm.md, "Glossy vertices"): PPB converges to the reference path
// tracer on the consistency room (reference_fixtures.h) with its mirror made a rough GGX conductor
// and its glass sphere rough GGX glass, in fog. The spot now lights the rough metal directly
// (the reference reaches that through next-event estimation at the glossy vertex; PPB through the
// delta-direct photons stored there), so every glossy route is exercised: camera paths continuing
// by sampling (beams gathered on the continuation), surface photons gathered with the BSDF,
// photons scattering by sampling, rough transmission in and out of the sphere.
#include <gtest/gtest.h>

#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

Scene glossyConsistencyScene() {
    Scene s = test::makeConsistencyScene();
    s.name = "glossy-consistency-room";
    for (Material& m : s.materials) {
        if (m.name == "mirror") {
            m.roughness = 0.4f;
            m.albedo = Rgb(0.95f, 0.75f, 0.45f);
        }
        if (m.name == "glass") m.roughness = 0.3f;
    }
    // Aim the spot at the metal panel on the back wall (the smooth version avoids it).
    for (Light& l : s.lights)
        if (l.name == "spot") l.direction = normalize(Vec3(-0.5f, 0.9f, -0.99f) - l.position);
    s.finalize();
    s.validate();
    return s;
}

TEST(GlossyConsistency, RoughMetalAndRoughGlassInFogConvergeToReference) {
    Scene scene = glossyConsistencyScene();
    ASSERT_TRUE(scene.materials[3].isGlossy());
    ASSERT_TRUE(scene.materials[4].isGlossy());
    // Measured here: relMSE 0.093, 0.047, 0.025 after 4, 16, 64 passes. The glossy reference is
    // noisier at 4096 spp (variance 0.0046, already subtracted from the relMSE): it may be up to
    // half of what it judges. Regions after 256 passes (the regional check): rough metal 0.984 +-
    // 0.007, floor 0.993 +- 0.012, rough glass 0.996 +- 0.022 (PPB 0.020, reference 0.010). The
    // rough glass region needs the 256 passes: at 64 its standard error was 0.040, a tolerance of
    // 4 se + 0.03 = 0.19 that would pass a sphere 15% too dark.
    test::ConsistencyBounds bounds{0.04};
    bounds.passes = 256;
    bounds.referenceVarianceShare = 0.5;
    test::expectPpbConvergesToReference(scene, bounds, 303, 404, "glossy_consistency");
}

}  // namespace
}  // namespace tyndall
