// `tyndall reference`: bad options fail with a message naming the option or file (before any
// rendering), and a small render writes a readable image of the requested size.
#include "app/cmd_reference.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "core/image_io.h"

namespace tyndall {
namespace {

/// Parses `args` as `tyndall <args>` with only the reference command registered.
int runReference(const std::string& args) {
    CLI::App app{"tyndall"};
    app.require_subcommand(1);
    int exitCode = -1;
    app::addReferenceCommand(app, exitCode);
    app.parse(args, false);
    return exitCode;
}

void expectErrorNaming(const std::string& args, const std::string& what) {
    try {
        runReference(args);
        ADD_FAILURE() << "'" << args << "' did not fail";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << "message: " << e.what();
    }
}

TEST(CmdReference, BadValuesNameTheOption) {
    expectErrorNaming("reference --spp 0", "--spp");
    expectErrorNaming("reference --max-depth 0", "--max-depth");
    expectErrorNaming("reference --size 0x16", "--size");
    expectErrorNaming("reference --size banana", "--size");
    expectErrorNaming("reference --spp 1 -o /nonexistent-dir/ref.png", "/nonexistent-dir/ref.png");
    expectErrorNaming("reference --spp 1 -o ref.bmpx", "ref.bmpx");
    EXPECT_THROW(runReference("reference --spp -3"), CLI::ParseError);
}

TEST(CmdReference, WritesTheImage) {
    std::string out = std::string(TYNDALL_TEST_OUTPUT_DIR) + "/cmd_reference.exr";
    std::filesystem::remove(out);
    EXPECT_EQ(runReference("reference --spp 2 --size 12x8 --seed 3 -o " + out), 0);
    Image img = readImage(out);
    EXPECT_EQ(img.width, 12);
    EXPECT_EQ(img.height, 8);
    double sum = 0;
    for (const Rgb& p : img.pixels) sum += p.r + p.g + p.b;
    EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace tyndall
