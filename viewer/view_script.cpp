#include "viewer/view_script.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace tyndall {

namespace {
struct LineReader {
    std::vector<std::string> words;
    size_t next = 1;
    std::string where;

    [[noreturn]] void fail(const std::string& what) const { throw Error(where + ": " + what); }
    bool more() const { return next < words.size(); }
    std::string word(const char* what) {
        if (!more()) fail(words[0] + ": missing " + what);
        return words[next++];
    }
    double number(const char* what, double lo, double hi) {
        std::string w = word(what);
        char* end = nullptr;
        double v = std::strtod(w.c_str(), &end);
        if (end == w.c_str() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
            fail(words[0] + ": " + what + " must be a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                 "], got '" + w + "'");
        return v;
    }
    int button() {
        std::string w = word("button (left, right or middle)");
        if (w == "left") return 0;
        if (w == "right") return 1;
        if (w == "middle") return 2;
        fail(words[0] + ": expected left, right or middle, got '" + w + "'");
    }
    int modifiers() {
        if (!more()) return 0;
        std::string w = word("modifiers"), part;
        int mods = 0;
        std::stringstream s(w);
        while (std::getline(s, part, '+')) {
            if (part == "shift") mods |= kModShift;
            else if (part == "ctrl") mods |= kModCtrl;
            else if (part == "alt") mods |= kModAlt;
            else fail(words[0] + ": modifiers are shift, ctrl, alt joined by '+', got '" + w + "'");
        }
        return mods;
    }
    void done() const {
        if (more()) fail(words[0] + ": unexpected '" + words[next] + "'");
    }
};

bool validKey(const std::string& k) {
    static const char* kKeys[] = {"F", "R", "S", "H", "B", "F5", "F12", "plus", "minus", "space", "escape"};
    for (const char* key : kKeys)
        if (k == key) return true;
    return k.size() == 1 && k[0] >= '1' && k[0] <= '9';
}

/// The commands that wait for a count of something (`counted`, as errors name it), at least 1, and
/// take an optional time-out in seconds.
struct WaitCommand {
    const char* name;
    ScriptOp op;
    const char* counted;
};
constexpr WaitCommand kWaitCommands[] = {{"wait-passes", ScriptOp::WaitPasses, "passes"},
                                         {"wait-input", ScriptOp::WaitInput, "releases"},
                                         {"wait-reload", ScriptOp::WaitReload, "reloads"},
                                         {"wait-final", ScriptOp::WaitFinal, "final renders"},
                                         {"wait-resize", ScriptOp::WaitResize, "resizes"}};
}  // namespace

std::vector<ScriptEvent> parseViewScript(const std::string& text, const std::string& file) {
    std::vector<ScriptEvent> events;
    std::istringstream lines(text);
    std::string line;
    const double kCoord = 1e6;
    for (int n = 1; std::getline(lines, line); ++n) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        LineReader r;
        r.where = file + ": line " + std::to_string(n);
        std::istringstream words(line);
        for (std::string w; words >> w;) r.words.push_back(w);
        if (r.words.empty()) continue;
        const std::string& cmd = r.words[0];
        ScriptEvent e;
        e.line = n;
        const WaitCommand* wait = nullptr;
        for (const WaitCommand& w : kWaitCommands)
            if (cmd == w.name) wait = &w;
        if (wait) {
            e.op = wait->op, e.value = std::floor(r.number(wait->counted, 1, 1e9));
            if (r.more()) e.timeout = r.number("seconds", 0.001, 1e6);
        } else if (cmd == "sleep") {
            e.op = ScriptOp::Sleep, e.value = r.number("milliseconds", 0, 3.6e6);
        } else if (cmd == "wait-frames") {
            e.op = ScriptOp::WaitFrames, e.value = std::floor(r.number("frames", 0, 1e7));
        } else if (cmd == "drop") {
            e.op = ScriptOp::Drop, e.text = r.word("path");
        } else if (cmd == "press" || cmd == "release") {
            e.op = cmd == "press" ? ScriptOp::Press : ScriptOp::Release;
            e.button = r.button();
            e.x = float(r.number("x", -kCoord, kCoord)), e.y = float(r.number("y", -kCoord, kCoord));
            if (cmd == "press") e.modifiers = r.modifiers();
        } else if (cmd == "move") {
            e.op = ScriptOp::Move;
            e.x = float(r.number("x", -kCoord, kCoord)), e.y = float(r.number("y", -kCoord, kCoord));
        } else if (cmd == "drag") {
            int button = r.button();
            float x0 = float(r.number("x0", -kCoord, kCoord)), y0 = float(r.number("y0", -kCoord, kCoord));
            float x1 = float(r.number("x1", -kCoord, kCoord)), y1 = float(r.number("y1", -kCoord, kCoord));
            int steps = r.more() ? int(r.number("steps", 1, 100000)) : 10;
            int mods = r.modifiers();
            r.done();
            ScriptEvent p = e;
            p.op = ScriptOp::Press, p.button = button, p.modifiers = mods, p.x = x0, p.y = y0;
            events.push_back(p);
            for (int i = 1; i <= steps; ++i) {
                ScriptEvent m = e;
                m.op = ScriptOp::Move, m.x = x0 + (x1 - x0) * float(i) / float(steps);
                m.y = y0 + (y1 - y0) * float(i) / float(steps);
                events.push_back(m);
            }
            e.op = ScriptOp::Release, e.button = button, e.x = x1, e.y = y1;
        } else if (cmd == "double-click") {
            e.op = ScriptOp::DoubleClick;
            e.x = float(r.number("x", -kCoord, kCoord)), e.y = float(r.number("y", -kCoord, kCoord));
        } else if (cmd == "scroll") {
            e.op = ScriptOp::Scroll;
            e.x = float(r.number("x", -kCoord, kCoord)), e.y = float(r.number("y", -kCoord, kCoord));
            e.value = r.number("steps", -1000, 1000);
        } else if (cmd == "key") {
            e.op = ScriptOp::Key, e.text = r.word("key name");
            if (!validKey(e.text))
                r.fail("key: expected F, R, S, H, B, F5, F12, 1-9, plus, minus, space or escape, got '" + e.text + "'");
        } else if (cmd == "exposure") {
            e.op = ScriptOp::Exposure, e.value = r.number("exposure", 1e-6, 1e6);
        } else if (cmd == "emission") {
            e.op = ScriptOp::Emission, e.medium = int(r.number("medium index", 0, 1e6));
            e.value = r.number("emission scale", 0, 1e6);
        } else if (cmd == "transparent") {
            const std::string w = r.word("on or off");
            if (w != "on" && w != "off") r.fail("transparent: expected on or off, got '" + w + "'");
            e.op = ScriptOp::Transparent, e.value = w == "on" ? 1 : 0;
        } else if (cmd == "save" || cmd == "screenshot") {
            e.op = cmd == "save" ? ScriptOp::Save : ScriptOp::Screenshot;
            e.text = r.word(cmd == "save" ? "file stem" : "file name");
        } else if (cmd == "quit") {
            e.op = ScriptOp::Quit;
        } else {
            r.fail("unknown command '" + cmd +
                   "' (expected sleep, wait-frames, wait-passes, wait-input, wait-reload, press, move, release, drag, double-click, scroll, "
                   "key, exposure, emission, transparent, save, screenshot or quit)");
        }
        r.done();
        events.push_back(e);
    }
    return events;
}

std::vector<ScriptEvent> loadViewScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error("--script '" + path + "': cannot be read");
    std::stringstream s;
    s << in.rdbuf();
    return parseViewScript(s.str(), path);
}

}  // namespace tyndall
