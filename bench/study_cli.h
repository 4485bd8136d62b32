#pragma once
// The command line of a study program: parse, run, and turn errors into one line and an exit code
// (2 for bad options, as CLI11 says; 1 for an Error, prefixed with the program's name).
#include <CLI/CLI.hpp>

#include <functional>

namespace tyndall::bench {

int runStudy(CLI::App& cli, int argc, char** argv, const std::function<void()>& study);

}  // namespace tyndall::bench
