// The command line with scene files: a bad file prints exactly one "tyndall: ..." line naming the
// file and place and exits non-zero; --camera and the file's render block reach the renderer.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>

#include "app/cli_common.h"
#include "tests/scene/scene_test_util.h"
#include "tests/tyndall_cli.h"

namespace tyndall {
namespace {

using test::CliRun;
using test::runTyndall;

const char* kSmallScene = R"({
  "render": {"width": 8, "height": 6, "passes": 1, "photons": 200},
  "materials": [{"name": "white"}],
  "shapes": [{"type": "quad", "name": "floor", "material": "white", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
  "lights": [{"type": "point", "position": [0, 1, 0], "intensity": 1}],
  "cameras": [{"name": "top", "position": [0, 2, 0.01], "target": [0, 0, 0]},
              {"name": "side", "position": [0, 0.5, 3], "target": [0, 0, 0]}]
})";

TEST(SceneCli, BadSceneFilePrintsOneLineAndFails) {
    std::string path = test::writeTestFile("cli-bad.json", R"({"materials": [{"name": "m", "albedo": "grey"}]})");
    CliRun r = runTyndall("render " + path + " -o " + test::outputDir() + "/cli-bad.png");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.output,
              "tyndall: " + path +
                  ": /materials/0/albedo: expected a finite number >= 0 or [r, g, b], got the string \"grey\"\n");
}

TEST(SceneCli, BadGltfPrintsOneLineAndFails) {
    std::string path = test::writeTestFile("cli-bad.gltf",
                                           "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [{\"mesh\": 3}], "
                                           "\"scenes\": [{\"nodes\": [0]}]}");
    CliRun r = runTyndall("render " + path + " -o " + test::outputDir() + "/cli-bad.png");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.output, "tyndall: " + path + ": node (index 0): mesh index 3 out of range (the file has 0 meshes)\n");
}

TEST(SceneCli, UnknownCameraIsAnError) {
    std::string path = test::writeTestFile("cli-small.json", kSmallScene);
    CliRun r = runTyndall("render " + path + " --camera front -o " + test::outputDir() + "/cli.png");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.output, "tyndall: " + path + ": --camera front: no such camera (this scene has: 0 'top', 1 'side')\n");
}

TEST(SceneCli, RenderBlockAppliesAndExplicitOptionsWin) {
    std::string path = test::writeTestFile("cli-small.json", kSmallScene);
    auto settingsFor = [&](std::vector<std::string> args) {
        CLI::App app;
        app::CommonOptions o;
        CLI::App* cmd = app.add_subcommand("render");
        app::addSceneAndOutputOptions(cmd, o, "x.png");
        app::addPpbOptions(cmd, o);
        args.insert(args.begin(), {"tyndall", "render", path});
        std::vector<const char*> argv;
        for (const std::string& a : args) argv.push_back(a.c_str());
        app.parse(int(argv.size()), argv.data());
        app::finishOptions(o);
        Scene s = app::loadScene(o);
        return std::make_pair(o.settings, s.camera);
    };
    auto [fromFile, top] = settingsFor({});
    EXPECT_EQ(fromFile.width, 8);
    EXPECT_EQ(fromFile.height, 6);
    EXPECT_EQ(fromFile.passes, 1u);
    EXPECT_EQ(fromFile.photonsPerPass, 200u);
    EXPECT_NEAR(top.position.y, 2.0f, 1e-6f);
    auto [overridden, side] = settingsFor({"--passes", "3", "--size", "16x16", "--camera", "1"});
    EXPECT_EQ(overridden.width, 16);
    EXPECT_EQ(overridden.passes, 3u);
    EXPECT_EQ(overridden.photonsPerPass, 200u);  // not given: the file's
    EXPECT_NEAR(side.position.z, 3.0f, 1e-6f);
}

TEST(SceneCli, RendersAJsonScene) {
    std::string path = test::writeTestFile("cli-small.json", kSmallScene);
    std::string out = test::outputDir() + "/cli-small.png";
    std::filesystem::remove(out);
    CliRun r = runTyndall("render " + path + " --camera side -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("1 passes, 200 photon paths"), std::string::npos) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace tyndall
