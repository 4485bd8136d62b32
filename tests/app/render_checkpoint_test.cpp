// Checkpoint and resume as a farm meets them: a render killed with SIGKILL at several moments
// (right after its first checkpoint, in the middle of writing a later one, late in the render) and
// resumed ends bit for bit equal to the same render left alone; SIGTERM writes a checkpoint and
// exits 130; a resume against a changed scene file, a truncated or a foreign checkpoint fails
// with one line and exit 1 and leaves the checkpoint's bytes as they were. The file format itself
// (round trip, truncations) is tested in tests/core/checkpoint_test.cpp.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "app/render_checkpoint.h"
#include "core/checkpoint.h"
#include "core/error.h"
#include "core/image_io.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

namespace fs = std::filesystem;
using tyndall::test::runTyndall;

// Small and single-threaded: a whole render takes a second or two, so the suite stays quick. The
// tests never rely on it lasting long enough to be killed: test hooks hold it (below).
const std::string kRender = "render --size 64x48 --photons 600 --passes 48 --threads 1 --gpu off";

std::string dirFor(const std::string& name) {
    std::string d = tyndall::test::outputDir() + "/checkpoint_" + name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// A `tyndall` child process; killed (SIGKILL) and reaped on destruction if the test did not.
struct Child {
    pid_t pid = -1;
    ~Child() {
        if (pid > 0) {
            ::kill(pid, SIGKILL);
            waitpid(pid, nullptr, 0);
        }
    }
    /// Sends `sig` and waits for the exit; returns the wait status.
    int signalAndWait(int sig) {
        int status = 0;
        ::kill(pid, sig);
        waitpid(pid, &status, 0);
        pid = -1;
        return status;
    }
};

/// Starts `tyndall <args>` (split on spaces) with `env` ("NAME=value" entries) added; output to `log`.
/// The test hooks in `env` (app/cmd_render.cpp, docs/production.md) hold the render at a chosen
/// point until the test signals it, so no test depends on how fast the machine renders.
void spawnTyndall(Child& child, const std::string& args, const std::string& log, std::vector<std::string> env = {}) {
    std::vector<std::string> words{TYNDALL_BINARY};
    std::istringstream in(args);
    for (std::string w; in >> w;) words.push_back(w);
    pid_t pid = fork();
    if (pid == 0) {
        for (auto& e : env) putenv(e.data());
        FILE* f = std::freopen(log.c_str(), "w", stdout);
        if (f) dup2(fileno(stdout), 2);
        std::vector<char*> argv;
        for (auto& w : words) argv.push_back(w.data());
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        _exit(127);
    }
    child.pid = pid;
}

/// Waits (up to 60 s) until `cond` holds; false on time-out.
template <class F>
bool waitFor(F cond) {
    for (int i = 0; i < 6000; ++i) {
        if (cond()) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
}

uintmax_t sizeOf(const std::string& path) {
    std::error_code ec;
    uintmax_t n = fs::file_size(path, ec);
    return ec ? 0 : n;
}

uint64_t checkpointPasses(const std::string& path) {
    return tyndall::loadCheckpoint(path).header.at("passes_done").get<uint64_t>();
}

class KillAndResume : public ::testing::Test {
protected:
    /// Resumes `ck` to `out` and expects the uninterrupted render, bit for bit. The reference is
    /// rendered beside `out`: each test has its own directory, so tests run in parallel (ctest -j)
    /// never share (or delete) each other's files.
    void expectResumedEqualsFull(const std::string& ck, const std::string& out) {
        const std::string full = fs::path(out).parent_path().string() + "/full.exr";
        auto r = runTyndall(kRender + " -q -o " + full);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        r = runTyndall("render --resume " + ck + " -o " + out + " -q");
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_TRUE(tyndall::test::identicalImages(tyndall::readImage(out), tyndall::readImage(full)))
            << "resumed render differs from the uninterrupted one";
        EXPECT_EQ(tyndall::readImageAttribute(out, "tyndall:passes"), "48");
    }
};

// The render is held after pass kHold (TYNDALL_TEST_HOLD_AFTER_PASS) until it is killed, so it can
// never finish its 48 passes before the test's signal arrives, however loaded the machine is.
const std::string kHoldLate = "TYNDALL_TEST_HOLD_AFTER_PASS=40";

bool holdsPasses(const std::string& ck, uint64_t n) {
    return fs::exists(ck) && checkpointPasses(ck) == n;
}

TEST_F(KillAndResume, AfterTheFirstCheckpoint) {
    std::string d = dirFor("first"), ck = d + "/r.ckpt";
    Child child;
    spawnTyndall(child, kRender + " -o " + d + "/x.exr --checkpoint " + ck + " --checkpoint-every 0.05 -q", d + "/log",
                 {kHoldLate});
    ASSERT_TRUE(waitFor([&] { return fs::exists(ck); }));
    child.signalAndWait(SIGKILL);
    uint64_t done = checkpointPasses(ck);
    EXPECT_GE(done, 1u);
    EXPECT_LE(done, 40u) << "the render went past its hold";
    expectResumedEqualsFull(ck, d + "/resumed.exr");
}

TEST_F(KillAndResume, InTheMiddleOfACheckpointWrite) {
    std::string d = dirFor("midwrite"), ck = d + "/r.ckpt";
    // The second checkpoint write stops halfway through its temporary file and waits to be killed
    // (it comes at the latest during the hold after pass 40, whose periodic checkpoints go on).
    Child child;
    spawnTyndall(child, kRender + " -o " + d + "/x.exr --checkpoint " + ck + " --checkpoint-every 0.05 -q", d + "/log",
                 {kHoldLate, "TYNDALL_TEST_CHECKPOINT_STALL_AT=2"});
    ASSERT_TRUE(waitFor([&] { return fs::exists(ck); }));
    const std::string before = readBytes(ck);
    // The second write is under way (a half-written temporary file exists, or, were the write not
    // atomic, the checkpoint itself has changed): kill it there.
    ASSERT_TRUE(waitFor([&] { return sizeOf(ck + ".tmp") > 0 || readBytes(ck) != before; }));
    child.signalAndWait(SIGKILL);
    EXPECT_GT(sizeOf(ck + ".tmp"), 0u) << "the temporary file should be half written";
    EXPECT_LT(sizeOf(ck + ".tmp"), before.size()) << "the temporary file should be half written";
    EXPECT_TRUE(readBytes(ck) == before) << "a kill during a write must leave the previous checkpoint intact";
    expectResumedEqualsFull(ck, d + "/resumed.exr");
}

TEST_F(KillAndResume, LateInTheRenderAndTwice) {
    std::string d = dirFor("late"), ck = d + "/r.ckpt";
    const std::string args = kRender + " -o " + d + "/x.exr --checkpoint " + ck + " --checkpoint-every 0.05 -q";
    Child first;
    spawnTyndall(first, args, d + "/log", {kHoldLate});
    ASSERT_TRUE(waitFor([&] { return holdsPasses(ck, 40); }));
    first.signalAndWait(SIGKILL);
    // Resume, and kill the resumed render too, once it checkpointed 4 passes further.
    Child second;
    spawnTyndall(second, "render --resume " + ck + " --checkpoint-every 0.05 -q", d + "/log2",
                 {"TYNDALL_TEST_HOLD_AFTER_PASS=44"});
    ASSERT_TRUE(waitFor([&] { return holdsPasses(ck, 44); }));
    second.signalAndWait(SIGKILL);
    expectResumedEqualsFull(ck, d + "/resumed.exr");
}

TEST_F(KillAndResume, SigtermWritesACheckpointAndExits130) {
    std::string d = dirFor("sigterm"), ck = d + "/r.ckpt";
    // No periodic checkpoint within the run: the one found afterwards is SIGTERM's. The render is
    // held after pass 3 (its progress line is the test's cue), so SIGTERM finds it mid-render.
    Child child;
    spawnTyndall(child,
                 kRender + " -o " + d + "/x.exr --checkpoint " + ck + " --checkpoint-every 3600 --progress-every 0",
                 d + "/log", {"TYNDALL_TEST_HOLD_AFTER_PASS=3"});
    ASSERT_TRUE(waitFor([&] { return readBytes(d + "/log").find("pass 3/") != std::string::npos; }));
    EXPECT_FALSE(fs::exists(ck)) << "no checkpoint before SIGTERM (--checkpoint-every 3600)";
    int status = child.signalAndWait(SIGTERM);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);
    ASSERT_TRUE(fs::exists(ck));
    EXPECT_TRUE(fs::exists(d + "/x.exr")) << "what was rendered is written on SIGTERM";
    EXPECT_EQ(checkpointPasses(ck), 3u) << "the render stops after the pass SIGTERM found under way";
    EXPECT_EQ(tyndall::readImageAttribute(d + "/x.exr", "tyndall:passes"), "3");
    expectResumedEqualsFull(ck, d + "/resumed.exr");
}

TEST(ResumeErrors, ChangedSceneTruncatedAndForeignFilesAreRefusedUntouched) {
    std::string d = dirFor("errors");
    const std::string scene = d + "/box.json";
    fs::copy_file(std::string(TYNDALL_SOURCE_DIR) + "/scenes/caustic-box.json", scene);
    const std::string ck = d + "/r.ckpt";
    auto r = runTyndall("render " + scene + " --size 32x24 --photons 200 --passes 3 --gpu off -q -o " + d +
                        "/a.exr --checkpoint " + ck);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const std::string good = readBytes(ck);

    // Changed scene: fog twice as thick.
    std::string text = readBytes(scene);
    size_t at = text.find("\"sigma_s\": 0.06");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, 15, "\"sigma_s\": 0.12");
    std::ofstream(scene, std::ios::binary) << text;
    r = runTyndall("render --resume " + ck + " --passes 6 -q");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("different scene"), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_TRUE(readBytes(ck) == good) << "a refused resume must not touch the checkpoint";

    // Truncated at several lengths, and a foreign file (an EXR).
    for (size_t keep : {size_t(0), size_t(40), good.size() / 2, good.size() - 1}) {
        const std::string cut = d + "/cut.ckpt";
        std::ofstream(cut, std::ios::binary) << good.substr(0, keep);
        const std::string cutBytes = readBytes(cut);
        r = runTyndall("render --resume " + cut + " -q");
        EXPECT_EQ(r.exitCode, 1) << "kept " << keep << " bytes";
        EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
        EXPECT_NE(r.output.find("cut.ckpt"), std::string::npos) << r.output;
        EXPECT_TRUE(readBytes(cut) == cutBytes);
    }
    r = runTyndall("render --resume " + d + "/a.exr -q");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("not a Tyndall checkpoint"), std::string::npos) << r.output;
    // Options that would change the passes are refused with --resume.
    r = runTyndall("render --resume " + ck + " --photons 5 -q");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.output.find("--photons"), std::string::npos) << r.output;
}

// The on/off switches are recorded as set; a checkpoint written before a switch existed has no key
// for it and was rendered as with it off, so it resumes that way, whatever today's default.
TEST(ResumeRecord, SwitchesAbsentFromOlderCheckpointsReadAsTheyWereRendered) {
    tyndall::app::RenderRecord record;
    record.settings.equiangular = record.settings.directLight = record.settings.surfaceBoundary = true;
    tyndall::Checkpoint c =
        tyndall::app::makeCheckpoint(record, std::vector<std::pair<std::string, tyndall::Accumulator>>{});
    tyndall::RenderSettings now = tyndall::app::readRecord(c, "new.ckpt").settings;
    EXPECT_TRUE(now.equiangular && now.directLight && now.surfaceBoundary);
    for (const char* key : {"equiangular", "direct_light", "surface_boundary"}) c.header["settings"].erase(key);
    tyndall::RenderSettings old = tyndall::app::readRecord(c, "old.ckpt").settings;
    EXPECT_FALSE(old.equiangular);
    EXPECT_FALSE(old.directLight);
    EXPECT_FALSE(old.surfaceBoundary);
}

}  // namespace
