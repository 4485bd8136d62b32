#pragma once
// The viewer's final render (F12, the panel's button): `tyndall render VIEW.json` in a child
// process at a lower priority (nice), so the window stays usable while it runs. Its output
// (stdout and stderr: the render's progress lines and its summary) is read on a thread of its
// own; the UI thread polls the state and the last line for the panel. Window-free: unit-tested
// with any program (tests/viewer/final_render_test.cpp).
#include <sys/types.h>

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace tyndall {

class FinalRender {
public:
    enum class State { Idle, Running, Done, Failed };

    FinalRender() = default;
    /// Stops a render still running (SIGTERM: `tyndall render` writes the passes done and exits).
    ~FinalRender();
    FinalRender(const FinalRender&) = delete;
    FinalRender& operator=(const FinalRender&) = delete;

    /// Starts `argv` (argv[0] a path, not searched) niced by `niceness` (added to this process's),
    /// its stdout and stderr read into lastLine(). Throws Error when one is running or it cannot be
    /// started (an exec failure shows as Failed with exit status 127).
    void start(const std::vector<std::string>& argv, int niceness);
    /// Reaps the child when it has exited; call from the UI thread. Returns the state.
    State poll();
    State state() const { return m_state; }
    /// The exit status once Done (0) or Failed; the child's process id while Running.
    int exitStatus() const { return m_exitStatus; }
    pid_t pid() const { return m_pid; }
    /// The last non-empty line the child wrote ("" before the first), "tyndall: " stripped.
    std::string lastLine() const;
    /// Asks a running child to stop (SIGTERM) and waits for it.
    void stop();

private:
    void readOutput(int fd);

    State m_state = State::Idle;
    pid_t m_pid = -1;
    int m_exitStatus = 0;
    std::thread m_reader;
    mutable std::mutex m_mutex;
    std::string m_lastLine;
};

}  // namespace tyndall
