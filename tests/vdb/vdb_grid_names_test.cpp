// Files with several grids of one name (OpenVDB allows it; simulation caches do it): the loader
// takes the first and says so in one Tyndall line naming how to pick another ("density[1]"),
// "name[k]" picks the k-th, an index past the end is an error listing the grids, and OpenVDB's
// own console warning ("more than one grid named ...", on stdout) never appears.
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "loading/vdb_grid.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

openvdb::FloatGrid::Ptr constantBlock(const std::string& name, float value) {
    auto g = openvdb::FloatGrid::create(0.0f);
    g->setName(name);
    g->setGridClass(openvdb::GRID_FOG_VOLUME);
    g->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(7)), value, true);
    return g;
}

/// Two grids named "density" (values 1 and 3) and one "temperature".
std::string writeDuplicateFile() {
    openvdb::initialize();
    std::string path = test::outputDir() + "/duplicate_density.vdb";
    openvdb::GridPtrVec grids{constantBlock("density", 1.0f), constantBlock("temperature", 5.0f),
                              constantBlock("density", 3.0f)};
    openvdb::io::File(path).write(grids);
    return path;
}

/// Runs `f` with stdout and stderr captured into the returned string (OpenVDB's log4cplus
/// console appender writes to stdout).
template <class F>
std::string captureConsole(F f) {
    std::string path = test::outputDir() + "/console_capture.txt";
    std::fflush(stdout);
    std::fflush(stderr);
    std::cout.flush();
    int saved1 = dup(1), saved2 = dup(2);
    FILE* file = std::fopen(path.c_str(), "w");
    dup2(fileno(file), 1);
    dup2(fileno(file), 2);
    f();
    std::cout.flush();
    std::fflush(stdout);
    std::fflush(stderr);
    dup2(saved1, 1);
    dup2(saved2, 2);
    close(saved1);
    close(saved2);
    std::fclose(file);
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(VdbGridNames, DuplicateNamesTakeTheFirstAndSaySoInOneTyndallLine) {
    const std::string path = writeDuplicateFile();
    const Vec3 inside(4.0f, 4.0f, 4.0f);
    for (std::string grid : {"", "density"}) {
        std::vector<std::string> notices;
        std::shared_ptr<const VdbDensityGrid> g;
        std::string err = captureConsole([&] {
            g = VdbDensityGrid::load({path, grid, 1.0f, Affine3()}, [&](const std::string& l) { notices.push_back(l); });
        });
        EXPECT_FLOAT_EQ(g->density(inside), 1.0f) << "the first grid named density, in file order";
        ASSERT_EQ(notices.size(), 1u);
        EXPECT_NE(notices[0].find("2 grids are named 'density'"), std::string::npos) << notices[0];
        EXPECT_NE(notices[0].find("\"grid\": \"density[1]\""), std::string::npos) << notices[0];
        EXPECT_EQ(err.find("more than one grid"), std::string::npos) << "OpenVDB's own warning leaked: " << err;
        EXPECT_EQ(err.find("WARN"), std::string::npos) << err;
    }
    // Without a sink the one line goes to stderr as Tyndall's, still without OpenVDB's.
    std::string err = captureConsole([&] { VdbDensityGrid::load({path, "", 1.0f, Affine3()}); });
    EXPECT_EQ(err.rfind("tyndall: ", 0), 0u) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

TEST(VdbGridNames, IndexPicksOneOfTheSameNameAndPastTheEndIsAnError) {
    const std::string path = writeDuplicateFile();
    const Vec3 inside(4.0f, 4.0f, 4.0f);
    int notices = 0;
    auto count = [&](const std::string&) { ++notices; };
    EXPECT_FLOAT_EQ(VdbDensityGrid::load({path, "density[1]", 1.0f, Affine3()}, count)->density(inside), 3.0f);
    EXPECT_FLOAT_EQ(VdbDensityGrid::load({path, "density[0]", 1.0f, Affine3()}, count)->density(inside), 1.0f);
    EXPECT_FLOAT_EQ(VdbDensityGrid::load({path, "temperature", 1.0f, Affine3()}, count)->density(inside), 5.0f);
    EXPECT_EQ(notices, 0) << "an explicit choice is not ambiguous";
    try {
        VdbDensityGrid::load({path, "density[2]", 1.0f, Affine3()}, count);
        FAIL() << "density[2] does not exist";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("holds 2"), std::string::npos) << m;
        EXPECT_NE(m.find("'density[1]' (float)"), std::string::npos) << "lists the grids by the names to use: " << m;
    }
}

}  // namespace
}  // namespace tyndall
