// Measurements, not checks: programs that print what a question about the renderer's bias needs
// (means over seeds and their standard errors) and assert nothing. They are built with the tests
// but not registered with ctest; run one with
//   build/tests/tyndall_measurements --gtest_filter=RoughFogBoxBias.*
// Their findings, and the bounds the tests take from them, are in docs/performance.md.
//
// Is PPB biased inside a rough dielectric box of fog under the sun? (cpu_equiangular_tests'
// EquiangularSunPpb.SunInsideARoughDielectricFogBoxAgreesWithThePathTracer bounds it.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "cpu/embree_scene.h"
#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

/// The means over the pixels that see each mesh of test::sunOverFogBoxes(true) (by pixelMeshes), for
/// each of `images`: their mean and standard error over the images.
std::vector<test::RegionEstimate> meshRegionMeans(const Scene& scene, const std::vector<int>& meshOfPixel,
                                                  const std::vector<Image>& images) {
    std::vector<test::RegionEstimate> out;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        std::vector<double> v;
        for (const Image& img : images) v.push_back(test::meanOverPixels(img, meshOfPixel, int(m)));
        const test::MeanVar mv = test::meanVar(v);
        out.push_back({mv.mean, std::sqrt(mv.var / double(v.size()))});
    }
    return out;
}

// About 3 CPU minutes (docs/performance.md "Is the rough box of fog biased?"): per mesh region at
// 32 x 32, 8 path-traced references of 4096 spp (independent seeds) against PPB at
// 0.5, 1 and 2 times the test's constant radii (16 batches of 32 passes of 24000 paths each), and
// the PPB means extrapolated linearly to radius 0 (least squares over the three radii).
TEST(RoughFogBoxBias, RegionMeansAgainstRadius) {
    const Scene scene = test::sunOverFogBoxes(true);
    const int size = 32;
    const std::vector<int> meshOfPixel = test::pixelMeshes(scene, size);
    EmbreeScene rt(scene);
    std::vector<Image> refs;
    for (uint64_t k = 0; k < 8; ++k) {
        ReferenceSettings rs;
        rs.width = rs.height = size;
        rs.samplesPerPixel = 4096;
        rs.seed = 100 + k;
        refs.push_back(ReferenceTracer(rt, rs).render().mean);
    }
    const std::vector<test::RegionEstimate> ref = meshRegionMeans(scene, meshOfPixel, refs);
    const float scales[3] = {0.5f, 1.0f, 2.0f};
    std::vector<std::vector<test::RegionEstimate>> ppb;
    for (float scale : scales) {
        std::vector<Image> batches;
        for (uint64_t seed = 0; seed < 4; ++seed) {
            RenderSettings ps = test::equiangularConstantRadii(size, 24000);
            ps.radius *= scale;
            ps.surfaceRadius *= scale;
            ps.seed = 200 + seed;
            PassRenderer renderer(scene, ps);
            for (uint64_t b = 0; b < 4; ++b) batches.push_back(test::renderPpbPasses(renderer, b * 32, 32));
        }
        ppb.push_back(meshRegionMeans(scene, meshOfPixel, batches));
    }
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        std::printf("%s: reference %.5f +- %.5f\n", scene.meshes[m].name.c_str(), ref[m].mean, ref[m].se);
        // Weighted least squares of mean = a + b scale; a and its standard error.
        double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (int r = 0; r < 3; ++r) {
            const test::RegionEstimate& e = ppb[size_t(r)][m];
            const double w = 1.0 / (e.se * e.se), x = scales[r], y = e.mean;
            sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
            const double d = y / ref[m].mean - 1, se = std::hypot(e.se, ref[m].se) / ref[m].mean;
            std::printf("  radii x%.1f: PPB %.5f +- %.5f, PPB / reference - 1 = %+.2f%% +- %.2f%%\n", scales[r], y,
                        e.se, 100 * d, 100 * se);
        }
        const double det = sw * sxx - sx * sx, a = (sxx * sy - sx * sxy) / det, seA = std::sqrt(sxx / det);
        const double se = std::hypot(seA, ref[m].se) / ref[m].mean;
        std::printf("  radius 0 (extrapolated): PPB %.5f +- %.5f, PPB / reference - 1 = %+.2f%% +- %.2f%% (%.1f se)\n",
                    a, seA, 100 * (a / ref[m].mean - 1), 100 * se, (a / ref[m].mean - 1) / se);
    }
}

}  // namespace
}  // namespace tyndall
