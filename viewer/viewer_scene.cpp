// The viewer's edited scene: its panel state, its render loops, reloading the scene file, saving.
#include "viewer/viewer_window.h"

#include <algorithm>
#include <cstdio>

#include "core/error.h"
#include "core/image_io.h"
#include "loading/scene_edits.h"
#include "viewer/view_save.h"

namespace tyndall {

void Viewer::initEditUi() {
    m_lightUi.clear();
    m_mediumUi.clear();
    for (const Light& l : m_edited.lights) {
        LightUi u;
        float p = std::max({l.intensity.r, l.intensity.g, l.intensity.b});
        u.power = p;
        if (p > 0) u.colour[0] = l.intensity.r / p, u.colour[1] = l.intensity.g / p, u.colour[2] = l.intensity.b / p;
        m_lightUi.push_back(u);
    }
    if (m_edited.environment) {
        m_environmentScale = m_edited.environment->scale();
        m_environmentRotation = m_edited.environment->rotation();
    }
    for (const Medium& m : m_edited.media) {
        MediumUi u;
        u.sigmaS[0] = m.sigmaS.r, u.sigmaS[1] = m.sigmaS.g, u.sigmaS[2] = m.sigmaS.b;
        u.sigmaA[0] = m.sigmaA.r, u.sigmaA[1] = m.sigmaA.g, u.sigmaA[2] = m.sigmaA.b;
        u.g = m.g;
        u.emissionScale = m.emissionScale;
        u.emits = !m.sigmaA.isBlack() && (m.emissionField || !m.emission.isBlack());
        u.heterogeneous = !m.homogeneous();
        m_mediumUi.push_back(u);
    }
    m_selectedLight = std::clamp(m_selectedLight, 0, std::max(int(m_edited.lights.size()) - 1, 0));
}

void Viewer::startLoops() {
    m_loops.push_back(std::make_unique<RenderLoop>(m_o.scene, m_settings, m_o.gpu, m_o.preview));
    if (m_o.compare) m_loops.push_back(std::make_unique<RenderLoop>(m_o.twin, m_settings, m_o.gpu, m_o.preview));
    m_frames.assign(m_loops.size(), ViewFrame{});
    for (auto& loop : m_loops)
        if (!loop->notice().empty()) std::fprintf(stderr, "tyndall: %s\n", loop->notice().c_str());
    m_edited.camera = m_camera.camera();
    for (size_t i = 0; i < m_loops.size(); ++i) {
        m_loops[i]->onPublish([] { glfwPostEmptyEvent(); });  // wakes the UI thread's event wait
        m_loops[i]->start(loopEdits(i));
    }
}

/// Loads the scene file at `path` and, if it loads, stops the render loops and puts its scene and
/// cameras in place of the current ones; if not, says `failure` and the loader's error and keeps
/// the current scene. The caller rebuilds what depends on the scene and starts the loops again.
bool Viewer::replaceScene(const std::string& path, const char* failure) {
    std::vector<std::string> names;
    std::vector<Camera> cameras;
    Scene scene;
    try {
        scene = m_o.load(path, &names, &cameras);
    } catch (const std::exception& e) {
        m_status = std::string(failure) + e.what();
        std::fprintf(stderr, "tyndall view: %s\n", m_status.c_str());
        return false;
    }
    for (auto& loop : m_loops) loop->stop();
    m_loops.clear();
    m_pendingChanges.clear();
    m_dragButton = -1;
    m_o.scene = std::move(scene);
    m_o.cameraNames = std::move(names);
    m_o.cameras = std::move(cameras);
    return true;
}

/// The scene file again, with the camera kept and the lights and media as the file now says; a file
/// that does not load leaves the last good scene rendering and says why.
void Viewer::reloadScene() {
    ++m_reloads;
    inputArrived();
    if (!m_o.load || m_o.scenePath.empty()) {
        m_status = "reload: only a scene file reloads (not a built-in scene, nor with --compare)";
        return;
    }
    if (!replaceScene(m_o.scenePath, "reload failed, the last good scene stays: ")) return;
    m_edited = m_o.scene;
    initEditUi();
    m_cameraIndex = std::min(m_cameraIndex, std::max(int(m_o.cameras.size()) - 1, 0));
    m_picker = std::make_unique<EmbreeScene>(m_o.scene);
    startLoops();
    m_status = "reloaded " + m_o.scenePath;
    std::printf("tyndall view: reloaded %s\n", m_o.scenePath.c_str());
    std::fflush(stdout);
}

void Viewer::pollSceneFile() {
    double t = seconds(Clock::now());
    if (m_o.scenePath.empty() || t < m_nextPoll) return;
    m_nextPoll = t + kScenePollSeconds;
    std::error_code ec;
    auto time = std::filesystem::last_write_time(m_o.scenePath, ec);
    if (ec || time == m_sceneTime) return;  // a file being replaced may be missing for a moment
    m_sceneTime = time;
    reloadScene();
}

void Viewer::pushEdits() {
    m_edited.camera = m_camera.camera();
    for (size_t i = 0; i < m_edited.lights.size(); ++i) {
        const LightUi& u = m_lightUi[i];
        m_edited.lights[i].intensity = Rgb(u.colour[0] * u.power, u.colour[1] * u.power, u.colour[2] * u.power);
    }
    for (size_t i = 0; i < m_edited.media.size(); ++i) {
        const MediumUi& u = m_mediumUi[i];
        Medium& m = m_edited.media[i];
        m.sigmaS = Rgb(u.sigmaS[0], u.sigmaS[1], u.sigmaS[2]) * u.densityScale;
        m.sigmaA = Rgb(u.sigmaA[0], u.sigmaA[1], u.sigmaA[2]) * u.densityScale;
        m.g = u.g;
        m.emissionScale = u.emissionScale;
    }
    if (m_edited.environment) {
        m_edited.environment->setScale(m_environmentScale);
        m_edited.environment->setRotation(m_environmentRotation);
    }
    m_pendingChanges.push_back({m_loops[0]->control().version() + 1, seconds(Clock::now()), m_dragButton < 0});
    for (size_t i = 0; i < m_loops.size(); ++i) m_loops[i]->setEdits(loopEdits(i));
}

nlohmann::json Viewer::loopEdits(size_t loop) const {
    // The compare view's twin has its own media; the emission scales are shared (twinSceneEdits).
    return loop == 0 ? sceneEdits(m_edited) : twinSceneEdits(m_edited, m_o.twin);
}

void Viewer::setRegion(const PixelRegion& region) {
    m_settings.region = region;
    m_regionArmed = false;
    pushSettings();
    inputArrived();
    m_status = region.whole() ? "region cleared: the whole image refines"
                              : "region " + std::to_string(region.x) + " " + std::to_string(region.y) + " " +
                                    std::to_string(region.width) + " " + std::to_string(region.height) +
                                    ": only it refines";
}

void Viewer::setTransparent(bool on) {
    if (m_settings.transparentFilm == on) return;
    m_settings.transparentFilm = on;
    pushSettings();
    inputArrived();
    m_status = on ? "transparent film: the background left out, alpha saved" : "opaque film";
}

const Image& Viewer::displayImage(size_t i) {
    const Image& image = regionImage(i);
    const ViewFrame& f = m_frames[i];
    if (!f.settings.region.whole() || f.alpha.width != image.width || f.alpha.height != image.height) return image;
    m_checkered = Image(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const float grey = ((x / 16 + y / 16) & 1) ? 0.36f : 0.18f;
            m_checkered.at(x, y) = image.at(x, y) + Rgb(grey * std::max(0.0f, 1.0f - f.alpha.at(x, y).r));
        }
    return m_checkered;
}

const Image& Viewer::regionImage(size_t i) {
    const ViewFrame& f = m_frames[i];
    m_backdrops.resize(m_frames.size());
    const PixelRegion& region = f.settings.region;
    if (region.whole()) {
        m_backdrops[i] = f.mean;  // a preview's smaller image too: stretched under a region
        return f.mean;
    }
    // Outside the region: the last whole image (a preview after a drag), black before there is one.
    const Image& back = m_backdrops[i];
    m_composite = Image(f.mean.width, f.mean.height);
    for (int y = 0; y < f.mean.height; ++y)
        for (int x = 0; x < f.mean.width; ++x) {
            if (region.contains(x, y)) m_composite.at(x, y) = f.mean.at(x, y);
            else if (back.width > 0)
                m_composite.at(x, y) = back.at(x * back.width / f.mean.width, y * back.height / f.mean.height);
        }
    return m_composite;
}

void Viewer::pushSettings() {
    for (auto& loop : m_loops) loop->setSettings(m_settings);
}

void Viewer::resetControllerTo(const Camera& camera) {
    // Orbit about what the camera looks at (the surface at the centre of the view), else about its
    // focus distance; the lens keeps the focus the scene gave it.
    float pivot = camera.focusDistance > 0 ? camera.focusDistance : 0.5f * length(m_o.scene.bounds.diagonal());
    SurfaceHit hit;
    Ray centre{camera.position, camera.forward, 0.0f, kInfinity};
    if (m_picker && m_picker->intersect(centre, &hit)) pivot = hit.t;
    m_camera = CameraController(camera, pivot);
    m_camera.setViewport(m_o.settings.width, m_o.settings.height);
}

std::string Viewer::save(const std::string& stem) {
    if (m_frames[0].serial == 0) {
        m_status = "save: nothing rendered yet";
        return "";
    }
    SavedView v = saveView(m_frames[0], stem, m_o.base, m_o.baseCamera, m_o.scene.name, m_exposure);
    if (m_o.compare && m_frames.size() > 1 && m_frames[1].serial > 0) {
        // The twin is made from the base in code (no view file can name it): its image only.
        writeImage(stem + "-homogeneous.exr", m_frames[1].mean);
        writeImage(stem + "-homogeneous.png", m_frames[1].mean, {}, m_exposure);
    }
    m_status = "saved " + v.exr + ", " + v.png + ", " + v.json;
    std::printf("tyndall view: saved %s (%llu passes, %s), %s, %s\n", v.exr.c_str(),
                (unsigned long long)m_frames[0].passes, m_frames[0].mode == RenderMode::Refine ? "refined" : "preview",
                v.png.c_str(), v.json.c_str());
    std::fflush(stdout);
    return v.json;
}

}  // namespace tyndall
