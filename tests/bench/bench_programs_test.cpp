// Each study program once, tiny: it runs, prints every section, and its output holds numbers
// (no NaN or inf from a rate over nothing). The figures themselves are not judged here.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::CliRun;
using tyndall::test::runShell;

bool hasNonFinite(const std::string& text) {
    for (const char* bad : {" nan", " -nan", " inf", " -inf"})
        if (text.find(bad) != std::string::npos) return true;
    return false;
}

TEST(BenchPrograms, StagesRunsEverySection) {
    CliRun r = runShell(std::string(TYNDALL_STAGES_BINARY) +
                        " --size 32x32 --passes 2 --photons 200 --rays 4096 --queries 512 --free-flights 4096 "
                        "--threads 2 --no-hybrid 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* section : {"baseline", "photon tracing", "beam gather", "full passes", "SIMD beam splat",
                                "heterogeneous media", "free flights: majorant grid"})
        EXPECT_NE(r.output.find(section), std::string::npos) << section << " missing from:\n" << r.output;
    EXPECT_FALSE(hasNonFinite(r.output)) << r.output;
}

TEST(BenchPrograms, QualityWritesTableCsvAndScript) {
    const std::string dir = tyndall::test::outputDir() + "/bench_quality";
    std::filesystem::remove_all(dir);
    CliRun r = runShell(std::string(TYNDALL_QUALITY_BINARY) + " --scene " + TYNDALL_SOURCE_DIR +
                        "/bench/scenes/fog-box.json:4 --size 16x16 --photons 200 --threads 2 --reference-spp 4 "
                        "--reference-dir " + dir + "/refs --plot " + dir + "/q 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* row : {"LEGACY", "AUTO, PLANNED", "AUTO, NO CONE", "AUTO, OPEN-ENDED"})
        EXPECT_NE(r.output.find(row), std::string::npos) << row << " missing from:\n" << r.output;
    EXPECT_FALSE(hasNonFinite(r.output)) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir + "/refs/fog-box-16x16-4spp.exr"));
    ASSERT_TRUE(std::filesystem::exists(dir + "/q.csv"));
    ASSERT_TRUE(std::filesystem::exists(dir + "/q.gp"));
    std::ifstream csv(dir + "/q.csv");
    int lines = 0;
    for (std::string line; std::getline(csv, line);) {
        ++lines;
        EXPECT_EQ(std::count(line.begin(), line.end(), ','), 3) << "four fields: " << line;
    }
    EXPECT_EQ(lines, 1 + 4 * 3) << "a header and, per row, passes 1, 2 and 4";
}

// bench/baseline_compare.sh with one build as both: a missing reference rendered once, by NEW, before
// anything is timed (BASE then finds it cached); each round's seeds its own; NEW's options reach NEW
// alone; the summary has both builds' defaults and their ratio.
TEST(BenchPrograms, BaselineCompareRunsBothBuildsAgainstOneCache) {
    const std::string dir = tyndall::test::outputDir() + "/bench_baseline_compare";
    std::filesystem::remove_all(dir);
    const std::string quality = TYNDALL_QUALITY_BINARY;
    CliRun r = runShell(std::string("sh ") + TYNDALL_SOURCE_DIR + "/bench/baseline_compare.sh --rounds 2 --seeds 1 " +
                        "--cpu-seconds 0.02 --size 16x16 --reference-spp 256 --scene " + TYNDALL_SOURCE_DIR +
                        "/bench/scenes/fog-box.json --log " + dir + "/log " + quality + " " + quality + " " + dir +
                        "/refs -- --no-switch-rows 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(dir + "/refs/fog-box-16x16-256spp.exr"));
    size_t rendered = 0;
    for (size_t at = r.output.find("rendered"); at != std::string::npos; at = r.output.find("rendered", at + 1))
        ++rendered;
    EXPECT_EQ(rendered, 1u) << r.output;
    for (const char* run : {"base-round0-fog-box.txt", "new-round0-fog-box.txt", "base-round1-fog-box.txt",
                            "new-round1-fog-box.txt"})
        EXPECT_TRUE(std::filesystem::exists(dir + "/log/" + run)) << run;
    // --no-switch-rows reached NEW (its rows: the defaults alone) and not BASE.
    std::ifstream base1(dir + "/log/base-round1-fog-box.txt"), new1(dir + "/log/new-round1-fog-box.txt");
    const std::string baseText((std::istreambuf_iterator<char>(base1)), {}), newText((std::istreambuf_iterator<char>(new1)), {});
    EXPECT_NE(baseText.find("EQUIANGULAR OFF"), std::string::npos) << baseText;
    EXPECT_EQ(newText.find("EQUIANGULAR OFF"), std::string::npos) << newText;
    const size_t base = r.output.find("base: DEFAULTS (--TIME)"), ours = r.output.find("new: DEFAULTS (--TIME)");
    ASSERT_NE(base, std::string::npos) << r.output;
    ASSERT_NE(ours, std::string::npos) << r.output;
    // The summary's NEW line ends with the ratio of the two RMSEs: the same build, so of order 1.
    const std::string line = r.output.substr(ours, r.output.find('\n', ours) - ours);
    const double ratio = std::stod(line.substr(line.find_last_of(' ') + 1));
    EXPECT_GT(ratio, 0.2) << line;
    EXPECT_LT(ratio, 5.0) << line;
    EXPECT_FALSE(hasNonFinite(r.output)) << r.output;
}

TEST(BenchPrograms, QualityRejectsASceneWithoutPasses) {
    CliRun r = runShell(std::string(TYNDALL_QUALITY_BINARY) + " --scene " + TYNDALL_SOURCE_DIR +
                        "/bench/scenes/fog-box.json 2>&1");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.output.find("--scene"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("FILE:PASSES"), std::string::npos) << r.output;
}

}  // namespace
