// `tyndall view` in a real X server (Xvfb) with real GL (llvmpipe), driven by --script. Skips with
// a message when xvfb-run is not installed (scripts/setup.sh installs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace tyndall {
namespace {
namespace fs = std::filesystem;

const char* kSmall = "--gpu off --size 128x128 --photons 500";

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

fs::path outDir(const std::string& name) {
    fs::path d = fs::path(test::outputDir()) / "viewer" / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

/// Runs `tyndall view ARGS --script` with `script` under xvfb-run.
test::CliRun runView(const fs::path& dir, const std::string& args, const std::string& script) {
    fs::path file = dir / "script.txt";
    std::ofstream(file) << script;
    std::string cmd = std::string("-a -s '-screen 0 1280x1024x24' ") + TYNDALL_BINARY + " view " + args +
                      " --script " + file.string();
    std::string full = "xvfb-run " + cmd + " 2>&1";
    test::CliRun r;
    FILE* pipe = popen(full.c_str(), "r");
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
    int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

double meanLuminance(const Image& img, int x0, int y0, int x1, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += (img.at(x, y).r + img.at(x, y).g + img.at(x, y).b) / 3.0;
    return sum / double((x1 - x0) * (y1 - y0));
}

#define SKIP_WITHOUT_XVFB() \
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb): viewer tests skipped"

TEST(ViewerCli, WithoutADisplayItSaysWhatIsMissingAndExits1) {
    test::CliRun r = test::runTyndall("view", "-u DISPLAY");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("tyndall render"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

TEST(ViewerXvfb, OrbitDragThenRefinementEqualsRenderOfTheSavedSceneBitForBit) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("orbit");
    test::CliRun r = runView(d, kSmall,
                             "wait-passes 1\n"
                             "drag left 64 64 94 70 6\n"
                             "wait-passes 3\n"
                             "save " + (d / "view").string() + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string exr = (d / "view.exr").string();
    EXPECT_EQ(readImageAttribute(exr, "tyndall:viewer"), "refined");
    std::string passes = readImageAttribute(exr, "tyndall:passes");
    ASSERT_GE(std::stoi(passes), 3);
    test::CliRun render = test::runTyndall("render " + (d / "view.json").string() + " --gpu off -o " +
                                           (d / "render.exr").string());
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_EQ(readImageAttribute((d / "render.exr").string(), "tyndall:passes"), passes);
    Image viewer = readImage(exr), rendered = readImage((d / "render.exr").string());
    EXPECT_TRUE(test::identicalImages(viewer, rendered)) << "viewer and `tyndall render` of its saved scene differ";
    // And the drag did move the camera: the default view renders differently.
    test::CliRun unmoved = test::runTyndall("render " + std::string(kSmall) + " --passes " + passes + " -o " +
                                            (d / "unmoved.exr").string());
    ASSERT_EQ(unmoved.exitCode, 0) << unmoved.output;
    EXPECT_FALSE(test::identicalImages(viewer, readImage((d / "unmoved.exr").string())));
}

TEST(ViewerXvfb, DraggingTheSpotToTheRightMovesTheLitFloorToTheRight) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("light");
    // Ctrl + left drag re-aims the default scene's spot at the floor under the cursor.
    test::CliRun r = runView(d, kSmall,
                             "wait-passes 4\nsave " + (d / "before").string() + "\n"
                             "drag left 40 108 96 108 8 ctrl\n"
                             "wait-passes 4\nsave " + (d / "after").string() + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image before = readImage((d / "before.exr").string()), after = readImage((d / "after.exr").string());
    // Where the floor got brighter vs darker (the bottom third: the floor), luminance-weighted.
    double brighterX = 0, brighterW = 0, darkerX = 0, darkerW = 0;
    for (int y = 85; y < 128; ++y)
        for (int x = 0; x < 128; ++x) {
            double diff = (after.at(x, y).r + after.at(x, y).g + after.at(x, y).b) -
                          (before.at(x, y).r + before.at(x, y).g + before.at(x, y).b);
            if (diff > 0) brighterX += diff * x, brighterW += diff;
            else darkerX -= diff * x, darkerW -= diff;
        }
    ASSERT_GT(brighterW, 0);
    ASSERT_GT(darkerW, 0);
    EXPECT_GT(brighterX / brighterW, darkerX / darkerW + 10.0)
        << "brighter at x=" << brighterX / brighterW << ", darker at x=" << darkerX / darkerW;
    nlohmann::json b = nlohmann::json::parse(std::ifstream(d / "before.json"));
    nlohmann::json a = nlohmann::json::parse(std::ifstream(d / "after.json"));
    EXPECT_NE(a["edits"]["lights"][0]["direction"], b["edits"]["lights"][0]["direction"]);
    EXPECT_EQ(a["edits"]["camera"], b["edits"]["camera"]);
}

TEST(ViewerXvfb, ExposureChangesTheWindowNotTheExr) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("exposure");
    // Paused, so both saves hold the same passes.
    test::CliRun r = runView(d, kSmall,
                             "wait-passes 2\nkey space\nsleep 1500\n"
                             "screenshot " + (d / "dim.png").string() + "\nsave " + (d / "dim").string() + "\n"
                             "exposure 4\nwait-frames 3\n"
                             "screenshot " + (d / "bright.png").string() + "\nsave " + (d / "bright").string() +
                             "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image dimExr = readImage((d / "dim.exr").string()), brightExr = readImage((d / "bright.exr").string());
    EXPECT_TRUE(test::identicalImages(dimExr, brightExr));
    Image dim = readImage((d / "dim.png").string()), bright = readImage((d / "bright.png").string());
    // The image area is right of the 330-pixel panel, at the window's top.
    double a = meanLuminance(dim, 330, 0, 458, 128), b = meanLuminance(bright, 330, 0, 458, 128);
    EXPECT_GT(b, 1.5 * a) << "window image mean " << a << " at exposure 1, " << b << " at exposure 4";
    EXPECT_GT(a, 0.005) << "the window shows no image";
}

TEST(ViewerXvfb, CompareShowsTwoDifferentHalves) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("compare");
    test::CliRun r = runView(d, "--compare --gpu off --size 96x96 --photons 300",
                             "wait-passes 2\nscreenshot " + (d / "compare.png").string() + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image shot = readImage((d / "compare.png").string());
    ASSERT_EQ(shot.width, 330 + 96 + 4 + 96);
    double diff = 0, level = 0;
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const Rgb& l = shot.at(330 + x, y);
            const Rgb& rr = shot.at(330 + 100 + x, y);
            diff += std::abs(l.r - rr.r) + std::abs(l.g - rr.g) + std::abs(l.b - rr.b);
            level += l.r + l.g + l.b + rr.r + rr.g + rr.b;
        }
    EXPECT_GT(level / (96 * 96 * 6), 0.005) << "the halves are black";
    EXPECT_GT(diff / (96 * 96 * 3), 0.01) << "the grid and its homogeneous twin look the same";
}

}  // namespace
}  // namespace tyndall
