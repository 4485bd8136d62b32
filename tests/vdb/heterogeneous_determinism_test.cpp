// The stream discipline in heterogeneous media: every free-flight distance (photon beams' stored
// distances, each pixel's primary distances, delta-tracked photon scattering, secondary camera
// segments) comes from a stream keyed by (seed, pass, path or pixel, purpose), never by thread:
// one thread or many, any pass order, the photon map and the pass image are bit-identical.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "loading/default_smoke_scene.h"
#include "cpu/pass_renderer.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

TEST(HeterogeneousDeterminism, FreeFlightsAndPassImagesDoNotDependOnThreads) {
    Scene scene = makeDefaultSmokeScene();
    RenderSettings s;
    s.width = 48;
    s.height = 40;
    s.photonsPerPass = 500;
    s.seed = 9;
    PassRenderer renderer(scene, s);
    PhotonMap many = renderer.tracePhotons(5);
    CameraPassResult camMany = renderer.traceCamera(5, many);
    Image imgMany = renderer.renderPass(5);
    PhotonMap one;
    CameraPassResult camOne;
    Image imgOne;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        (void)renderer.renderPass(2);  // another pass first
        one = renderer.tracePhotons(5);
        camOne = renderer.traceCamera(5, one);
        imgOne = renderer.renderPass(5);
    }
    ASSERT_EQ(many.freeFlightsPerBeam, s.freeFlightSamples);
    ASSERT_EQ(many.freeFlights.size(), many.beams.size() * size_t(s.freeFlightSamples));
    EXPECT_EQ(many.freeFlights, one.freeFlights);
    ASSERT_EQ(many.beams.size(), one.beams.size());
    for (size_t i = 0; i < many.beams.size(); ++i) ASSERT_EQ(many.beams[i].tMax, one.beams[i].tMax) << i;
    EXPECT_EQ(camMany.primary.freeFlights, camOne.primary.freeFlights);
    EXPECT_TRUE(test::identicalImages(camMany.radiance, camOne.radiance));
    EXPECT_TRUE(test::identicalImages(imgMany, imgOne));
    // The smoke really is sampled: some primary distances are finite, some beams stop inside.
    size_t finite = 0;
    for (float d : camMany.primary.freeFlights) finite += std::isfinite(d) ? 1 : 0;
    EXPECT_GT(finite, 0u);
    EXPECT_LT(finite, camMany.primary.freeFlights.size());
}

}  // namespace
}  // namespace tyndall
