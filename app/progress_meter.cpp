#include "app/progress_meter.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace tyndall::app {

ProgressStyle progressStyleFor(FILE* out, bool quiet) {
    if (quiet) return ProgressStyle::Quiet;
    return isatty(fileno(out)) ? ProgressStyle::Bar : ProgressStyle::Lines;
}

std::string formatDuration(double seconds) {
    if (!std::isfinite(seconds) || seconds < 0 || seconds > 1e8) return "--";
    long s = long(std::lround(seconds));
    char buf[32];
    if (s < 60)
        std::snprintf(buf, sizeof buf, "%ld s", s);
    else if (s < 3600)
        std::snprintf(buf, sizeof buf, "%ld:%02ld", s / 60, s % 60);
    else
        std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    return buf;
}

ProgressMeter::ProgressMeter(FILE* out, ProgressStyle style, ProgressTarget target, double plainEvery)
    : m_out(out), m_style(style), m_target(target), m_plainEvery(plainEvery) {}

std::string ProgressMeter::line(uint64_t passesDone, double elapsed, int width) const {
    const uint64_t total = m_target.passesBefore + passesDone;
    const double rate = passesDone / std::max(elapsed, 1e-9);
    double fraction, eta;
    char count[64];
    if (m_target.seconds > 0) {
        fraction = elapsed / m_target.seconds;
        eta = m_target.seconds - elapsed;
        std::snprintf(count, sizeof count, "pass %llu", (unsigned long long)total);
    } else {
        const uint64_t target = std::max<uint64_t>(m_target.passes, 1);
        fraction = double(total) / double(target);
        eta = passesDone ? double(m_target.passes - std::min(total, m_target.passes)) / rate : NAN;
        std::snprintf(count, sizeof count, "pass %llu/%llu", (unsigned long long)total,
                      (unsigned long long)m_target.passes);
    }
    fraction = std::clamp(fraction, 0.0, 1.0);
    char tail[160];
    std::snprintf(tail, sizeof tail, "%3d%%  %s  %.2f passes/s  ETA %s", int(fraction * 100), count, rate,
                  formatDuration(std::max(eta, 0.0)).c_str());
    std::string text = tail;
    if (m_style != ProgressStyle::Bar) return text;
    // Bar: what is left of the terminal's width, between 10 and 40 cells.
    int cells = std::clamp(width - int(text.size()) - 4, 0, 40);
    if (cells < 10) return text;
    int filled = int(fraction * cells + 0.5);
    return "[" + std::string(filled, '#') + std::string(cells - filled, '.') + "] " + text;
}

void ProgressMeter::update(uint64_t passesDone, double elapsed) {
    if (m_style == ProgressStyle::Quiet) return;
    if (m_style == ProgressStyle::Lines) {
        if (elapsed - m_lastPlain < m_plainEvery) return;
        m_lastPlain = elapsed;
        std::fprintf(m_out, "tyndall: %s\n", line(passesDone, elapsed, 0).c_str());
        std::fflush(m_out);
        return;
    }
    winsize ws{};
    int width = ioctl(fileno(m_out), TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 ? ws.ws_col : 80;
    // "\r" back to the line's start, "\x1b[K" erases what a longer previous line left.
    std::fprintf(m_out, "\r%s\x1b[K", line(passesDone, elapsed, width - 1).c_str());
    std::fflush(m_out);
    m_drawn = true;
}

void ProgressMeter::finish() {
    if (m_style == ProgressStyle::Bar && m_drawn) std::fprintf(m_out, "\n");
    m_drawn = false;
}

}  // namespace tyndall::app
