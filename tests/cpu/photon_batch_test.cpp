// Bounded-memory passes: a pass traced in photon batches is the pass.
//   BatchesSplitThePass: the batches' beams and photons are the whole pass's, bit for bit (same
//     streams, radii, and power divided by the pass's path count, not the batch's).
//   ABatchedPassIsTheWholePass: a pass rendered in many batches equals the one-batch pass up to
//     float rounding, on a scene with every estimate: primary beams (rasterizer), secondary beams
//     through glass (BVH gather), surface photons, and an area light seen directly and through the
//     glass (emission belongs to one batch only). Planted bugs: emission added in every batch, or
//     the power divided by the batch's paths, make it fail.
//   BatchedPassesDoNotDependOnThreads: bit-identical with 1 thread and with all.
//   MemoryPlan*: the batch size fits the budget, does not depend on the machine, and an image that
//     cannot fit is refused up front with the figures.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

#include "core/checkpoint.h"
#include "core/error.h"
#include "core/layer_accumulator.h"
#include "cpu/pass_renderer.h"
#include "loading/mesh_builders.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

/// The caustic test scene plus an area light on the far wall, visible directly and through the
/// glass sphere.
Scene batchScene() {
    Scene s = test::causticScene();
    Material lamp;
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.5f);
    lamp.emission = Rgb(3.0f, 2.5f, 2.0f);
    s.materials.push_back(lamp);
    s.meshes.push_back(makeQuad("lamp", {-0.4f, -0.9f, -1.49f}, {0.8f, 0, 0}, {0, 0.5f, 0}, int(s.materials.size()) - 1));
    s.finalize();
    s.validate();
    return s;
}

RenderSettings batchSettings(uint64_t memoryMiB) {
    RenderSettings s;
    s.width = 48;
    s.height = 36;
    s.photonsPerPass = 3000;
    s.seed = 11;
    s.memoryMiB = memoryMiB;
    return s;
}

double relativeDifference(const Image& a, const Image& ref, double* worst) {
    double num = 0, den = 0;
    *worst = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double d = double(a.pixels[i][c]) - double(ref.pixels[i][c]);
            num += d * d;
            den += double(ref.pixels[i][c]) * ref.pixels[i][c];
            *worst = std::max(*worst, std::abs(d) / (std::abs(double(ref.pixels[i][c])) + 1e-6));
        }
    return std::sqrt(num / std::max(den, 1e-30));
}

TEST(PhotonBatches, BatchesSplitThePass) {
    Scene scene = batchScene();
    PassRenderer renderer(scene, batchSettings(2048));
    const PhotonMap whole = renderer.tracePhotons(3);
    PhotonMap joined;
    for (auto [b, e] : {std::pair<uint32_t, uint32_t>{0, 137}, {137, 1000}, {1000, 1001}, {1001, 3000}}) {
        PhotonMap part = renderer.photonTracer().traceBatch(3, b, e);
        EXPECT_EQ(part.pathCount, e - b);
        EXPECT_EQ(part.firstPath, 3u * 3000u + b);
        joined.beams.insert(joined.beams.end(), part.beams.begin(), part.beams.end());
        joined.surfacePhotons.insert(joined.surfacePhotons.end(), part.surfacePhotons.begin(), part.surfacePhotons.end());
    }
    ASSERT_EQ(joined.beams.size(), whole.beams.size());
    ASSERT_EQ(joined.surfacePhotons.size(), whole.surfacePhotons.size());
    ASSERT_GT(whole.beams.size(), 1000u);
    ASSERT_GT(whole.surfacePhotons.size(), 100u);
    for (size_t i = 0; i < whole.beams.size(); ++i) {
        const PhotonBeam &a = joined.beams[i], &b = whole.beams[i];
        ASSERT_TRUE(a.origin.x == b.origin.x && a.origin.y == b.origin.y && a.origin.z == b.origin.z && a.tMax == b.tMax &&
                    a.radius == b.radius && a.power.r == b.power.r && a.power.g == b.power.g && a.power.b == b.power.b)
            << "beam " << i;
    }
    for (size_t i = 0; i < whole.surfacePhotons.size(); ++i) {
        const SurfacePhoton &a = joined.surfacePhotons[i], &b = whole.surfacePhotons[i];
        ASSERT_TRUE(a.position.x == b.position.x && a.position.y == b.position.y && a.radius == b.radius &&
                    a.power.r == b.power.r)
            << "surface photon " << i;
    }
}

TEST(PhotonBatches, ABatchedPassIsTheWholePass) {
    Scene scene = batchScene();
    PassRenderer whole(scene, batchSettings(2048));
    PassRenderer batched(scene, batchSettings(64));
    ASSERT_EQ(whole.memoryPlan().batches, 1u);
    ASSERT_GE(batched.memoryPlan().batches, 4u) << batched.memoryPlan().describe();
    std::printf("%s\n", batched.memoryPlan().describe().c_str());
    for (uint64_t pass : {0u, 5u}) {
        PassStats statsWhole, statsBatched;
        Image a = whole.renderPass(pass, &statsWhole);
        Image b = batched.renderPass(pass, &statsBatched);
        double worst = 0;
        double rms = relativeDifference(b, a, &worst);
        std::printf("pass %llu in %u batches vs one: relative RMS %.3g, worst pixel %.3g\n", (unsigned long long)pass,
                    batched.memoryPlan().batches, rms, worst);
        EXPECT_LT(rms, 1e-5);
        EXPECT_LT(worst, 1e-3);
        EXPECT_EQ(statsBatched.photonPaths, 3000u);
        EXPECT_EQ(statsBatched.beams, statsWhole.beams);
        EXPECT_EQ(statsBatched.surfacePhotons, statsWhole.surfacePhotons);
        EXPECT_GT(statsWhole.beamHits, 0u) << "the glass should give secondary segments that gather beams";
    }
}

TEST(PhotonBatches, BatchedPassesDoNotDependOnThreads) {
    Scene scene = batchScene();
    PassRenderer batched(scene, batchSettings(64));
    Image many = batched.renderPass(2), one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = batched.renderPass(2);
    }
    EXPECT_TRUE(test::identicalImages(many, one));
}

TEST(PhotonBatches, MemoryPlanFitsTheBudget) {
    for (uint64_t mib : {64u, 256u, 2048u})
        for (uint32_t photons : {1000u, 100000u, 30000000u}) {
            RenderSettings s = batchSettings(mib);
            s.width = s.height = 512;
            s.photonsPerPass = photons;
            if (mib == 64) s.width = s.height = 128;
            MemoryPlan plan = MemoryPlan::resolve(s, 4);
            EXPECT_LE(plan.peakBytes(), plan.budgetBytes) << plan.describe();
            EXPECT_GE(uint64_t(plan.batchPaths) * plan.batches, photons);
            EXPECT_LT(uint64_t(plan.batchPaths) * (plan.batches - 1), photons);
            // The bound holds for the longest paths: one beam and one photon per vertex.
            EXPECT_GE(plan.bytesPerPath, uint64_t(s.maxPhotonBounces) * (sizeof(PhotonBeam) + sizeof(SurfacePhoton)));
        }
}

TEST(PhotonBatches, AnImageThatCannotFitIsRefusedWithItsFigures) {
    RenderSettings s = batchSettings(2048);
    s.width = s.height = 16384;
    try {
        MemoryPlan::resolve(s, 0);
        FAIL() << "a 16384x16384 image fits 2 GiB?";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("--size 16384x16384"), std::string::npos) << m;
        EXPECT_NE(m.find("image buffers"), std::string::npos) << m;
        EXPECT_NE(m.find("GiB"), std::string::npos) << m;
        EXPECT_NE(m.find("--memory 2.0 GiB"), std::string::npos) << m;
    }
}

TEST(PhotonBatches, ImageBuffersCountAovLayersAndCheckpoints) {
    // The plan's figures against the real buffers: the sums of a LayerAccumulator and the bytes of
    // a checkpoint of them, with and without AOV layers.
    RenderSettings s = batchSettings(2048);
    s.width = 640;
    s.height = 400;
    s.photonsPerPass = 4000;
    const uint64_t pixels = uint64_t(s.width) * s.height;
    ImageBuffers plain = imageBuffers(s, 0, false), aov = imageBuffers(s, 0, true);
    for (bool layers : {false, true}) {
        const ImageBuffers& b = layers ? aov : plain;
        LayerAccumulator acc(s.width, s.height, layers);
        uint64_t sums = 0;
        for (const auto& [name, a] : acc.named()) sums += a.sums().size() * sizeof(double);
        EXPECT_EQ(b.sums, sums) << "aov " << layers;
        Checkpoint c;
        c.header = {{"scene", std::string(200, 's')}, {"settings", s.toJson()}, {"passes_done", 0}};
        c.layers = acc.named();
        const uint64_t serialized = serializeCheckpoint(c).size();
        EXPECT_GE(b.checkpoint, sums + serialized) << "a checkpoint holds the sums' copy and its bytes (aov " << layers << ")";
        EXPECT_EQ(b.total(), imageBufferBytes(s, 0, layers));
    }
    // The AOV pass: three component images more than the beauty pass, at least; the EXR writer's
    // 15 interleaved float channels.
    EXPECT_GE(aov.passes, plain.passes / 2 + pixels * 3 * sizeof(Rgb));
    EXPECT_GE(aov.output, pixels * 15 * sizeof(float));

    // A budget that holds the plain render's image buffers and all its photons in one batch gives
    // the AOV render smaller batches, both under the budget.
    const uint64_t mib = 1024 * 1024, bytesPerPath = photonPathBytes(s, 0);
    s.memoryMiB = (plain.total() + 2 * s.photonsPerPass * bytesPerPath) / mib + 1;
    MemoryPlan p = MemoryPlan::resolve(s, 0, false), q = MemoryPlan::resolve(s, 0, true);
    EXPECT_EQ(p.batches, 1u) << p.describe();
    EXPECT_GT(q.batches, 1u) << q.describe();
    EXPECT_LE(p.peakBytes(), p.budgetBytes);
    EXPECT_LE(q.peakBytes(), q.budgetBytes);
    // A budget under the AOV image buffers: the AOV render is refused with its figures, the plain one fits.
    s.memoryMiB = aov.total() / mib;
    ASSERT_LE(plain.total() + 2 * 256 * bytesPerPath, s.memoryMiB * mib) << "the plain render should fit";
    EXPECT_NO_THROW(MemoryPlan::resolve(s, 0, false));
    try {
        MemoryPlan::resolve(s, 0, true);
        FAIL() << "the AOV image buffers (" << formatBytes(aov.total()) << ") fit in --memory " << s.memoryMiB;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("AOV layers"), std::string::npos) << e.what();
    }
    // For the record (docs/production.md): 1920x1080 at the default --memory and --photons.
    RenderSettings hd;
    hd.width = 1920;
    hd.height = 1080;
    for (bool layers : {false, true})
        std::printf("1920x1080%s: %s\n", layers ? " --aov" : "", MemoryPlan::resolve(hd, 0, layers).describe().c_str());
}

}  // namespace
}  // namespace tyndall
