#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall bench`: throughput of every stage on a scene, each against a baseline from the same run.
void addBenchCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
