#include "app/interrupt.h"

#include <atomic>
#include <csignal>
#include <cstdlib>

namespace tyndall::app {
namespace {
std::atomic<int> g_interrupts{0};
std::atomic<int> g_quitAfter{2};
extern "C" void onSignal(int) {
    if (g_interrupts.fetch_add(1) + 1 >= g_quitAfter.load()) std::_Exit(130);
}
}  // namespace

void installInterruptHandler(int quitAfter) {
    g_quitAfter = quitAfter;
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
}
int interruptCount() {
    return g_interrupts.load();
}
}  // namespace tyndall::app
