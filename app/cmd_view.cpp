#include "app/cmd_view.h"

#include <cmath>
#include <memory>

#include "app/cli_common.h"
#include "core/error.h"
#include "loading/default_smoke_scene.h"
#include "loading/scene_edits.h"
#include "viewer/viewer_app.h"

namespace tyndall::app {

namespace {
struct ViewCommandOptions {
    CommonOptions common;
    float exposure = 1.0f;
    std::string script, stats, saveStem = "tyndall-view";
    bool compare = false;
    float density = -1.0f;
    TwinRegion twin = TwinRegion::Support;
    int previewScale = 4, previewPhotons = 16;
    uint64_t finalPasses = 0;
    float uiScale = 0;
    bool transparent = false;
};
}  // namespace

void addViewCommand(CLI::App& app, int& exitCode) {
    auto o = std::make_shared<ViewCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "view", "Interactive viewer: drag the camera or a light, see a preview at once and the refinement on release "
                "(needs a display; docs/viewer.md)");
    CommonOptions& c = o->common;
    addSceneAndOutputOptions(cmd, c, "");
    addPpbOptions(cmd, c);
    addRegionOption(cmd, c);
    addGpuOption(cmd, c, "Primary-beam splatting on OpenGL: auto, on or off (as for `tyndall render`)");
    cmd->add_option("--exposure", o->exposure, "Display exposure (also + / - and the panel)")->capture_default_str();
    cmd->add_option("--script", o->script, "Scripted input (tests, benchmarks; format in docs/viewer.md)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--stats", o->stats, "Write UI frame times, preview rate and input latencies as JSON on exit");
    cmd->add_option("--save-stem", o->saveStem, "The S key writes STEM-N.exr, .png and .json")->capture_default_str();
    cmd->add_option("--ui-scale", o->uiScale,
                    "Panel scale, 0.5-4 (default: the monitor's content scale, e.g. from Xft.dpi)")
        ->check(CLI::Range(0.5, 4.0));
    cmd->add_option("--final-passes", o->finalPasses,
                    "Passes of the final render (F12: saves the view, renders it to STEM-N-final.exr in the "
                    "background); also set in the panel (default: the scene's render passes)")
        ->check(positiveInteger());
    cmd->add_flag("--compare", o->compare,
                  "Show the scene's density-grid media next to their homogeneous twins (as `tyndall compare`)");
    CLI::Option* density =
        cmd->add_option("--density", o->density, "--compare: density of the homogeneous twin (default: each grid's mean)");
    addTwinOption(cmd, o->twin);
    cmd->add_option("--preview-scale", o->previewScale, "Preview passes render at 1/N of the resolution per axis")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    cmd->add_option("--preview-photons", o->previewPhotons, "Preview passes trace 1/N of the photon paths")
        ->check(CLI::Range(1, 1024))
        ->capture_default_str();
    cmd->add_flag("--transparent", o->transparent,
                  "Transparent film, as tyndall render's: the image is shown over a checkerboard where it is not covered "
                  "and saved with its alpha channel; the render block's \"transparent\"");
    cmd->callback([o, cmd, density, &exitCode]() {
        CommonOptions& c = o->common;
        for (const char* opt : {"--passes", "--time"})
            if (cmd->get_option(opt)->count() > 0)
                throw Error(std::string(opt) + ": the viewer refines until you stop it (use `tyndall render` for a "
                                               "fixed budget, or save the view and render it)");
        finishOptions(c);
        if (!(o->exposure > 0) || !std::isfinite(o->exposure)) throw Error("--exposure must be a positive number");
        if (density->count() > 0 && !o->compare) throw Error("--density needs --compare");
        if (cmd->get_option("--twin")->count() > 0 && !o->compare) throw Error("--twin needs --compare");
        if (density->count() > 0 && !(o->density >= 0 && std::isfinite(o->density)))
            throw Error("--density must be a finite number >= 0");
        ViewerOptions v;
        v.scene = loadScene(c, &v.cameraNames, &v.cameras);
        v.base = c.scene.empty() ? kBuiltinDefaultScene : c.scene;
        v.baseCamera = c.camera;
        if (o->compare) {
            if (c.scene.empty()) {
                v.scene = makeDefaultSmokeScene();
                v.base = kBuiltinSmokeScene;
                v.cameras = {v.scene.camera};
            }
            v.scene.validate();
            v.twin = makeHomogeneousTwin(v.scene, o->density, nullptr, o->twin);
            v.twin.validate();
        }
        v.settings = c.settings;
        if (o->transparent) v.settings.transparentFilm = true;
        v.gpu = c.settings.gpu;
        v.exposure = o->exposure;
        v.script = o->script;
        v.statsPath = o->stats;
        v.saveStem = o->saveStem;
        v.uiScale = o->uiScale;
        v.finalPasses = o->finalPasses > 0 ? o->finalPasses : c.settings.passes;
        v.compare = o->compare;
        v.preview.scale = o->previewScale;
        v.preview.photonDivisor = o->previewPhotons;
        if (!o->compare) {
            v.scenePath = c.scene;
            v.load = [c](const std::string& path, std::vector<std::string>* names, std::vector<Camera>* cameras) {
                CommonOptions again = c;
                if (path != c.scene) again.camera.clear();
                again.scene = path;
                return loadScene(again, names, cameras);
            };
        }
        ThreadLimit threads(c.settings.threads);
        exitCode = runViewer(v);
    });
}

}  // namespace tyndall::app
