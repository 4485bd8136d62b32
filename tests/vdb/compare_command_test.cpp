// `tyndall compare`: the homogeneous twin keeps albedo and g and takes the grid's mean density; the
// command writes one side-by-side image with labels and one EXR per half, with equal pass counts;
// a scene without a grid medium is a clear error. Also the bitmap label font.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app/cmd_compare.h"
#include "app/label_text.h"
#include "loading/default_scene.h"
#include "loading/default_smoke_scene.h"
#include "loading/homogeneous_twin.h"
#include "core/error.h"
#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace tyndall {
namespace {

TEST(HomogeneousTwin, KeepsAlbedoAndGAndUsesTheMeanDensity) {
    Scene smoke = makeDefaultSmokeScene();
    const Medium& grid = smoke.media[smoke.globalMedium];
    ASSERT_FALSE(grid.homogeneous());
    std::vector<float> used;
    Scene twin = makeHomogeneousTwin(smoke, -1.0f, &used, TwinRegion::Domain);
    const Medium& hom = twin.media[twin.globalMedium];
    ASSERT_TRUE(hom.homogeneous());
    ASSERT_EQ(used.size(), 1u);
    EXPECT_FLOAT_EQ(used[0], grid.density->meanDensity());
    EXPECT_GT(used[0], 0.0f);
    EXPECT_LT(used[0], grid.density->maxDensity());
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(hom.albedo()[c], grid.albedo()[c], 1e-6f);
        EXPECT_NEAR(hom.sigmaT()[c], grid.sigmaT()[c] * used[0], 1e-6f);
    }
    EXPECT_EQ(hom.g, grid.g);
    // The scene is otherwise the same.
    EXPECT_EQ(twin.meshes.size(), smoke.meshes.size());
    EXPECT_EQ(twin.lights.size(), smoke.lights.size());
    // An explicit density.
    Scene fixed = makeHomogeneousTwin(smoke, 0.5f, nullptr, TwinRegion::Domain);
    EXPECT_NEAR(fixed.media[fixed.globalMedium].sigmaS.r, grid.sigmaS.r * 0.5f, 1e-6f);
    // Nothing to compare in a scene without grids.
    EXPECT_THROW(makeHomogeneousTwin(makeDefaultScene()), Error);
}

TEST(CompareCommand, WritesLabelledHalvesAndOneExrPerHalf) {
    CLI::App app;
    int exitCode = -1;
    app::addCompareCommand(app, exitCode);
    const std::string out = test::outputDir() + "/compare-test.exr";
    std::vector<std::string> args = {"tyndall",   "compare", "--size", "64x48", "--passes", "2",
                                     "--photons", "300",     "--gpu",  "off",   "-o",       out};
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    app.parse(int(argv.size()), const_cast<char**>(argv.data()));
    EXPECT_EQ(exitCode, 0);

    Image both = readImage(out);
    Image het = readImage(test::outputDir() + "/compare-test-heterogeneous.exr");
    Image hom = readImage(test::outputDir() + "/compare-test-homogeneous.exr");
    ASSERT_EQ(het.width, 64);
    ASSERT_EQ(het.height, 48);
    ASSERT_EQ(hom.width, 64);
    const int gap = both.width - 2 * 64;
    EXPECT_GE(gap, 2);
    ASSERT_EQ(both.height, 48);
    // Outside the label boxes the halves are the per-half images; the gap is black.
    const int labelBottom = 2 + app::labelHeight(1);
    for (int y = labelBottom; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            ASSERT_EQ(both.at(x, y).g, het.at(x, y).g);
            ASSERT_EQ(both.at(64 + gap + x, y).g, hom.at(x, y).g);
        }
    for (int y = 0; y < 48; ++y) ASSERT_EQ(both.at(64, y).g, 0.0f);
    // Label glyphs are drawn (value 20) inside each half's label box.
    int lit[2] = {0, 0};
    for (int y = 0; y < labelBottom; ++y)
        for (int x = 0; x < 64; ++x) {
            lit[0] += both.at(x, y).g == 20.0f;
            lit[1] += both.at(64 + gap + x, y).g == 20.0f;
        }
    EXPECT_GT(lit[0], 20);
    EXPECT_GT(lit[1], 20);
    // The two media differ: the images are not the same.
    double diff = 0;
    for (size_t i = 0; i < het.pixels.size(); ++i) diff += std::abs(het.pixels[i].g - hom.pixels[i].g);
    EXPECT_GT(diff, 0.0);
}

namespace {
/// Whether process `pid` runs the tyndall binary (its exec is done: before, the forked child has
/// the test's signal handlers) and has a handler for SIGINT (Linux: SigCgt in /proc/PID/status).
bool catchesSigint(pid_t pid) {
    std::error_code ec;
    auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
    if (ec || !std::filesystem::equivalent(exe, TYNDALL_BINARY, ec)) return false;
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (SIGINT - 1)) & 1;
    return false;
}

}  // namespace

TEST(CompareCommand, SceneFileAndExplicitDensity) {
    const std::string out = test::outputDir() + "/compare-scene.png";
    test::CliRun r = test::runTyndall("compare " + std::string(TYNDALL_SOURCE_DIR) +
                                      "/scenes/caustic-box-smoke.json --density 0.5 --size 48x32 " +
                                      "--passes 2 --photons 200 --gpu off -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 passes each"), std::string::npos) << r.output;
    const std::string hom = test::outputDir() + "/compare-scene-homogeneous.exr";
    EXPECT_EQ(readImageAttribute(hom, "tyndall:twin_density"), "0.5");
    EXPECT_EQ(readImageAttribute(hom, "tyndall:half"), "homogeneous");
    EXPECT_EQ(readImageAttribute(hom, "tyndall:passes"), "2");
    EXPECT_NE(readImageAttribute(hom, "tyndall:scene").find("caustic-box-smoke.json"), std::string::npos);
    Image both = readImage(out);
    EXPECT_EQ(both.height, 32);
    EXPECT_GT(both.width, 2 * 48);

    // A scene without a density grid has nothing to compare: one line, non-zero exit.
    test::CliRun bad = test::runTyndall("compare " + std::string(TYNDALL_SOURCE_DIR) +
                                        "/scenes/caustic-box.json --passes 1 --size 16x16 -o " + test::outputDir() +
                                        "/compare-bad.png");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_EQ(std::count(bad.output.begin(), bad.output.end(), '\n'), 1) << bad.output;
    test::CliRun negative =
        test::runTyndall("compare --density -1 --passes 1 --gpu off -o " + test::outputDir() + "/compare-bad.png");
    EXPECT_NE(negative.exitCode, 0);
    EXPECT_NE(negative.output.find("--density"), std::string::npos) << negative.output;
}

/// Mean of channel `c` over an image.
double imageMean(const Image& img, int c) {
    double sum = 0;
    for (const Rgb& p : img.pixels) sum += p[c];
    return sum / double(img.pixels.size());
}

TEST(CompareCommand, AnEmittingGridsTwinGlows) {
    // A procedural fire in a dark room, the only light: the twin lights the room only if it carries
    // the fire's emission (the grid's power, spread over its support box).
    const std::string dir = test::outputDir() + "/compare-fire";
    std::filesystem::create_directories(dir);
    std::ofstream(dir + "/fire.json") << R"({
  "materials": [{"name": "white", "albedo": 0.6}],
  "media": [{"name": "fire", "sigma_s": 1.0, "sigma_a": 1.0,
             "density": {"procedural": "fire", "radius": 0.3, "flame_height": 0.6, "height": 1.0, "voxel_size": 0.05},
             "emission": {"grid": "temperature", "blackbody": true, "scale": 50}}],
  "global_medium": "fire",
  "shapes": [{"type": "box", "name": "room", "material": "white", "min": [-1.5, 0, -1.5], "max": [1.5, 2, 1.5],
              "inward": true}],
  "cameras": [{"position": [0, 1, 1.4], "target": [0, 0.4, 0], "fov": 80}]
})";
    const std::string out = dir + "/compare.exr";
    test::CliRun r =
        test::runTyndall("compare " + dir + "/fire.json --size 32x24 --passes 2 --photons 400 --gpu off -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Image het = readImage(dir + "/compare-heterogeneous.exr");
    const Image hom = readImage(dir + "/compare-homogeneous.exr");
    for (int c = 0; c < 3; ++c) {
        const double h = imageMean(het, c), t = imageMean(hom, c);
        std::printf("channel %d: image mean, grid %.4g, twin %.4g\n", c, h, t);
        EXPECT_GT(h, 0.0);
        // The same power from a box about the fire's size, seen from the same place: the images'
        // means agree to well within a factor of 2.
        EXPECT_GT(t, 0.5 * h) << "channel " << c;
        EXPECT_LT(t, 2.0 * h) << "channel " << c;
    }
}

TEST(CompareCommand, InterruptKeepsBothHalvesAtTheSamePassCount) {
    // Ctrl-C during the heterogeneous half: that half is written at once and the homogeneous twin
    // still renders as many passes, so the comparison stays fair.
    const std::string out = test::outputDir() + "/compare-interrupt.png";
    const std::string het = test::outputDir() + "/compare-interrupt-heterogeneous.exr";
    const std::string hom = test::outputDir() + "/compare-interrupt-homogeneous.exr";
    std::filesystem::remove(het);
    std::filesystem::remove(hom);
    pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        std::freopen("/dev/null", "w", stdout);
        std::freopen("/dev/null", "w", stderr);
        execl(TYNDALL_BINARY, TYNDALL_BINARY, "compare", "--passes", "100000", "--size", "32x24", "--photons", "100",
              "--gpu", "off", "-o", out.c_str(), (char*)nullptr);
        _exit(127);
    }
    // Interrupt once the command catches SIGINT (its handler is installed just before rendering),
    // and a moment later, so that some passes are in.
    for (int i = 0; i < 600 && !catchesSigint(pid); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(50));
    ASSERT_TRUE(catchesSigint(pid)) << "compare never installed its interrupt handler";
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    ASSERT_TRUE(std::filesystem::exists(het)) << "the heterogeneous half was not written";
    ASSERT_TRUE(std::filesystem::exists(hom)) << "the homogeneous half was not written";
    const std::string hetPasses = readImageAttribute(het, "tyndall:passes");
    ASSERT_FALSE(hetPasses.empty());
    EXPECT_GE(std::stoull(hetPasses), 1u);
    EXPECT_EQ(readImageAttribute(hom, "tyndall:passes"), hetPasses);
    EXPECT_TRUE(std::filesystem::exists(out));
}

TEST(LabelText, DrawsGlyphsInsideItsBox) {
    Image img(80, 20);
    app::drawLabel(img, 3, 2, "Ab 1.5", 1, Rgb(1.0f), Rgb(0.25f));
    const int w = app::labelWidth("Ab 1.5", 1), h = app::labelHeight(1);
    EXPECT_EQ(w, 6 * 6 - 1 + 2);
    EXPECT_EQ(h, 9);
    int on = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 80; ++x) {
            bool inside = x >= 3 && x < 3 + w && y >= 2 && y < 2 + h;
            if (!inside) {
                ASSERT_EQ(img.at(x, y).g, 0.0f) << x << "," << y;
            }
            on += img.at(x, y).g == 1.0f;
        }
    EXPECT_GT(on, 30);
    // 'A' starts with its top row 0x0E: pixels 1..3 of the first glyph row.
    EXPECT_EQ(img.at(3 + 1 + 0, 3).g, 0.25f);
    EXPECT_EQ(img.at(3 + 1 + 1, 3).g, 1.0f);
    // Clipping at the image edge is safe.
    app::drawLabel(img, 70, 15, "CLIPPED", 2, Rgb(1.0f), Rgb(0.0f));
}

}  // namespace
}  // namespace tyndall
