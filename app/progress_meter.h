#pragma once
// The render command's progress report on stderr. On a terminal: one line redrawn in place
// ("\r" + erase-to-end) with a bar, the percentage, passes/s and the ETA, for a pass target and
// for a time budget alike. Not on a terminal (logs, CI, a pipe): a plain line every `plainEvery`
// seconds and none in between, so a log is not flooded. Quiet: nothing. Called on the render
// loop's thread only.
#include <cstdint>
#include <cstdio>
#include <string>

namespace tyndall::app {

enum class ProgressStyle { Bar, Lines, Quiet };

struct ProgressTarget {
    uint64_t passes = 0;        ///< total passes of the render (used when seconds == 0)
    double seconds = 0;         ///< time budget of this run (> 0: the bar follows the clock)
    uint64_t passesBefore = 0;  ///< passes already rendered before this run (a resumed render)
};

/// Bar on a terminal, Lines otherwise, Quiet when asked.
ProgressStyle progressStyleFor(FILE* out, bool quiet);

/// "1:02:03", "4:05", "7 s"-style durations for the ETA ("--" for unknown or absurd values).
std::string formatDuration(double seconds);

class ProgressMeter {
public:
    ProgressMeter(FILE* out, ProgressStyle style, ProgressTarget target, double plainEvery = 5.0);
    /// After each pass: `passesDone` passes rendered by this run in `elapsed` seconds.
    void update(uint64_t passesDone, double elapsed);
    /// Ends the bar's line (Bar) so later output starts on a fresh line.
    void finish();
    /// The text of one report, without "\r" or newline (what update() draws; tests use it too).
    std::string line(uint64_t passesDone, double elapsed, int width) const;

private:
    FILE* m_out;
    ProgressStyle m_style;
    ProgressTarget m_target;
    double m_plainEvery;
    double m_lastPlain = 0;
    bool m_drawn = false;
};

}  // namespace tyndall::app
