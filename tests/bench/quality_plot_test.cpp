// The quality study's plot: the CSV holds exactly the curves' points (no comma inside a field, so
// gnuplot's plain CSV reading splits it right), and the gnuplot script draws one line per curve
// plus the noise slope through the end of each panel's first curve.
#include "bench/quality_plot.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "tests/test_util.h"

namespace tyndall::bench {
namespace {

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

std::vector<PlotPanel> twoPanels() {
    return {{"fog-box", {{"LEGACY", {{1, 0.5}, {2, 0.25}, {1584, 0.0123456789}}}, {"AUTO, PLANNED", {{1, 0.4}}}}},
            {"lamp,2", {{"LEGACY", {{3.5, 1e-3}}}}}};
}

TEST(QualityPlot, CsvHoldsEveryPointOnce) {
    const std::string prefix = test::outputDir() + "/quality_plot_csv";
    writePlotData(prefix, twoPanels(), 0.5, "passes (equal work)");
    EXPECT_EQ(readText(prefix + ".csv"),
              "scene,row,x,rel_rmse\n"
              "fog-box,legacy,1,0.5\n"
              "fog-box,legacy,2,0.25\n"
              "fog-box,legacy,1584,0.0123456789\n"
              "fog-box,auto-planned,1,0.4\n"
              "lamp;2,legacy,3.5,0.001\n");
}

TEST(QualityPlot, ScriptDrawsEveryCurveAndTheSlope) {
    const std::string prefix = test::outputDir() + "/quality_plot_gp";
    writePlotData(prefix, twoPanels(), 0.5, "passes (equal work)");
    const std::string gp = readText(prefix + ".gp");
    EXPECT_NE(gp.find("set output \"quality_plot_gp.png\""), std::string::npos) << gp;
    EXPECT_NE(gp.find("data = \"quality_plot_gp.csv\""), std::string::npos) << gp;
    EXPECT_NE(gp.find("set multiplot layout 1,2"), std::string::npos) << gp;
    EXPECT_EQ(count(gp, "with linespoints"), 3u) << gp;
    EXPECT_NE(gp.find("strcol(1) eq \"fog-box\" && strcol(2) eq \"auto-planned\" ? $4 : NaN) with linespoints title "
                      "\"AUTO, PLANNED\""),
              std::string::npos)
        << gp;
    EXPECT_NE(gp.find("set title \"lamp,2\"\nplot data using 3:(strcol(1) eq \"lamp;2\""), std::string::npos) << gp;
    // The slope -alpha/2 through the last point of each panel's first curve.
    EXPECT_NE(gp.find("(0.0123456789 * (x / 1584) ** (-0.25))"), std::string::npos) << gp;
    EXPECT_NE(gp.find("(0.001 * (x / 3.5) ** (-0.25))"), std::string::npos) << gp;
}

TEST(QualityPlot, GnuplotDrawsTheScript) {
    if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed (gnuplot-nox)";
    const std::string prefix = test::outputDir() + "/quality_plot_png";
    std::filesystem::remove(prefix + ".png");
    writePlotData(prefix, twoPanels(), 0.5, "passes (equal work)");
    std::string why;
    ASSERT_TRUE(runGnuplot(prefix, &why)) << why;
    ASSERT_TRUE(std::filesystem::exists(prefix + ".png"));
    EXPECT_GT(std::filesystem::file_size(prefix + ".png"), 1000u);
}

TEST(QualityPlot, UnwritablePrefixIsNamed) {
    try {
        writePlotData("/no/such/dir/plot", twoPanels(), 0.5, "passes");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/no/such/dir/plot.csv"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace tyndall::bench
