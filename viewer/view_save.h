#pragma once
// Saving what the viewer shows (the S key, a script's `save`): STEM.exr (linear, with the metadata
// `tyndall render` writes), STEM.png (tone-mapped at the window's exposure), both with the alpha
// channel of a transparent film (as `tyndall render --transparent` writes it), and STEM.json, a view
// file (loading/scene_edits.h) holding the base scene, the frame's edits and its resolved render
// settings (passes = the passes in the image, the radii resolved to scene units), so that
// `tyndall render STEM.json` renders the same image bit for bit (CPU mode).
#include <string>

#include "viewer/render_loop.h"

namespace tyndall {

struct SavedView {
    std::string exr, png, json;
};

/// The render settings that reproduce `frame`: its settings with passes = frame.passes, no time
/// budget, and the first radii resolved.
RenderSettings resolvedSettings(const ViewFrame& frame);

/// Writes the three files; `base`/`baseCamera` as for viewFileJson. Throws Error naming the file.
SavedView saveView(const ViewFrame& frame, const std::string& stem, const std::string& base,
                   const std::string& baseCamera, const std::string& sceneName, float exposure);

}  // namespace tyndall
