// The hybrid render loop: with the same seed, GL-splatted and CPU-only renders of the default
// scene agree up to float rounding; reset and exit (from the display or another thread) throw
// away the passes in flight and the result equals a fresh render; the queue stays bounded; the
// --gpu modes choose and fall back as documented; AOV layers come from the GL splat; a GL failure
// mid-render finishes on the CPU keeping the passes done.
#include "hybrid/pass_scheduler.h"

#include <gtest/gtest.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <thread>

#include "loading/default_scene.h"
#include "core/error.h"
#include "hybrid/gl_thread.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/test_scenes.h"

using namespace tyndall;
using tyndall::test::kGlCpuParity;
using tyndall::test::mismatchedPixels;
using tyndall::test::relativeRms;

namespace {

RenderSettings smallSettings(uint64_t passes) {
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.passes = passes;
    s.photonsPerPass = 500;
    // One plan for every pass count, so renders of different lengths share their radii (the
    // prefix property holds for equal radii only; docs/algorithm.md).
    s.plannedPaths = 16 * 500;
    return s;
}

struct Rendered {
    Image image;
    std::vector<uint64_t> passOrder;
    int restarts = 0;
};

/// Renders with `mode`; `command(passesDone)` answers after every pass.
Rendered render(GpuMode mode, const Scene& scene, const RenderSettings& s,
                const std::function<DisplayCommand(uint64_t)>& command = {}) {
    PassScheduler scheduler(mode);
    PassRenderer renderer(scene, s);
    Accumulator acc(s.width, s.height);
    Rendered out;
    CallbackDisplay display(
        [&](const Accumulator& a, const RenderProgress& p) {
            EXPECT_EQ(a.passCount(), p.passesDone);
            out.passOrder.push_back(p.pass);
            return command ? command(p.passesDone) : DisplayCommand::Continue;
        },
        [&] { ++out.restarts; });
    scheduler.run(renderer, acc, 0, display);
    EXPECT_EQ(scheduler.hybrid(), mode == GpuMode::On);
    EXPECT_LE(scheduler.peakPassesHeld(), 2);
    out.image = acc.mean();
    return out;
}

const Scene& defaultScene() {
    static const Scene scene = [] {
        Scene s = makeDefaultScene();
        s.validate();
        return s;
    }();
    return scene;
}

}  // namespace

TEST(PassScheduler, HybridAndCpuOnlyGiveTheSameImage) {
    // What `tyndall render --gpu on` and `--gpu off` do with no options: the default scene at its
    // own settings, 512x512, 4000 photon paths a pass; its first 8 passes of 64 (the radii planned
    // for all 64, so these are exactly the first passes of that render).
    RenderSettings s = RenderSettings::fromJson(defaultSceneRender(), "default scene", RenderSettings());
    ASSERT_EQ(s.width, 512);
    ASSERT_EQ(s.passes, 64u);
    s.plannedPaths = s.passes * s.photonsPerPass;
    s.passes = 8;
    Rendered cpu = render(GpuMode::Off, defaultScene(), s);
    Rendered hybrid = render(GpuMode::On, defaultScene(), s);
    double rms = relativeRms(hybrid.image, cpu.image);
    int mismatched = mismatchedPixels(hybrid.image, cpu.image, 1e-4);
    std::printf("%llu passes, %dx%d: relative RMS hybrid vs CPU-only %.3g, %d pixels differ\n",
                (unsigned long long)s.passes, s.width, s.height, rms, mismatched);
    // Measured 3e-8 (the GL splat against the scalar CPU rasterizer; see kGlCpuParity).
    EXPECT_LT(rms, kGlCpuParity);
    EXPECT_EQ(mismatched, 0) << "pixels the GL side left uncovered or splatted twice";
    ASSERT_EQ(hybrid.passOrder.size(), s.passes);
    for (uint64_t i = 0; i < s.passes; ++i) EXPECT_EQ(hybrid.passOrder[i], i);
    if (rms >= kGlCpuParity || mismatched) tyndall::test::writeEvidence("hybrid_vs_cpu", hybrid.image, cpu.image);

    // The comparison means something: the primary-segment splat is a large part of the image.
    PassRenderer renderer(defaultScene(), s);
    PhotonMap photons = renderer.tracePhotons(0);
    CameraPassResult camera = renderer.traceCamera(0, photons);
    Image splat = renderer.splatPrimary(camera.primary, photons), none(s.width, s.height);
    Image full = splat;
    full += camera.radiance;
    EXPECT_GT(relativeRms(camera.radiance, full), 0.05);
}

TEST(PassScheduler, HybridAndCpuOnlyAgreeInAGridMedium) {
    // The default scene's fog made heterogeneous: the GL side samples the dense volume and reads
    // the stored free flights of every pixel and beam.
    Scene scene = defaultScene();
    scene.media[0].density = std::make_shared<tyndall::test::LatticeTestGrid>(scene.bounds, 12);
    scene.validate();
    RenderSettings s = smallSettings(16);
    Rendered cpu = render(GpuMode::Off, scene, s);
    Rendered hybrid = render(GpuMode::On, scene, s);
    double rms = relativeRms(hybrid.image, cpu.image);
    int mismatched = mismatchedPixels(hybrid.image, cpu.image, 1e-4);
    std::printf("grid medium, 16 passes: relative RMS hybrid vs CPU-only %.3g, %d pixels differ\n", rms, mismatched);
    EXPECT_LT(rms, kGlCpuParity);
    EXPECT_EQ(mismatched, 0) << "pixels the GL side left uncovered or splatted twice";
    if (rms >= kGlCpuParity || mismatched) tyndall::test::writeEvidence("hybrid_vs_cpu_grid", hybrid.image, cpu.image);
    EXPECT_GT(relativeRms(cpu.image, render(GpuMode::Off, defaultScene(), s).image), 0.02)
        << "the grid should change the image";
    PassRenderer renderer(scene, s);
    PhotonMap photons = renderer.tracePhotons(0);
    CameraPassResult camera = renderer.traceCamera(0, photons);
    ASSERT_GT(photons.freeFlightsPerBeam, 0);
    Image full = renderer.splatPrimary(camera.primary, photons);
    full += camera.radiance;
    EXPECT_GT(relativeRms(camera.radiance, full), 0.05) << "the primary splat should matter in the grid medium";
}

TEST(PassScheduler, RenderRegionOnGlHasTheWholeImagesPixelsAndZeroElsewhere) {
    // The GL splat with a scissor: inside the region the same fragments in the same order as in
    // the whole image (exact on llvmpipe), nothing outside; and the CPU twin agrees.
    RenderSettings s = smallSettings(4);
    Rendered whole = render(GpuMode::On, defaultScene(), s);
    s.region = {9, 5, 37, 29};
    Rendered part = render(GpuMode::On, defaultScene(), s), cpu = render(GpuMode::Off, defaultScene(), s);
    int different = 0, outside = 0, lit = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const Rgb &a = whole.image.at(x, y), &b = part.image.at(x, y);
            if (!s.region.contains(x, y)) {
                outside += !b.isBlack();
                continue;
            }
            different += a.r != b.r || a.g != b.g || a.b != b.b;
            lit += !b.isBlack();
        }
    EXPECT_EQ(different, 0);
    EXPECT_EQ(outside, 0);
    EXPECT_GT(lit, s.region.width * s.region.height / 2);
    EXPECT_LT(relativeRms(part.image, cpu.image), kGlCpuParity);
    EXPECT_EQ(mismatchedPixels(part.image, cpu.image, 1e-4), 0);
}

TEST(PassScheduler, FewerPassesAreExactlyTheFirstPassesOfMore) {
    // `--passes 8` is the first 8 passes of `--passes 16`, through the real render loop: the mean
    // the display sees after pass 8 of a 16-pass run equals the 8-pass run's result bit for bit,
    // in either mode (the queue and the GL thread do not reorder or leak passes).
    for (GpuMode mode : {GpuMode::Off, GpuMode::On}) {
        Image after8;
        PassScheduler scheduler(mode);
        PassRenderer renderer(defaultScene(), smallSettings(16));
        Accumulator acc(renderer.settings().width, renderer.settings().height);
        CallbackDisplay display([&](const Accumulator& a, const RenderProgress& p) {
            if (p.passesDone == 8) after8 = a.mean();
            return DisplayCommand::Continue;
        });
        scheduler.run(renderer, acc, 0, display);
        Rendered r8 = render(mode, defaultScene(), smallSettings(8));
        ASSERT_EQ(acc.passCount(), 16u);
        ASSERT_EQ(after8.pixels.size(), r8.image.pixels.size());
        EXPECT_TRUE(tyndall::test::identicalImages(after8, r8.image)) << "mode " << int(mode);
        EXPECT_FALSE(tyndall::test::identicalImages(after8, acc.mean())) << "passes 8..15 changed nothing";
    }
}

TEST(PassScheduler, ResetFromTheDisplayRestartsCleanly) {
    RenderSettings s = smallSettings(12);
    Rendered fresh = render(GpuMode::Off, defaultScene(), s);
    for (GpuMode mode : {GpuMode::Off, GpuMode::On}) {
        bool didReset = false;
        Rendered r = render(mode, defaultScene(), s, [&](uint64_t done) {
            if (done == 5 && !didReset) {
                didReset = true;
                return DisplayCommand::Reset;
            }
            return DisplayCommand::Continue;
        });
        EXPECT_EQ(r.restarts, 1);
        ASSERT_EQ(r.passOrder.size(), 5u + 12u);
        EXPECT_EQ(r.passOrder[5], 0u) << "the render restarts at pass 0";
        EXPECT_LT(relativeRms(r.image, fresh.image), kGlCpuParity) << "passes in flight at the reset leaked into the image";
        EXPECT_EQ(mismatchedPixels(r.image, fresh.image, 1e-4), 0) << "passes in flight at the reset leaked";
    }
}

TEST(PassScheduler, ExitFromTheDisplayStopsAfterThatPass) {
    RenderSettings s = smallSettings(50);
    for (GpuMode mode : {GpuMode::Off, GpuMode::On}) {
        Rendered r = render(mode, defaultScene(), s,
                            [](uint64_t done) { return done == 3 ? DisplayCommand::Exit : DisplayCommand::Continue; });
        EXPECT_EQ(r.passOrder.size(), 3u);
    }
}

TEST(PassScheduler, ResetAndExitFromAnotherThread) {
    // Requests are heard at the next stage boundary: at most one pass (one whose last stage was
    // under way) is added between a request and its effect.
    RenderSettings s = smallSettings(100000);
    for (GpuMode mode : {GpuMode::Off, GpuMode::On}) {
        PassScheduler scheduler(mode);
        PassRenderer renderer(defaultScene(), s);
        Accumulator acc(s.width, s.height);
        std::atomic<uint64_t> passes{0};
        std::atomic<int> restarts{0};
        std::atomic<bool> resetRequested{false}, exitRequested{false};
        int addedAfterReset = 0, addedAfterExit = 0;
        CallbackDisplay display(
            [&](const Accumulator&, const RenderProgress& p) {
                if (resetRequested && restarts == 0) ++addedAfterReset;
                if (exitRequested) ++addedAfterExit;
                passes = p.passesDone;
                return DisplayCommand::Continue;
            },
            [&] {
                passes = 0;
                ++restarts;
            });
        std::thread viewer([&] {
            while (passes < 3) std::this_thread::yield();
            resetRequested = true;
            scheduler.requestReset();
            while (restarts == 0) std::this_thread::yield();
            while (passes < 2) std::this_thread::yield();
            exitRequested = true;
            scheduler.requestExit();
        });
        RenderProgress p = scheduler.run(renderer, acc, 0, display);
        viewer.join();
        EXPECT_EQ(restarts, 1);
        EXPECT_LE(addedAfterReset, 1);
        EXPECT_LE(addedAfterExit, 1);
        EXPECT_GE(p.passesDone, 2u);
        EXPECT_EQ(acc.passCount(), p.passesDone);
    }
}

TEST(PassScheduler, CameraAndLightMovedAtAResetAreRendered) {
    // The viewer's reset: restarting() moves the camera (out of the fog, into the glass ball, so
    // the medium it sits in changes too) and the spot light; the render that follows equals a
    // fresh render of the moved scene.
    auto move = [](Scene& scene) {
        scene.camera = Camera::lookAt({0.05f, 0.0f, 0.1f}, {0, -0.4f, -1.5f}, {0, 1, 0}, 1.2f);
        scene.lights[0].position = {0.4f, 1.4f, 0.2f};
    };
    Scene moved = test::causticScene();
    move(moved);
    // The radii are resolved once per render (a reset keeps them): give every render the moved
    // scene's, as plain numbers.
    const RenderSettings s = PassRenderer(moved, smallSettings(6)).settings();
    PassRenderer freshRenderer(moved, s);
    Accumulator fresh(s.width, s.height);
    for (uint64_t i = 0; i < s.passes; ++i) fresh.addPass(freshRenderer.renderPass(i));

    Scene original = test::causticScene();
    PassRenderer unmovedRenderer(original, s);
    Accumulator unmoved(s.width, s.height);
    for (uint64_t i = 0; i < s.passes; ++i) unmoved.addPass(unmovedRenderer.renderPass(i));
    ASSERT_GT(relativeRms(unmoved.mean(), fresh.mean()), 0.1) << "the move should change the image";

    for (GpuMode mode : {GpuMode::Off, GpuMode::On}) {
        Scene scene = test::causticScene();
        PassScheduler scheduler(mode);
        PassRenderer renderer(scene, s);
        Accumulator acc(s.width, s.height);
        bool reset = false;
        CallbackDisplay display(
            [&](const Accumulator&, const RenderProgress& p) {
                if (p.passesDone == 3 && !reset) {
                    reset = true;
                    return DisplayCommand::Reset;
                }
                return DisplayCommand::Continue;
            },
            [&] { move(scene); });
        scheduler.run(renderer, acc, 0, display);
        ASSERT_TRUE(reset);
        ASSERT_EQ(acc.passCount(), s.passes);
        double rms = relativeRms(acc.mean(), fresh.mean());
        if (mode == GpuMode::Off) {
            EXPECT_EQ(rms, 0.0) << "CPU-only: the same passes bit for bit";
        } else {
            EXPECT_LT(rms, kGlCpuParity) << "hybrid: the same passes up to float rounding";
            EXPECT_EQ(mismatchedPixels(acc.mean(), fresh.mean(), 1e-4), 0) << "hybrid: pixels differ";
        }
    }
}

TEST(PassScheduler, TimeBudgetStopsTheRender) {
    RenderSettings s = smallSettings(1);
    s.timeBudget = 0.5;
    PassScheduler scheduler(GpuMode::On);
    PassRenderer renderer(defaultScene(), s);
    Accumulator acc(s.width, s.height);
    CallbackDisplay display([](const Accumulator&, const RenderProgress&) { return DisplayCommand::Continue; });
    RenderProgress p = scheduler.run(renderer, acc, 0, display);
    EXPECT_GE(p.passesDone, 1u);
    EXPECT_GE(p.elapsedSeconds, 0.5);
    EXPECT_LT(p.elapsedSeconds, 5.0);
}

TEST(PassScheduler, GpuModes) {
    EXPECT_EQ(gpuModeFromText("auto"), GpuMode::Auto);
    EXPECT_FALSE(gpuModeFromText("yes"));
    PassScheduler off(GpuMode::Off);
    EXPECT_FALSE(off.hybrid());
    EXPECT_TRUE(off.glDescription().empty());
    EXPECT_TRUE(off.notice().empty());
    // What auto does depends on this machine's OpenGL: a software rasterizer (llvmpipe) keeps the
    // splat on the CPU and says why in one line; a hardware GPU splats.
    bool software = false;
    {
        GlThread probe;  // throws (fails the test) without any OpenGL, as `on` below would
        software = probe.isSoftware();
        std::printf("OpenGL here: %s (%s)\n", probe.description().c_str(), software ? "software" : "hardware");
    }
    PassScheduler automatic(GpuMode::Auto);
    automatic.bind(defaultScene());
    if (software) {
        EXPECT_FALSE(automatic.hybrid());
        EXPECT_NE(automatic.notice().find("software"), std::string::npos) << automatic.notice();
        EXPECT_EQ(automatic.notice().find('\n'), std::string::npos);
        EXPECT_TRUE(automatic.glDescription().empty());
    } else {
        EXPECT_TRUE(automatic.hybrid());
        EXPECT_TRUE(automatic.notice().empty()) << automatic.notice();
        EXPECT_FALSE(automatic.glDescription().empty());
    }
    PassScheduler on(GpuMode::On);
    on.bind(defaultScene());
    EXPECT_TRUE(on.hybrid());
    EXPECT_FALSE(on.glDescription().empty());
}

TEST(PassScheduler, GridWithoutDenseFormFailsOnAndFallsBackOnAuto) {
    Scene scene = defaultScene();
    scene.media[0].name = "smoke";
    scene.media[0].sigmaA = Rgb(0.01f);
    scene.media[0].density = std::make_shared<tyndall::test::OpaqueTestGrid>(scene.bounds, 4);
    PassScheduler on(GpuMode::On);
    try {
        on.bind(scene);
        FAIL() << "--gpu on accepted a medium the GL splatter cannot render";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("--gpu on"), std::string::npos) << m;
        EXPECT_NE(m.find("'smoke'"), std::string::npos) << m;
    }
    SchedulerOptions softwareOk;
    softwareOk.autoAcceptsSoftwareGl = true;
    PassScheduler automatic(GpuMode::Auto, softwareOk);
    automatic.bind(scene);
    EXPECT_FALSE(automatic.hybrid());
    EXPECT_NE(automatic.notice().find("'smoke'"), std::string::npos) << automatic.notice();
    automatic.bind(defaultScene());
    EXPECT_TRUE(automatic.hybrid()) << "a scene it can splat brings the GL side back";
}

TEST(PassScheduler, BatchedPassesAgreeOnGlAndCpuAndWithTheWholePass) {
    // Bounded-memory passes: with --memory 64 each pass of 3000 photon paths is traced in
    // several batches; the GL splats of the batches are summed in batch order, the CPU twin sums
    // its per-batch images: both equal the one-batch render up to float rounding.
    RenderSettings whole = smallSettings(6);
    whole.photonsPerPass = 3000;
    RenderSettings batched = whole;
    batched.memoryMiB = 64;
    ASSERT_GT(PassRenderer(defaultScene(), batched).memoryPlan().batches, 2u);
    Rendered reference = render(GpuMode::Off, defaultScene(), whole);
    Rendered cpu = render(GpuMode::Off, defaultScene(), batched);
    Rendered hybrid = render(GpuMode::On, defaultScene(), batched);
    double rmsCpu = relativeRms(cpu.image, reference.image), rmsGl = relativeRms(hybrid.image, reference.image);
    std::printf("batched vs one batch: CPU relative RMS %.3g, hybrid %.3g\n", rmsCpu, rmsGl);
    EXPECT_LT(rmsCpu, 1e-5);
    EXPECT_LT(rmsGl, 1e-5);
    if (rmsGl >= 1e-5) tyndall::test::writeEvidence("batched_hybrid_vs_cpu", hybrid.image, reference.image);
}

namespace {
/// Fails the GL splat of every pass from `after` on, as a lost context would.
struct FailGlAfter : TestHooks {
    explicit FailGlAfter(uint64_t n) : after(n) {}
    bool failGlSplat(uint64_t pass) const override { return pass >= after; }
    uint64_t after;
};
}  // namespace

TEST(PassScheduler, GlFailureFinishesOnTheCpuKeepingThePassesDone) {
    // GL fails from pass 2 of 6 on (the splat throws on the GL thread): the render goes on with
    // one notice; the image is passes 0-1 from the GL splat and passes 2-5 from the CPU, bit for
    // bit, and agrees with a CPU render to GL/CPU parity. Pass 2's splat was in flight when it
    // failed: it is rendered again on the CPU, not dropped.
    const RenderSettings s = smallSettings(6);
    FailGlAfter hooks(2);
    SchedulerOptions options;
    options.hooks = &hooks;
    PassScheduler failing(GpuMode::On, options);
    PassRenderer renderer(defaultScene(), s);
    Accumulator acc(s.width, s.height);
    std::vector<std::string> notices;
    std::vector<uint64_t> order;
    CallbackDisplay display(
        [&](const Accumulator&, const RenderProgress& p) {
            order.push_back(p.pass);
            return DisplayCommand::Continue;
        },
        {}, [&](const std::string& line) { notices.push_back(line); });
    ASSERT_TRUE((failing.bind(defaultScene()), failing.hybrid()));
    RenderProgress p = failing.run(renderer, acc, 0, display);
    EXPECT_EQ(p.passesDone, 6u);
    EXPECT_EQ(order, (std::vector<uint64_t>{0, 1, 2, 3, 4, 5}));
    ASSERT_EQ(notices.size(), 1u);
    std::printf("notice: %s\n", notices[0].c_str());
    EXPECT_NE(notices[0].find("pass 3"), std::string::npos) << notices[0];
    EXPECT_FALSE(failing.hybrid()) << "the scheduler stays on the CPU after GL failed";

    // The expected sums: two passes through a working GL scheduler, then the CPU's passes.
    PassScheduler gl(GpuMode::On);
    Accumulator expected(s.width, s.height);
    CallbackDisplay twoPasses([](const Accumulator& a, const RenderProgress&) {
        return a.passCount() == 2 ? DisplayCommand::Exit : DisplayCommand::Continue;
    });
    gl.run(renderer, expected, 0, twoPasses);
    ASSERT_EQ(expected.passCount(), 2u);
    for (uint64_t pass = 2; pass < 6; ++pass) expected.addPass(renderer.renderPass(pass));
    EXPECT_TRUE(tyndall::test::identicalImages(acc.mean(), expected.mean()));
    const double rms = relativeRms(acc.mean(), render(GpuMode::Off, defaultScene(), s).image);
    std::printf("after the GL failure: relative RMS against the CPU render %.3g\n", rms);
    EXPECT_LT(rms, kGlCpuParity);

    // A later run of the same scheduler renders on the CPU without a second notice.
    Accumulator again(s.width, s.height);
    failing.run(renderer, again, 0, display);
    EXPECT_EQ(notices.size(), 1u);
    EXPECT_TRUE(tyndall::test::identicalImages(again.mean(), render(GpuMode::Off, defaultScene(), s).image));
}

TEST(PassScheduler, AovLayersComeFromTheGlSplat) {
    // With AOV layers on GL the beauty image is the plain GL render's bit for bit, the three
    // components add up to it, and each agrees with the CPU's layer to GL/CPU parity.
    const RenderSettings s = smallSettings(4);
    PassRenderer renderer(defaultScene(), s, BeamBvh::Kind::FlatCurves, true);
    CallbackDisplay display([](const Accumulator&, const RenderProgress&) { return DisplayCommand::Continue; });
    auto layersWith = [&](GpuMode mode) {
        PassScheduler scheduler(mode);
        LayerAccumulator layers(s.width, s.height, true);
        scheduler.run(renderer, layers, 0, display);
        EXPECT_EQ(scheduler.hybrid(), mode == GpuMode::On);
        EXPECT_EQ(layers.passCount(), 4u);
        return layers;
    };
    LayerAccumulator gl = layersWith(GpuMode::On), cpu = layersWith(GpuMode::Off);
    PassScheduler plainScheduler(GpuMode::On);
    Accumulator plain(s.width, s.height);
    plainScheduler.run(renderer, plain, 0, display);
    EXPECT_TRUE(tyndall::test::identicalImages(gl.beauty().mean(), plain.mean())) << "the layers changed the beauty";

    const ImageLayers glLayers = gl.imageLayers(), cpuLayers = cpu.imageLayers();
    ASSERT_EQ(glLayers.size(), 4u);
    const Image beauty = gl.beauty().mean();
    double worst = 0;
    for (size_t i = 0; i < beauty.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double sum = double(glLayers[0].second.pixels[i][c]) + glLayers[1].second.pixels[i][c] +
                         glLayers[2].second.pixels[i][c];
            worst = std::max(worst, std::abs(sum - beauty.pixels[i][c]) / std::max(double(beauty.pixels[i][c]), 1e-3));
        }
    EXPECT_LT(worst, 1e-5) << "media_primary + media_secondary + surface != beauty";
    for (int k = 0; k < 3; ++k) {
        const double rms = relativeRms(glLayers[k].second, cpuLayers[k].second);
        std::printf("layer %s: relative RMS GL vs CPU %.3g\n", glLayers[k].first.c_str(), rms);
        EXPECT_LT(rms, kGlCpuParity) << glLayers[k].first;
    }
    EXPECT_GT(relativeRms(Image(s.width, s.height), glLayers[0].second), 0.5) << "the splat layer is not empty";
}
