#include "app/test_hooks.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "app/interrupt.h"

namespace tyndall::app {

namespace {
const char* variable(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? v : nullptr;
}
uint64_t number(const char* name) {
    const char* v = variable(name);
    return v ? std::strtoull(v, nullptr, 10) : 0;
}
}  // namespace

const RenderTestHooks& RenderTestHooks::fromEnvironment() {
    static const RenderTestHooks hooks = [] {
        RenderTestHooks h;
        if (const char* xy = variable("TYNDALL_TEST_NAN_PIXEL")) std::sscanf(xy, "%d,%d", &h.m_nanX, &h.m_nanY);
        h.m_glFail = variable("TYNDALL_TEST_GL_FAIL_AFTER_PASS") != nullptr;
        h.m_glFailAfter = number("TYNDALL_TEST_GL_FAIL_AFTER_PASS");
        h.m_holdAfterPass = number("TYNDALL_TEST_HOLD_AFTER_PASS");
        h.m_checkpointStallAt = number("TYNDALL_TEST_CHECKPOINT_STALL_AT");
        return h;
    }();
    return hooks;
}

std::function<void()> RenderTestHooks::checkpointStall() const {
    if (!m_checkpointStallAt) return {};
    return [at = m_checkpointStallAt, writes = uint64_t(0)]() mutable {
        if (++writes == at) holdForTests({});
    };
}

void RenderTestHooks::cameraRadiance(uint64_t, Image& radiance) const {
    if (m_nanX >= 0 && m_nanX < radiance.width && m_nanY >= 0 && m_nanY < radiance.height)
        radiance.at(m_nanX, m_nanY).g = std::nanf("");
}

void holdForTests(const std::function<void()>& tick) {
    const auto start = std::chrono::steady_clock::now();
    while (!interruptRequested() &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < kTestHoldLimit) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (tick) tick();
    }
}

}  // namespace tyndall::app
