// Checkpoint writes that fail while a render goes on (a full disk, a folder in the way): the
// previous checkpoint stays as it was, the failure is said once, the render finishes and writes
// its image. Real failures, no injected ones: the temporary file's path ("FILE.tmp") is made a
// folder (open() fails on every write, root or not) or a link to /dev/full (the write fails with
// "No space left on device", as on a full disk, once: the failed write removes the link).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/checkpoint.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

namespace fs = std::filesystem;
using tyndall::test::CliRun;

std::string fileBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

uint64_t passesIn(const std::string& path) {
    return tyndall::loadCheckpoint(path).header.at("passes_done").get<uint64_t>();
}

TEST(FailingCheckpoints, TheRenderGoesOnAndThePreviousCheckpointStays) {
    const std::string dir = tyndall::test::outputDir() + "/failing-checkpoints";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string ckpt = dir + "/frame.ckpt", image = dir + "/frame.png";
    CliRun first = tyndall::test::runTyndall("render --size 16x16 --passes 2 --photons 200 --gpu off --quiet -o " +
                                             image + " --checkpoint " + ckpt);
    ASSERT_EQ(first.exitCode, 0) << first.output;
    const std::string before = fileBytes(ckpt);
    ASSERT_EQ(passesIn(ckpt), 2u);

    // Every write fails: a folder where the temporary file goes.
    fs::create_directory(ckpt + ".tmp");
    fs::remove(image);
    CliRun blocked = tyndall::test::runTyndall("render --resume " + ckpt +
                                               " --passes 6 --checkpoint-every 0.000001 --quiet -o " + image);
    EXPECT_EQ(blocked.exitCode, 0) << blocked.output;
    EXPECT_EQ(count(blocked.output, "checkpoints are failing"), 1u) << blocked.output;
    EXPECT_NE(blocked.output.find("cannot create '" + ckpt + ".tmp'"), std::string::npos) << blocked.output;
    EXPECT_NE(blocked.output.find("checkpoint writes failed; '" + ckpt + "' holds no checkpoint written by this run"),
              std::string::npos)
        << blocked.output;
    EXPECT_TRUE(fs::exists(image)) << "the image is written all the same";
    EXPECT_EQ(fileBytes(ckpt), before) << "the previous checkpoint must stay as it was";

    // A full disk for one write: it fails, later ones succeed, the last holds the whole render.
    fs::remove(ckpt + ".tmp");
    fs::create_symlink("/dev/full", ckpt + ".tmp");
    CliRun full = tyndall::test::runTyndall("render --resume " + ckpt +
                                            " --passes 8 --checkpoint-every 0.000001 --quiet -o " + image);
    EXPECT_EQ(full.exitCode, 0) << full.output;
    EXPECT_EQ(count(full.output, "checkpoints are failing"), 1u) << full.output;
    EXPECT_NE(full.output.find("No space left on device"), std::string::npos) << full.output;
    EXPECT_NE(full.output.find("1 of "), std::string::npos) << full.output;
    EXPECT_NE(full.output.find("holds the checkpoint of pass 8"), std::string::npos) << full.output;
    EXPECT_EQ(passesIn(ckpt), 8u);
}

}  // namespace
