#pragma once
// Faults that tests plant in a render, through an object handed to the renderer and the render
// driver (PassRenderer::setTestHooks, SchedulerOptions::hooks). Null in normal use: no test hook
// is looked up per pass. `tyndall render` builds one from its environment once, at start
// (app/test_hooks.h); in-process tests subclass it.
#include <cstdint>

#include "core/image.h"

namespace tyndall {

class TestHooks {
public:
    virtual ~TestHooks() = default;
    /// The camera stage's radiance of pass `pass` (its first photon batch): a test may plant bad
    /// samples (NaN) here to follow them through the loop to the accumulator's guard.
    virtual void cameraRadiance(uint64_t /*pass*/, Image& /*radiance*/) const {}
    /// Called on the GL thread before pass `pass`'s primary media are splatted: true makes the
    /// splat fail as a lost GL context would (the driver then goes on on the CPU).
    virtual bool failGlSplat(uint64_t /*pass*/) const { return false; }
};

}  // namespace tyndall
