#include "app/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace tyndall::app {
namespace {
std::atomic<bool> g_interrupted{false};
extern "C" void onSignal(int) {
    if (g_interrupted.exchange(true)) std::_Exit(130);  // a second Ctrl-C quits at once
}
}  // namespace

void installInterruptHandler() {
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
}
bool interruptRequested() { return g_interrupted.load(); }
}  // namespace tyndall::app
