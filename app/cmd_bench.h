#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall bench`: what this machine does with a scene: the throughput of every stage and, with
/// OpenGL, the split between the CPU passes and the GL splat.
void addBenchCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
