#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall render`: progressive photon beams to an image.
void addRenderCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
