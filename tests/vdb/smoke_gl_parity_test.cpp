// The GL splatter renders OpenVDB media through VdbDensityGrid::denseVolume: a real pass of the
// built-in smoke scene and of the real smoke_000002.vdb plume (stored free flights on beams and
// pixels, sigma_s read from the grid at every gather point) gives the same primary-segment image
// from GL as from the CPU rasterizer.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "loading/default_smoke_scene.h"
#include "cpu/pass_renderer.h"
#include "gpu/beam_splatter.h"
#include "gpu/gl_context.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_util.h"
#include "tests/vdb/grid_scenes.h"

namespace tyndall {
namespace {

/// Passes 0 and 3 of `scene`: GL and CPU primary-segment images agree.
void expectGlMatchesCpu(const Scene& scene, const RenderSettings& s, const char* name) {
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
        std::printf("%s, pass %llu: %zu beams, relative RMS GL vs CPU %.3g\n", name, (unsigned long long)pass,
                    photons.beams.size(), rms);
        EXPECT_LT(rms, test::kGlCpuParity) << "pass " << pass;  // measured 0 (bit-identical)
        EXPECT_EQ(test::coverageMismatches(gl, cpu, 1e-6f), 0) << "pass " << pass;
        double sum = 0;
        for (const Rgb& c : cpu.pixels) sum += c.luminance();
        EXPECT_GT(sum, 0.0) << "the splat should see the medium";
        if (rms >= test::kGlCpuParity) test::writeEvidence(name, gl, cpu);
    }
}

TEST(SmokeGlParity, RealPassOfTheSmokeSceneMatchesTheCpuRasterizer) {
    RenderSettings s;
    s.width = 128;
    s.height = 96;
    expectGlMatchesCpu(makeDefaultSmokeScene(), s, "smoke_scene_pass");
}

TEST(SmokeGlParity, RealVdbFileMatchesTheCpuRasterizer) {
    const std::string path = test::assetsDir() + "/vdb/openusd/smoke_000002.vdb";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "asset " << path << " absent (../shared/assets)";
    RenderSettings s;
    s.width = 96;
    s.height = 96;
    s.photonsPerPass = 2000;
    expectGlMatchesCpu(test::makeSmoke000002Room(path), s, "smoke_000002_pass");
}

}  // namespace
}  // namespace tyndall
