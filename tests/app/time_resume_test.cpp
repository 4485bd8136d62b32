// Checkpoints of `--time` renders: the seconds already spent are saved and read back, so a resumed
// render spends only what is left of its budget, and the saved total is the sum of its runs. (The
// kill-and-resume tests in tests/app/render_checkpoint_test.cpp all use --passes.)
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/checkpoint.h"
#include "tests/test_util.h"
#include "tests/tyndall_cli.h"

namespace {

using tyndall::test::runTyndall;

std::string path(const std::string& name) { return tyndall::test::outputDir() + "/time_resume_" + name; }

std::string writeScene() {
    std::string p = path("scene.json");
    std::ofstream(p) << R"({"name": "time-resume",
 "materials": [{"name": "grey", "albedo": 0.5}],
 "media": [{"name": "fog", "sigma_s": 0.2, "sigma_a": 0.02}], "global_medium": "fog",
 "shapes": [{"type": "quad", "name": "floor", "material": "grey", "corner": [-1, 0, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2]}],
 "lights": [{"type": "point", "name": "p", "position": [0, 1, 0], "intensity": 1}],
 "cameras": [{"name": "c", "position": [0, 1, 3], "target": [0, 0.5, 0], "fov": 50}]})";
    return p;
}

struct Saved {
    double elapsed = 0;
    uint64_t passes = 0;
};
Saved readCheckpoint(const std::string& file) {
    tyndall::Checkpoint c = tyndall::loadCheckpoint(file);
    return {c.header.at("elapsed").get<double>(), c.header.at("passes_done").get<uint64_t>()};
}

/// Seconds of wall-clock time `f` takes.
template <class F>
double timed(F&& f) {
    auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Starts `tyndall <args>` (split on spaces), its output to `log`; returns its pid.
pid_t spawnTyndall(const std::string& args, const std::string& log) {
    std::vector<std::string> words{TYNDALL_BINARY};
    std::istringstream in(args);
    for (std::string w; in >> w;) words.push_back(w);
    pid_t pid = fork();
    if (pid == 0) {
        FILE* f = std::freopen(log.c_str(), "w", stdout);
        if (f) dup2(fileno(stdout), 2);
        std::vector<char*> argv;
        for (auto& w : words) argv.push_back(w.data());
        argv.push_back(nullptr);
        execv(argv[0], argv.data());
        _exit(127);
    }
    return pid;
}

// Tiny passes (well under a millisecond): a render overshoots its budget by about one pass; the
// slack is for a loaded machine. The planted bugs these catch are whole runs off: a resume that
// forgets the seconds spent renders the whole budget again (saved total 1 s too high), one that
// saves only its own run's seconds saves 1 s too little. Wall-clock times include the program's
// start (a second or more on a loaded 2-core machine), so they are only held from below.
constexpr double kSlack = 0.3;
const std::string kSmall = " --size 16x12 --photons 300 --gpu off -q";

TEST(TimeResume, ANewBudgetCountsTheSecondsAlreadySpent) {
    const std::string scene = writeScene(), ck = path("a.ckpt"), exr = path("a.exr");
    std::remove(ck.c_str());
    auto r = runTyndall("render " + scene + kSmall + " --time 1 --checkpoint " + ck + " -o " + exr);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Saved first = readCheckpoint(ck);
    EXPECT_GE(first.elapsed, 1.0);
    EXPECT_LT(first.elapsed, 1.0 + kSlack);
    ASSERT_GT(first.passes, 0u);

    double wall = timed([&] { r = runTyndall("render --resume " + ck + " --time 2 -q"); });
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Saved second = readCheckpoint(ck);
    std::printf("first run %.3f s, %llu passes; after resuming to 2 s: %.3f s, %llu passes; resume took %.3f s\n",
                first.elapsed, (unsigned long long)first.passes, second.elapsed, (unsigned long long)second.passes, wall);
    EXPECT_GE(second.elapsed, 2.0) << "the saved time is the total of both runs";
    EXPECT_LT(second.elapsed, 2.0 + kSlack) << "the resumed run spent more than what was left of the budget";
    EXPECT_GT(second.passes, first.passes);
    EXPECT_GT(wall, 2.0 - first.elapsed - 0.05) << "the resumed run stopped before its budget";
}

TEST(TimeResume, AnInterruptedTimedRenderResumesToItsOwnBudget) {
    const std::string scene = writeScene(), ck = path("b.ckpt"), exr = path("b.exr"), log = path("b.log");
    std::remove(ck.c_str());
    // SIGTERM once the render has saved a checkpoint (every 0.2 s) and run a little more: it saves
    // its state and exits 130. Polling the file keeps the test independent of the start-up time.
    pid_t pid = spawnTyndall("render " + scene + kSmall + " --time 2 --checkpoint " + ck + " --checkpoint-every 0.2 -o " +
                             exr, log);
    bool saved = false;
    for (int i = 0; i < 6000 && !saved; ++i) {
        saved = std::filesystem::exists(ck);
        if (!saved) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(saved) << "no checkpoint within 60 s";
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 130) << "status " << status;
    const Saved first = readCheckpoint(ck);
    ASSERT_GT(first.passes, 0u);
    EXPECT_GT(first.elapsed, 0.2);
    EXPECT_LT(first.elapsed, 2.0) << "interrupted before its budget";

    auto r = runTyndall("render --resume " + ck + " -q");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Saved second = readCheckpoint(ck);
    std::printf("interrupted at %.3f s, %llu passes; resumed to %.3f s, %llu passes\n", first.elapsed,
                (unsigned long long)first.passes, second.elapsed, (unsigned long long)second.passes);
    EXPECT_GE(second.elapsed, 2.0) << "the resumed render keeps its own --time 2";
    EXPECT_LT(second.elapsed, 2.0 + kSlack) << "the resumed render spent more than what was left of its budget";
    EXPECT_GT(second.passes, first.passes);
}

}  // namespace
