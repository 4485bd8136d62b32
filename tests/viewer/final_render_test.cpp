// FinalRender (viewer/final_render.h): the child runs niced by the amount asked, its last output
// line and exit status come back, a program that cannot start fails with 127, stop() ends it.
#include "viewer/final_render.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <thread>

#include "core/error.h"

namespace tyndall {
namespace {

FinalRender::State waitForEnd(FinalRender& r, double seconds = 20) {
    auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (r.poll() == FinalRender::State::Running && std::chrono::steady_clock::now() < end)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return r.state();
}

TEST(FinalRender, TheChildRunsNicedAndItsLastLineAndStatusComeBack) {
    const int ours = getpriority(PRIO_PROCESS, 0);
    FinalRender r;
    r.start({"/bin/sh", "-c", "echo 'tyndall: 50%  pass 1/2'; nice; exit 3"}, 7);
    EXPECT_EQ(r.state(), FinalRender::State::Running);
    EXPECT_THROW(r.start({"/bin/true"}, 0), Error) << "a second one while the first runs";
    ASSERT_EQ(waitForEnd(r), FinalRender::State::Failed);
    EXPECT_EQ(r.exitStatus(), 3);
    // `nice` prints the child's niceness: ours plus the 7 asked (capped at 19).
    EXPECT_EQ(r.lastLine(), std::to_string(std::min(ours + 7, 19)));

    r.start({"/bin/sh", "-c", "printf 'tyndall: pass 1/2\\rtyndall: pass 2/2\\nrendered x -> y.exr\\n'"}, 0);
    ASSERT_EQ(waitForEnd(r), FinalRender::State::Done);
    EXPECT_EQ(r.exitStatus(), 0);
    EXPECT_EQ(r.lastLine(), "rendered x -> y.exr");
}

TEST(FinalRender, AProgramThatCannotStartFailsWith127AndStopEndsARunningOne) {
    FinalRender r;
    r.start({"/no/such/program"}, 0);
    ASSERT_EQ(waitForEnd(r), FinalRender::State::Failed);
    EXPECT_EQ(r.exitStatus(), 127);

    r.start({"/bin/sleep", "30"}, 0);
    auto t0 = std::chrono::steady_clock::now();
    r.stop();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
    EXPECT_EQ(r.state(), FinalRender::State::Failed);
    EXPECT_EQ(r.exitStatus(), 128 + 15) << "SIGTERM";
}

}  // namespace
}  // namespace tyndall
