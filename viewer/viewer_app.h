#pragma once
// `tyndall view`: the interactive viewer window (GLFW + Dear ImGui). The UI thread owns the
// window, draws the newest running mean of each render loop (viewer/render_loop.h) tone-mapped on
// the GPU when there is something new to show (a published pass, input; at most 60 frames a
// second, none at rest), runs the panel, and turns mouse and keys (or a --script) into
// camera, light and medium edits; the render loops run on their own threads and the UI never
// waits for a pass. docs/viewer.md lists the bindings.
#include <functional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "core/settings.h"
#include "hybrid/pass_scheduler.h"
#include "viewer/render_loop.h"

namespace tyndall {

struct ViewerOptions {
    Scene scene;                       ///< loaded and validated (the heterogeneous half for compare)
    RenderSettings settings;           ///< resolved: the scene's render block and the options
    GpuMode gpu = GpuMode::Auto;
    std::string base;                  ///< the scene as a view file's "base" (a path or builtin:...)
    std::string baseCamera;            ///< the --camera it was loaded with
    std::vector<std::string> cameraNames;  ///< the scene's cameras (keys 1-9, the panel list)
    std::vector<Camera> cameras;
    float exposure = 1.0f;
    std::string script;                ///< --script FILE ("" = interactive)
    std::string saveStem = "tyndall-view";  ///< the S key writes STEM-N.{exr,png,json}
    uint64_t finalPasses = 64;         ///< F12's render of the saved view: STEM-N-final.exr
    bool compare = false;              ///< show `twin` (homogeneous) next to `scene`
    Scene twin;
    PreviewOptions preview;
    float uiScale = 0;                 ///< --ui-scale: the panel's scale (0 = the monitor's content scale)
    std::string statsPath;             ///< --stats FILE: frame times, preview rate, latencies (JSON)
    /// The scene file, polled for changes ("" for a built-in scene and --compare: nothing reloads).
    std::string scenePath;
    /// Loads a scene file as at the start (the --camera given for scenePath, the first camera for
    /// another file: a dropped one); throws Error naming the file and place. Unset with --compare.
    std::function<Scene(const std::string& path, std::vector<std::string>* cameraNames, std::vector<Camera>* cameras)>
        load;
};

/// Opens the window and runs until Escape, the window's close button or a script's quit; returns
/// the exit status (0). Throws Error with one line when there is no display or no OpenGL 3.3
/// ("... use `tyndall render`"), or when a render loop fails.
int runViewer(ViewerOptions& options);

}  // namespace tyndall
