#pragma once
#include <CLI/CLI.hpp>

namespace tyndall::app {
/// `tyndall view [SCENE]`: the interactive viewer (viewer/viewer_app.h). Parses only.
void addViewCommand(CLI::App& app, int& exitCode);
}  // namespace tyndall::app
