#pragma once
// Ctrl-C (SIGINT) or SIGTERM during a render stops after the current pass and writes what was
// rendered. Each signal counts one interrupt; the `quitAfter`-th quits at once (exit code 130)
// for a user who does not want to wait for the writing.
namespace tyndall::app {
/// `tyndall render`: quitAfter 2 (one Ctrl-C stops and writes, a second quits). `tyndall
/// compare`: 3 (the first ends the heterogeneous half, the second its homogeneous twin).
void installInterruptHandler(int quitAfter = 2);
/// Interrupts received so far.
int interruptCount();
inline bool interruptRequested() {
    return interruptCount() > 0;
}
}  // namespace tyndall::app
