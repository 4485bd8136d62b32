#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall compare`: the scene's heterogeneous medium next to its homogeneous twin.
void addCompareCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
