#pragma once
// The test hooks of `tyndall render`: environment variables read once, when the command starts
// (unset in normal use, not in --help; docs/production.md, "Test hooks"). They let a test stop a
// render at a chosen point and wait for its signal, plant bad samples, or make the GL splatter
// fail, so what a test sees never depends on how fast the machine is. The faults inside a pass go
// to the renderer and the driver as a TestHooks object (cpu/test_hooks.h), nothing is looked up
// per pass.
//   TYNDALL_TEST_CHECKPOINT_STALL_AT=K: the K-th checkpoint write of this run stops halfway
//     through its temporary file and waits there until the process is killed or interrupted.
//   TYNDALL_TEST_HOLD_AFTER_PASS=N: once the render holds N passes (resumed ones included) it
//     waits, still writing its periodic checkpoints, until it is killed or interrupted.
//   TYNDALL_TEST_NAN_PIXEL=X,Y: the camera stage's radiance at pixel (X, Y) is NaN in every pass.
//   TYNDALL_TEST_GL_FAIL_AFTER_PASS=N: the GL splat of every pass after the first N fails as a
//     lost GL context would.
// The waits give up after kTestHoldLimit seconds (a test that forgot to kill does not hang).
#include <cstdint>
#include <functional>

#include "cpu/test_hooks.h"

namespace tyndall::app {

constexpr double kTestHoldLimit = 300;

class RenderTestHooks : public TestHooks {
public:
    /// The hooks set in this process's environment (read on the first call).
    static const RenderTestHooks& fromEnvironment();

    /// Null when no hook that acts inside a pass is set (the renderer and driver then get none).
    const TestHooks* passHooks() const { return m_nanX >= 0 || m_glFail ? this : nullptr; }
    uint64_t holdAfterPass() const { return m_holdAfterPass; }
    /// The hook for saveCheckpoint (stalls the K-th write); empty when unset.
    std::function<void()> checkpointStall() const;

    void cameraRadiance(uint64_t pass, Image& radiance) const override;
    bool failGlSplat(uint64_t pass) const override { return m_glFail && pass >= m_glFailAfter; }

private:
    int m_nanX = -1, m_nanY = -1;
    bool m_glFail = false;
    uint64_t m_glFailAfter = 0;
    uint64_t m_holdAfterPass = 0;
    uint64_t m_checkpointStallAt = 0;
};

/// Sleeps in short steps until an interrupt or kTestHoldLimit seconds; `tick` runs at every step.
void holdForTests(const std::function<void()>& tick);

}  // namespace tyndall::app
