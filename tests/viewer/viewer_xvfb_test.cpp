// `tyndall view` in a real X server (Xvfb) with real GL (llvmpipe), driven by --script. Skips with
// a message when xvfb-run is not installed (scripts/setup.sh installs it).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
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

/// Runs the shell script `body` (DIR/run.sh) under xvfb-run, the X server given `serverArgs` too:
/// its output and exit status.
test::CliRun runUnderXvfb(const fs::path& dir, const std::string& body, const std::string& serverArgs = "") {
    fs::path file = dir / "run.sh";
    std::ofstream(file) << "#!/bin/sh\n" << body;
    fs::permissions(file, fs::perms::owner_all);
    return test::runShell("xvfb-run -a -s '-screen 0 1280x1024x24 " + serverArgs + "' " + file.string() + " 2>&1");
}

/// The command line of `tyndall view ARGS --script DIR/script.txt`, `script` written there.
std::string viewCommand(const fs::path& dir, const std::string& args, const std::string& script) {
    fs::path file = dir / "script.txt";
    std::ofstream(file) << script;
    return std::string(TYNDALL_BINARY) + " view " + args + " --script " + file.string();
}

/// Runs `tyndall view ARGS` with `script` under xvfb-run.
test::CliRun runView(const fs::path& dir, const std::string& args, const std::string& script) {
    return runUnderXvfb(dir, viewCommand(dir, args, script) + "\n");
}

/// Runs `tyndall view ARGS` with `script` in the background under xvfb-run and, beside it, the
/// shell lines `input`, which find the window in $win (xdotool) and send it real input; waits for
/// the viewer and returns its exit status. `input` usually waits for a file the script saves first.
test::CliRun runViewWithInput(const fs::path& dir, const std::string& args, const std::string& script,
                              const std::string& input) {
    return runUnderXvfb(dir, viewCommand(dir, args, script) + " &\npid=$!\n" +
                                 "win=$(xdotool search --sync --name 'tyndall view')\n" + input + "wait $pid\n");
}

/// A shell line that waits until `path` exists.
std::string waitForFile(const fs::path& path) {
    return "while [ ! -f " + path.string() + " ]; do sleep 0.2; done\n";
}

bool haveXdotool() { return std::system("command -v xdotool >/dev/null 2>&1") == 0; }

double meanLuminance(const Image& img, int x0, int y0, int x1, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += (img.at(x, y).r + img.at(x, y).g + img.at(x, y).b) / 3.0;
    return sum / double((x1 - x0) * (y1 - y0));
}

#define SKIP_WITHOUT_XVFB() \
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb): viewer tests skipped"
#define SKIP_WITHOUT_XDOTOOL() \
    if (!haveXdotool()) GTEST_SKIP() << "xdotool is not installed (scripts/setup.sh installs it): real-input test skipped"

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

TEST(ViewerXvfb, TheTransparentFilmTogglesAtRunTime) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("film");
    // A card on the left half of the image, a constant environment behind it.
    std::ofstream(d / "card.json") << R"({"name": "card", "materials": [{"name": "card", "albedo": 0.5}],
  "shapes": [{"type": "quad", "name": "card", "material": "card", "corner": [-2, -2, -3], "edge1": [2, 0, 0],
              "edge2": [0, 4, 0]}],
  "environment": {"radiance": [1.5, 1.5, 1.5]},
  "cameras": [{"position": [0, 0, 0], "target": [0, 0, -3], "fov": 40}]})";
    auto stem = [&](const char* name) { return (d / name).string(); };
    test::CliRun r = runView(d, (d / "card.json").string() + " " + kSmall,
                             "wait-passes 1\nwait-frames 2\nscreenshot " + stem("opaque-window.png") + "\nsave " +
                                 stem("opaque") + "\ntransparent on\nwait-passes 1\nwait-frames 2\nscreenshot " +
                                 stem("film-window.png") + "\nsave " + stem("film") +
                                 "\ntransparent off\nwait-passes 1\nsave " + stem("back") + "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::vector<std::string> rgb = {"R", "G", "B"}, rgba = {"R", "G", "B", "A"};
    EXPECT_EQ(readImageChannels(stem("opaque") + ".exr"), rgb);
    EXPECT_EQ(readImageChannels(stem("film") + ".exr"), rgba);
    EXPECT_EQ(readImageChannels(stem("back") + ".exr"), rgb);
    auto film = [&](const char* name) {
        return nlohmann::json::parse(std::ifstream(d / (std::string(name) + ".json")))["render"]["transparent"];
    };
    EXPECT_EQ(film("opaque"), "off");
    EXPECT_EQ(film("film"), "on");
    EXPECT_EQ(film("back"), "off");
    // The background (the image's right half, right of the 330-pixel panel): one shade opaque,
    // the checkerboard's 16-pixel squares (linear grey 0.18 and 0.36) with the film transparent.
    auto squares = [&](const std::string& png) {
        const Image shot = readImage(png);
        return meanLuminance(shot, 330 + 82, 2, 330 + 94, 14) - meanLuminance(shot, 330 + 66, 2, 330 + 78, 14);
    };
    EXPECT_NEAR(squares(stem("opaque-window.png")), 0.0, 0.01) << "the opaque background is not uniform";
    EXPECT_GT(squares(stem("film-window.png")), 0.1) << "no checkerboard behind the transparent film";
}

TEST(ViewerXvfb, AtRestItDrawsOnlyWhatIsNew) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("rest");
    // Paused for 3 s: no pass is published and no input arrives, so next to no frame is drawn
    // (a window redrawing at 60 Hz draws ~180).
    test::CliRun r = runView(d, std::string(kSmall) + " --stats " + (d / "stats.json").string(),
                             "wait-passes 1\nkey space\nsleep 3000\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(d / "stats.json"));
    uint64_t frames = j["frames"], images = j["images_shown"];
    ASSERT_GE(images, 1u);
    // One frame per image shown, plus a few to settle the panel at the start and after the key.
    EXPECT_LE(frames, images + 10) << frames << " frames for " << images << " images";
}

/// `tyndall render VIEW.json --gpu off` reproduces the viewer's VIEW.exr bit for bit.
void expectRenderReproduces(const fs::path& d, const std::string& stem) {
    const std::string exr = (d / (stem + ".exr")).string();
    test::CliRun render = test::runTyndall("render " + (d / (stem + ".json")).string() + " --gpu off -o " +
                                           (d / (stem + "-render.exr")).string());
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(test::identicalImages(readImage(exr), readImage((d / (stem + "-render.exr")).string())))
        << stem << ": the viewer and `tyndall render` of its saved view differ";
}

TEST(ViewerXvfb, EveryBindingRunsAndTheSavedViewStillReproduces) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("bindings");
    test::CliRun r = runView(d, std::string(kSmall) + " --save-stem " + (d / "key").string(),
                             "wait-passes 1\nkey H\nkey plus\nkey minus\nkey F\nscroll 64 64 3\nscroll 64 64 -1\n"
                             "double-click 64 100\ndrag right 64 64 50 70 4\ndrag middle 50 70 60 60 2\n"
                             "drag left 64 64 70 40 3\nkey 1\nkey 9\nkey R\nkey space\nkey space\n"
                             "wait-passes 2\nkey S\nsave " + (d / "view").string() + "\nkey escape\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(d / "key-1.exr") && fs::exists(d / "key-1.png") && fs::exists(d / "key-1.json"))
        << r.output;
    expectRenderReproduces(d, "view");
}

TEST(ViewerXvfb, RealMouseDragThroughTheXServerOrbits) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
    fs::path d = outDir("xdotool");
    // The viewer waits for one real button release; xdotool drags in the image area (right of the
    // 330-pixel panel) once the first view is saved.
    test::CliRun r = runViewWithInput(
        d, kSmall,
        "wait-passes 1\nsave " + (d / "before").string() + "\nwait-input 1 300\nwait-passes 2\nsave " +
            (d / "after").string() + "\nquit\n",
        waitForFile(d / "before.json") +
            "xdotool mousemove --window $win 394 64 mousedown 1 mousemove --window $win 404 66 "
            "mousemove --window $win 414 68 mousemove --window $win 424 70 mouseup 1\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    nlohmann::json b = nlohmann::json::parse(std::ifstream(d / "before.json"));
    nlohmann::json a = nlohmann::json::parse(std::ifstream(d / "after.json"));
    // The real drag moved the camera (an orbit: the eye moved, the pivot distance kept).
    EXPECT_NE(a["edits"]["camera"]["position"], b["edits"]["camera"]["position"]);
    expectRenderReproduces(d, "after");
}

TEST(ViewerXvfb, AnAltDragDrawsARenderRegionThatGoesIntoTheViewFileAndIsReadBack) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
    fs::path d = outDir("region");
    auto stem = [&](const char* name) { return (d / name).string(); };
    // Alt + left drag from window (350, 30) to (410, 70): image pixels (20, 30) to (80, 70), the
    // image area being right of the 330-pixel panel.
    test::CliRun r = runViewWithInput(
        d, kSmall,
        "wait-passes 1\nsave " + stem("before") + "\nwait-input 1 300\nwait-passes 2\nsave " + stem("region") +
            "\nscreenshot " + stem("window.png") + "\nquit\n",
        waitForFile(stem("before") + ".json") +
            // A person's pace: the X server may deliver a burst's button press after its warps.
            "xdotool mousemove --window $win 350 30; sleep 0.3; xdotool keydown alt mousedown 1; sleep 0.3\n"
            "xdotool mousemove --window $win 380 50; sleep 0.3; xdotool mousemove --window $win 410 70; sleep 0.3\n"
            "xdotool mouseup 1 keyup alt\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto view = [&](const char* name) { return nlohmann::json::parse(std::ifstream(d / (std::string(name) + ".json"))); };
    EXPECT_EQ(view("before")["render"].count("region"), 0u);
    ASSERT_EQ(view("region")["render"]["region"], nlohmann::json({20, 30, 61, 41})) << r.output;
    EXPECT_EQ(view("region")["edits"], view("before")["edits"]) << "a region drag moved the camera";
    // The saved image refined the region alone; `tyndall render` of the view file does the same.
    Image saved = readImage(stem("region") + ".exr");
    EXPECT_EQ(meanLuminance(saved, 0, 0, 128, 30), 0.0);
    EXPECT_GT(meanLuminance(saved, 20, 30, 81, 71), 0.005);
    expectRenderReproduces(d, "region");
    // The window keeps the last whole image around the region.
    Image window = readImage(stem("window.png"));
    EXPECT_GT(meanLuminance(window, 330, 0, 458, 25), 0.005) << "outside the region (and its outline) the window went black";

    // Opened again, the view file's region refines; B clears it; B and a drag draw a new one.
    test::CliRun again = runView(d, stem("region") + ".json --gpu off",
                                 "wait-passes 1\nsave " + stem("reread") + "\nkey B\nwait-passes 1\nsave " +
                                     stem("cleared") + "\nkey B\ndrag left 10 10 30 20 3\nwait-passes 1\nsave " +
                                     stem("keyed") + "\nquit\n");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_EQ(view("reread")["render"]["region"], nlohmann::json({20, 30, 61, 41}));
    EXPECT_EQ(view("cleared")["render"].count("region"), 0u);
    EXPECT_EQ(view("keyed")["render"]["region"], nlohmann::json({10, 10, 21, 11}));
    EXPECT_GT(meanLuminance(readImage(stem("cleared") + ".exr"), 0, 0, 128, 30), 0.005);
}

TEST(ViewerXvfb, F12SavesTheViewAndRendersItInTheBackgroundWhileTheWindowStaysUsable) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
    fs::path d = outDir("final");
    auto stem = [&](const char* name) { return (d / name).string(); };
    // F12 from the X server, then at once a real orbit drag while the final render runs.
    test::CliRun r = runViewWithInput(
        d, std::string(kSmall) + " --final-passes 3 --save-stem " + stem("key"),
        "wait-passes 1\nsave " + stem("before") + "\nwait-final 1 300\nwait-input 1 300\nwait-passes 1\nsave " +
            stem("after") + "\nscreenshot " + stem("window.png") + "\nquit\n",
        waitForFile(stem("before") + ".json") + "sleep 0.3; xdotool key --window $win F12; sleep 0.3\n" +
            "xdotool mousemove --window $win 394 64; sleep 0.2; xdotool mousedown 1; sleep 0.2\n"
            "xdotool mousemove --window $win 424 70; sleep 0.2; xdotool mouseup 1\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("final render of " + stem("key-1") + ".json"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("nice +10"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("final render done: " + stem("key-1") + "-final.exr"), std::string::npos) << r.output;
    // The final image is `tyndall render` of the saved view at the panel's pass count.
    const std::string final = stem("key-1") + "-final.exr";
    const std::string passes = readImageAttribute(final, "tyndall:passes");
    EXPECT_EQ(passes, "3") << r.output;
    test::CliRun again = test::runTyndall("render " + stem("key-1") + ".json --passes " + passes + " -o " +
                                          stem("again") + ".exr");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    EXPECT_TRUE(test::identicalImages(readImage(final), readImage(stem("again") + ".exr")));
    // The window went on: the drag moved the camera.
    nlohmann::json b = nlohmann::json::parse(std::ifstream(stem("before") + ".json"));
    nlohmann::json a = nlohmann::json::parse(std::ifstream(stem("after") + ".json"));
    EXPECT_NE(a["edits"]["camera"]["position"], b["edits"]["camera"]["position"]);
}

/// A one-room scene whose lamp has `intensity`.
std::string roomScene(const std::string& intensity) {
    return R"({"name": "room", "materials": [{"name": "wall", "albedo": 0.5}],
  "shapes": [{"type": "box", "name": "room", "material": "wall", "min": [-1, 0, -1], "max": [1, 2, 1], "inward": true}],
  "lights": [{"type": "point", "name": "lamp", "position": [0, 1.5, 0], "intensity": )" +
           intensity + R"(}],
  "cameras": [{"name": "front", "position": [0, 1, 0.9], "target": [0, 1, 0], "fov": 60}]})";
}

TEST(ViewerXvfb, TheSceneFileReloadsOnChangeAndOnF5KeepingTheCameraAndABadFileKeepsTheLastGoodScene) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
    fs::path d = outDir("reload");
    const fs::path scene = d / "room.json";
    std::ofstream(scene) << roomScene("1");
    std::ofstream(d / "brighter.json") << roomScene("4");
    std::ofstream(d / "bad.json") << roomScene("[4, 4]");  // not an RGB triple
    auto stem = [&](const char* name) { return (d / name).string(); };
    // Orbit, then: the file is replaced (a brighter lamp), F5 from the X server, a bad file.
    std::ostringstream script;
    script << "wait-passes 1\ndrag left 64 64 84 60 4\nwait-passes 1\nsave " << stem("before")
           << "\nwait-reload 1 120\nwait-passes 1\nsave " << stem("changed")
           << "\nwait-reload 2 120\nwait-passes 1\nsave " << stem("keyed")
           << "\nwait-reload 3 120\nwait-passes 1\nsave " << stem("bad") << "\nquit\n";
    auto replaceScene = [&](const char* with) {
        return "sleep 1.1; cp " + (d / with).string() + " " + scene.string() + ".new; mv " + scene.string() +
               ".new " + scene.string() + "\n";
    };
    test::CliRun r = runViewWithInput(d, scene.string() + " " + kSmall, script.str(),
                                      waitForFile(stem("before") + ".json") + replaceScene("brighter.json") +
                                          waitForFile(stem("changed") + ".json") + "xdotool key --window $win F5\n" +
                                          waitForFile(stem("keyed") + ".json") + replaceScene("bad.json"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto view = [&](const char* name) { return nlohmann::json::parse(std::ifstream(d / (std::string(name) + ".json"))); };
    nlohmann::json before = view("before"), changed = view("changed"), keyed = view("keyed"), bad = view("bad");
    // The file's change shows (4x the lamp), the orbited camera stays.
    EXPECT_EQ(changed["edits"]["lights"][0]["intensity"], nlohmann::json({4, 4, 4}));
    EXPECT_EQ(before["edits"]["lights"][0]["intensity"], nlohmann::json({1, 1, 1}));
    EXPECT_EQ(changed["edits"]["camera"], before["edits"]["camera"]);
    double lumBefore = meanLuminance(readImage(stem("before") + ".exr"), 0, 0, 128, 128);
    double lumChanged = meanLuminance(readImage(stem("changed") + ".exr"), 0, 0, 128, 128);
    EXPECT_NEAR(lumChanged / lumBefore, 4.0, 0.4) << "a lamp 4x brighter, same view and seed";
    // F5 reloads (the same file: the same view and lamp); the bad file keeps the last good scene
    // and says why, naming the file.
    EXPECT_EQ(keyed["edits"], changed["edits"]);
    EXPECT_EQ(bad["edits"], changed["edits"]);
    EXPECT_NE(r.output.find("reload failed, the last good scene stays"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(scene.string() + ": "), std::string::npos) << r.output;
}

TEST(ViewerXvfb, TheImageFollowsTheWindowSizeXdotoolSets) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
    fs::path d = outDir("resize");
    auto stem = [&](const char* name) { return (d / name).string(); };
    test::CliRun r = runViewWithInput(
        d, kSmall,
        "wait-passes 1\nsave " + stem("before") + "\nwait-resize 1 60\nwait-passes 2\nsave " + stem("after") +
            "\nscreenshot " + stem("window.png") + "\nquit\n",
        waitForFile(stem("before") + ".json") + "xdotool windowsize $win 700 300\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("image 370x300"), std::string::npos) << r.output;
    nlohmann::json after = nlohmann::json::parse(std::ifstream(stem("after") + ".json"));
    nlohmann::json before = nlohmann::json::parse(std::ifstream(stem("before") + ".json"));
    // The window less the 330-pixel panel; the camera stays where it was.
    EXPECT_EQ(after["render"]["width"], 370);
    EXPECT_EQ(after["render"]["height"], 300);
    EXPECT_EQ(after["edits"]["camera"], before["edits"]["camera"]);
    Image saved = readImage(stem("after") + ".exr");
    EXPECT_EQ(saved.width, 370);
    EXPECT_EQ(saved.height, 300);
    expectRenderReproduces(d, "after");
    Image window = readImage(stem("window.png"));
    ASSERT_EQ(window.width, 700);
    ASSERT_EQ(window.height, 300);
    EXPECT_GT(meanLuminance(window, 600, 200, 700, 300), 0.005) << "the window's new corner shows no image";
}

TEST(ViewerXvfb, ThePanelScalesWithTheContentScale) {
    SKIP_WITHOUT_XVFB();
    if (std::system("command -v xprop >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "xprop is not installed (x11-utils): content-scale test skipped";
    fs::path d = outDir("content-scale");
    // Xft.dpi 192 is a content scale of 2 (GLFW on X11 reads it at start): the panel is 660 wide.
    // -noreset: the property outlives xprop's connection.
    test::CliRun r = runUnderXvfb(
        d, "xprop -root -f RESOURCE_MANAGER 8s -set RESOURCE_MANAGER 'Xft.dpi: 192'\n" +
               viewCommand(d, kSmall, "wait-passes 1\nscreenshot " + (d / "window.png").string() + "\nquit\n") +
               "\n",
        "-noreset");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image window = readImage((d / "window.png").string());
    EXPECT_EQ(window.width, 660 + 128);
    EXPECT_GT(meanLuminance(window, 660, 0, 788, 128), 0.005) << "no image right of the scaled panel";
    // Where a 1x panel would end, the 2x panel still is: its background, not the image's light.
    EXPECT_LT(meanLuminance(window, 400, 150, 460, 200), meanLuminance(window, 660, 64, 788, 128));
}

TEST(ViewerXvfb, ASceneFileDroppedThroughXdndOpensAndABadOneLeavesTheSceneShown) {
    SKIP_WITHOUT_XVFB();
    SKIP_WITHOUT_XDOTOOL();
#ifndef XDND_DROP_BINARY
    GTEST_SKIP() << "built without libX11: no drag-and-drop source for the drop test";
#else
    fs::path d = outDir("drop");
    std::ofstream(d / "room.json") << roomScene("2");
    std::ofstream(d / "bad.json") << roomScene("[4, 4]");
    auto stem = [&](const char* name) { return (d / name).string(); };
    // The room is dropped on the image area through XDND, as a file manager drops it; then the
    // script drops the bad file.
    test::CliRun r = runViewWithInput(
        d, kSmall,
        "wait-passes 1\nsave " + stem("before") + "\nwait-reload 1 30\nwait-passes 1\nsave " + stem("dropped") +
            "\ndrop " + stem("bad.json") + "\nwait-passes 1\nsave " + stem("after-bad") + "\nquit\n",
        waitForFile(stem("before") + ".json") + XDND_DROP_BINARY + " $win 400 60 " + stem("room.json") + "\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("opened " + stem("room.json")), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("drop: not opened, the scene stays: " + stem("bad.json")), std::string::npos)
        << r.output;
    auto view = [&](const char* name) { return nlohmann::json::parse(std::ifstream(stem(name) + ".json")); };
    const std::string room = fs::absolute(d / "room.json").lexically_normal().string();
    EXPECT_EQ(view("before")["base"], "builtin:default");
    EXPECT_EQ(view("dropped")["base"], room);
    EXPECT_EQ(view("dropped")["edits"]["lights"][0]["intensity"], nlohmann::json({2, 2, 2}));
    EXPECT_EQ(view("after-bad")["base"], room);
    expectRenderReproduces(d, "dropped");
#endif
}

TEST(ViewerXvfb, WithGlSplattingTheSavedViewReproducesUnderGpuOn) {
    SKIP_WITHOUT_XVFB();
    fs::path d = outDir("gl");
    test::CliRun r = runView(d, "--gpu on --size 128x128 --photons 500",
                             "wait-passes 1\ndrag left 64 64 80 64 4\nwait-passes 2\nsave " + (d / "view").string() +
                                 "\nscreenshot " + (d / "window.png").string() + "\nquit\n");
    if (r.exitCode != 0 && r.output.find("--gpu on") != std::string::npos)
        GTEST_SKIP() << "no headless OpenGL for the splatter here: " << r.output;
    ASSERT_EQ(r.exitCode, 0) << r.output;
    test::CliRun render = test::runTyndall("render " + (d / "view.json").string() + " --gpu on -o " +
                                           (d / "render.exr").string());
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_NE(render.output.find("hybrid"), std::string::npos) << render.output;
    // The same GL splatter in the same primitive order: llvmpipe's float blending is exact.
    EXPECT_TRUE(test::identicalImages(readImage((d / "view.exr").string()), readImage((d / "render.exr").string())));
}

TEST(ViewerXvfb, CompareShowsTwoDifferentHalvesAndTheEmissionSliderDrivesBoth) {
    SKIP_WITHOUT_XVFB();
    // A procedural fire in a dark room, its only light: the grid left, its glowing twin right.
    fs::path d = outDir("compare");
    std::ofstream(d / "fire.json") << R"({
  "materials": [{"name": "white", "albedo": 0.6}],
  "media": [{"name": "fire", "sigma_s": 1.0, "sigma_a": 1.0,
             "density": {"procedural": "fire", "radius": 0.3, "flame_height": 0.6, "height": 1.0, "voxel_size": 0.05},
             "emission": {"grid": "temperature", "blackbody": true, "scale": 2000}}],
  "global_medium": "fire",
  "shapes": [{"type": "box", "name": "room", "material": "white", "min": [-1.5, 0, -1.5], "max": [1.5, 2, 1.5],
              "inward": true}],
  "cameras": [{"position": [0, 1, 1.4], "target": [0, 0.4, 0], "fov": 80}]
})";
    test::CliRun r = runView(d, "--compare " + (d / "fire.json").string() + " --gpu off --size 96x96 --photons 300",
                             "wait-passes 2\nscreenshot " + (d / "compare.png").string() +
                                 "\nemission 0 0.02\nwait-passes 2\nscreenshot " + (d / "dim.png").string() +
                                 "\nquit\n");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Image shot = readImage((d / "compare.png").string()), dim = readImage((d / "dim.png").string());
    ASSERT_EQ(shot.width, 330 + 96 + 4 + 96);
    double diff = 0, level = 0, half[2] = {0, 0}, dimHalf[2] = {0, 0};
    for (int y = 0; y < 96; ++y)
        for (int x = 0; x < 96; ++x) {
            const Rgb& l = shot.at(330 + x, y);
            const Rgb& rr = shot.at(330 + 100 + x, y);
            diff += std::abs(l.r - rr.r) + std::abs(l.g - rr.g) + std::abs(l.b - rr.b);
            level += l.r + l.g + l.b + rr.r + rr.g + rr.b;
            for (int h = 0; h < 2; ++h) {
                const Rgb& a = shot.at(330 + 100 * h + x, y);
                const Rgb& b = dim.at(330 + 100 * h + x, y);
                half[h] += a.r + a.g + a.b;
                dimHalf[h] += b.r + b.g + b.b;
            }
        }
    EXPECT_GT(level / (96 * 96 * 6), 0.005) << "the halves are black";
    EXPECT_GT(diff / (96 * 96 * 3), 0.01) << "the grid and its homogeneous twin look the same";
    // The emission slider at 0.02 dims both halves (the fire is the only light; display values).
    for (int h = 0; h < 2; ++h) {
        std::printf("%s half: mean display value %.4f, with the emission at 0.02 %.4f\n", h ? "twin" : "grid",
                    half[h] / (96 * 96 * 3), dimHalf[h] / (96 * 96 * 3));
        EXPECT_LT(dimHalf[h], 0.5 * half[h]) << (h ? "the twin" : "the grid") << " did not follow the emission slider";
    }
}

}  // namespace
}  // namespace tyndall
