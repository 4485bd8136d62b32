#include "viewer/final_render.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"

namespace tyndall {

FinalRender::~FinalRender() { stop(); }

void FinalRender::start(const std::vector<std::string>& argv, int niceness) {
    if (m_state == State::Running) throw Error("final render: one is already running");
    if (argv.empty()) throw Error("final render: no program");
    if (m_reader.joinable()) m_reader.join();
    int pipeFds[2];
    if (pipe2(pipeFds, O_CLOEXEC) != 0) throw Error(std::string("final render: pipe: ") + std::strerror(errno));
    // Everything the child needs is made before fork: between fork and exec it calls only
    // async-signal-safe functions (this process has other threads).
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = fork();
    if (pid < 0) {
        close(pipeFds[0]);
        close(pipeFds[1]);
        throw Error(std::string("final render: fork: ") + std::strerror(errno));
    }
    if (pid == 0) {
        if (niceness != 0) (void)!nice(niceness);
        dup2(pipeFds[1], STDOUT_FILENO);
        dup2(pipeFds[1], STDERR_FILENO);
        execv(args[0], args.data());
        _exit(127);
    }
    close(pipeFds[1]);
    m_pid = pid;
    m_state = State::Running;
    m_exitStatus = 0;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_lastLine.clear();
    }
    m_reader = std::thread([this, fd = pipeFds[0]] { readOutput(fd); });
}

void FinalRender::readOutput(int fd) {
    std::string pending;
    char buf[4096];
    for (;;) {
        ssize_t n = read(fd, buf, sizeof buf);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        pending.append(buf, size_t(n));
        size_t end;
        while ((end = pending.find_first_of("\r\n")) != std::string::npos) {
            std::string line = pending.substr(0, end);
            pending.erase(0, end + 1);
            if (line.rfind("tyndall: ", 0) == 0) line.erase(0, 9);
            if (line.empty()) continue;
            std::lock_guard<std::mutex> lock(m_mutex);
            m_lastLine = line;
        }
    }
    close(fd);
}

FinalRender::State FinalRender::poll() {
    if (m_state != State::Running) return m_state;
    int status = 0;
    pid_t r = waitpid(m_pid, &status, WNOHANG);
    if (r == 0) return m_state;
    if (m_reader.joinable()) m_reader.join();  // the child's end of the pipe closed with it
    m_exitStatus = r < 0 ? -1 : WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    m_state = m_exitStatus == 0 ? State::Done : State::Failed;
    m_pid = -1;
    return m_state;
}

std::string FinalRender::lastLine() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_lastLine;
}

void FinalRender::stop() {
    if (m_state == State::Running) {
        kill(m_pid, SIGTERM);
        int status = 0;
        waitpid(m_pid, &status, 0);
        m_exitStatus = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        m_state = State::Failed;
        m_pid = -1;
    }
    if (m_reader.joinable()) m_reader.join();
}

}  // namespace tyndall
