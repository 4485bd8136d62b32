#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall reference`: the unbiased volumetric path tracer (ground truth) to an image.
void addReferenceCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
