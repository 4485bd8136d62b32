#pragma once
// `tyndall view --script FILE`: scripted input for tests, benchmarks and screenshots. One command
// per line, `#` starts a comment; coordinates are pixels of the image area (origin top-left; in
// the compare view, of the left half). docs/viewer.md documents the format:
//   sleep MS                      let MS milliseconds of wall time pass (the UI keeps drawing)
//   wait-frames N                 let N UI frames pass
//   wait-passes N [SECONDS]       wait until the refinement of the current view has >= N passes
//                                 (error after SECONDS, default 600)
//   wait-input N [SECONDS]        wait until N mouse-button releases have come from the window
//                                 system since the start (real input, e.g. xdotool in tests)
//   wait-reload N [SECONDS]       wait until the scene file has been reloaded or a dropped file
//                                 opened (or tried: a bad file counts) N times since the start
//   wait-final N [SECONDS]        wait until N final renders (F12) have ended (done or failed)
//   wait-resize N [SECONDS]       wait until the image has followed the window's size N times
//   drop PATH                     as a file dropped on the window: opens it as the scene
//   press BUTTON X Y [MODS]       BUTTON: left | right | middle; MODS: shift, ctrl, alt joined by +
//   move X Y                      the cursor moves (drags when a button is down)
//   release BUTTON X Y
//   drag BUTTON X0 Y0 X1 Y1 [STEPS] [MODS]   press, STEPS moves (default 10, one per frame), release
//   double-click X Y              sets the pivot to the surface under (X, Y)
//   scroll X Y STEPS              the wheel: STEPS > 0 dollies in
//   key NAME                      F, 1-9, plus, minus, space, R, S, H, B, F5, F12, escape (as typed)
//   exposure VALUE                sets the display exposure
//   emission MEDIUM SCALE         sets the emission slider of medium MEDIUM (from 0, in scene order;
//                                 with --compare it drives the grid and its twin) to SCALE
//   transparent on|off            the panel's "transparent film" checkbox
//   save STEM                     writes STEM.exr, STEM.png and STEM.json (as the S key)
//   screenshot FILE               the window's pixels as PNG
//   quit                          closes the window, exit status 0
// Parsing is GLFW-free (tests/viewer/view_script_test.cpp).
#include <string>
#include <vector>

namespace tyndall {

enum class ScriptOp { Sleep, WaitFrames, WaitPasses, WaitInput, WaitReload, WaitFinal, WaitResize, Drop, Press, Move, Release, DoubleClick, Scroll, Key, Exposure, Emission, Transparent, Save,
                      Screenshot, Quit };

enum ScriptModifier : int { kModShift = 1, kModCtrl = 2, kModAlt = 4 };

struct ScriptEvent {
    ScriptOp op = ScriptOp::Quit;
    int button = 0;        ///< 0 left, 1 right, 2 middle
    int modifiers = 0;     ///< ScriptModifier bits
    float x = 0, y = 0;    ///< image-area pixels
    double value = 0;      ///< ms, frames, passes, scroll steps, exposure, emission scale, transparent 1/0
    int medium = 0;        ///< emission: the medium's index
    double timeout = 600;  ///< wait-passes: seconds
    std::string text;      ///< key name, file stem or path
    int line = 0;          ///< in the script file, for messages
};

/// Parses a script; throws Error "<file>: line N: ..." naming what was expected.
std::vector<ScriptEvent> parseViewScript(const std::string& text, const std::string& file);
/// Reads and parses a script file.
std::vector<ScriptEvent> loadViewScript(const std::string& path);

}  // namespace tyndall
