#pragma once
// Ctrl-C during a render stops after the current pass and writes what was rendered.
namespace tyndall::app {
void installInterruptHandler();
bool interruptRequested();
}  // namespace tyndall::app
