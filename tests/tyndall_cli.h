#pragma once
// Runs the `tyndall` binary as a user does, for the tests that drive the command line (their
// target defines TYNDALL_BINARY, see tests/CMakeLists.txt).
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace tyndall::test {

struct CliRun {
    int exitCode = -1;   ///< -1 when the program did not exit normally (a signal, a crash)
    std::string output;  ///< stdout and stderr together
};

/// `tyndall <args>` through the shell (quote paths with spaces yourself), with `environment`
/// ("NAME=value ...") added to its environment.
inline CliRun runShell(const std::string& cmd);
inline CliRun runTyndall(const std::string& args, const std::string& environment = "") {
    return runShell((environment.empty() ? "" : "env " + environment + " ") + std::string(TYNDALL_BINARY) + " " +
                    args + " 2>&1");
}

/// A shell command line (popen: /bin/sh -c), its output and exit status.
inline CliRun runShell(const std::string& cmd) {
    CliRun r;
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return r;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
    int status = pclose(pipe);
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

}  // namespace tyndall::test
