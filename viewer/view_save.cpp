#include "viewer/view_save.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/image_io.h"
#include "loading/scene_edits.h"

namespace tyndall {

RenderSettings resolvedSettings(const ViewFrame& frame) {
    RenderSettings s = frame.settings;
    s.passes = frame.passes;
    s.timeBudget = 0;
    s.radius = frame.radii.beamRadius;
    s.surfaceRadius = frame.radii.surfaceRadius;
    return s;
}

SavedView saveView(const ViewFrame& frame, const std::string& stem, const std::string& base,
                   const std::string& baseCamera, const std::string& sceneName, float exposure) {
    SavedView out{stem + ".exr", stem + ".png", stem + ".json"};
    RenderSettings s = resolvedSettings(frame);
    nlohmann::json settings = s.toJson();
    // A view file's base is relative to the view file: make a relative base absolute first.
    std::string basePath = base;
    if (base.rfind("builtin:", 0) != 0) basePath = std::filesystem::absolute(base).lexically_normal().string();
    nlohmann::json view = viewFileJson(sceneName, basePath, baseCamera, frame.edits, settings);
    {
        std::ofstream f(out.json);
        if (!f) throw Error("save: cannot write '" + out.json + "'");
        f << view.dump(2) << "\n";
        if (!f) throw Error("save: failed writing '" + out.json + "'");
    }
    nlohmann::json meta = settings;
    meta["resolved_radius"] = frame.radii.beamRadius;
    meta["resolved_surface_radius"] = frame.radii.surfaceRadius;
    ImageMetadata metadata = {{"Software", "tyndall"},
                              {"tyndall:scene", out.json},
                              {"tyndall:settings", meta.dump()},
                              {"tyndall:passes", std::to_string(frame.passes)},
                              {"tyndall:photon_paths", std::to_string(frame.passes * s.photonsPerPass)},
                              {"tyndall:viewer", frame.mode == RenderMode::Refine ? "refined" : "preview"}};
    const Image* alpha = frame.alpha.width > 0 ? &frame.alpha : nullptr;
    writeImageLayers(out.exr, frame.mean, {}, metadata, 1.0f, alpha);
    writeImageLayers(out.png, frame.mean, {}, {}, exposure, alpha);
    return out;
}

}  // namespace tyndall
