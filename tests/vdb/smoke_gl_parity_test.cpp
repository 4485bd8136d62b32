// The GL splatter renders OpenVDB media through VdbDensityGrid::denseVolume: a real pass of the
// built-in smoke scene (stored free flights on beams and pixels, sigma_s read from the grid at
// every gather point) gives the same primary-segment image from GL as from the CPU rasterizer.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/default_smoke_scene.h"
#include "cpu/pass_renderer.h"
#include "gpu/beam_splatter.h"
#include "gpu/gl_context.h"
#include "tests/gpu/gpu_test_util.h"

namespace tyndall {
namespace {

TEST(SmokeGlParity, RealPassOfTheSmokeSceneMatchesTheCpuRasterizer) {
    Scene scene = makeDefaultSmokeScene();
    RenderSettings s;
    s.width = 128;
    s.height = 96;
    PassRenderer renderer(scene, s);
    auto ctx = GlContext::create();
    GlBeamSplatter splatter(*ctx, scene);
    for (uint64_t pass : {0u, 3u}) {
        PhotonMap photons = renderer.tracePhotons(pass);
        CameraPassResult camera = renderer.traceCamera(pass, photons);
        ASSERT_GT(camera.primary.freeFlightsPerRay, 0);
        Image cpu = renderer.splatPrimary(camera.primary, photons);
        Image gl = splatter.splat(camera.primary, photons);
        double rms = test::relativeRms(gl, cpu);
        std::printf("pass %llu: %zu beams, relative RMS GL vs CPU %.3g\n", (unsigned long long)pass,
                    photons.beams.size(), rms);
        EXPECT_LT(rms, 1e-3) << "pass " << pass;
        EXPECT_EQ(test::coverageMismatches(gl, cpu, 1e-6f), 0) << "pass " << pass;
        if (rms >= 1e-3) test::writeEvidence("smoke_scene_pass", gl, cpu);
    }
}

}  // namespace
}  // namespace tyndall
