// The viewer's final render: F12 or the panel's button saves the view and renders it with
// `tyndall render` in a child process at nice +10 (viewer/final_render.h), beside the view file.
#include "viewer/viewer_window.h"

#include <unistd.h>

#include <cstdio>

namespace tyndall {

namespace {
constexpr int kFinalNiceness = 10;

/// This program's path, to run its `render` command.
std::string selfExecutable() {
    char buf[4096];
    ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    return n > 0 ? std::string(buf, size_t(n)) : std::string();
}
}  // namespace

void Viewer::startFinalRender() {
    inputArrived();
    if (m_final.state() == FinalRender::State::Running) {
        m_status = "final render: one is running (" + m_final.lastLine() + ")";
        return;
    }
    const std::string stem = m_o.saveStem + "-" + std::to_string(++m_saves);
    const std::string view = save(stem);
    if (view.empty()) return;  // save said why
    const std::string self = selfExecutable();
    if (self.empty()) {
        m_status = "final render: cannot find the tyndall program (/proc/self/exe)";
        return;
    }
    m_finalOutput = stem + "-final.exr";
    std::vector<std::string> argv = {self,          "render", view, "-o", m_finalOutput, "--passes",
                                     std::to_string(std::max(m_finalPasses, 1)), "--progress-every", "0.5"};
    try {
        m_final.start(argv, kFinalNiceness);
    } catch (const std::exception& e) {
        m_status = e.what();
        return;
    }
    m_finalLine.clear();
    m_status = "final render started: " + m_finalOutput;
    std::printf("tyndall view: final render of %s (%d passes, nice +%d, pid %d) -> %s\n", view.c_str(),
                std::max(m_finalPasses, 1), kFinalNiceness, int(m_final.pid()), m_finalOutput.c_str());
    std::fflush(stdout);
}

void Viewer::pollFinalRender() {
    if (m_final.state() != FinalRender::State::Running) return;
    FinalRender::State state = m_final.poll();
    std::string line = m_final.lastLine();
    if (line != m_finalLine) m_finalLine = line, inputArrived();  // the panel shows the progress
    if (state == FinalRender::State::Running) return;
    ++m_finalsEnded;
    inputArrived();
    m_status = state == FinalRender::State::Done
                   ? "final render done: " + m_finalOutput
                   : "final render failed (exit " + std::to_string(m_final.exitStatus()) + "): " + line;
    std::printf("tyndall view: %s\n", m_status.c_str());
    std::fflush(stdout);
}

}  // namespace tyndall
