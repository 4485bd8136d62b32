#include "viewer/viewer_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>

#include "core/error.h"
#include "core/image_io.h"
#include "cpu/embree_scene.h"
#include "loading/scene_edits.h"
#include "viewer/camera_controller.h"
#include "viewer/image_view_gl.h"
#include "viewer/view_save.h"
#include "viewer/view_script.h"

namespace tyndall {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

constexpr int kPanelWidth = 330;
constexpr double kFrameSeconds = 1.0 / 60.0;  // the most frames a second the window draws
// Frames drawn after an input event whatever else happens, so the panel's hover, press and release
// states settle (Dear ImGui updates them one frame late).
constexpr int kSettleFrames = 3;
// With nothing new the UI thread sleeps in the event queue; it wakes this often only to check
// script time-outs and render errors, and draws nothing unless something changed.
constexpr double kIdleWakeSeconds = 0.5;
constexpr double kScenePollSeconds = 0.5;  // how often the scene file's modification time is read
constexpr double kDoubleClickSeconds = 0.35;

const char* kBindings[][2] = {
    {"left drag", "orbit about the pivot"},
    {"right / middle drag", "pan"},
    {"wheel", "dolly toward / away from the pivot"},
    {"double-click", "set the pivot (and focus) on a surface"},
    {"ctrl/shift + left drag", "move the selected light (a spot aims at the cursor)"},
    {"F", "frame the scene"},
    {"1 - 9", "pick a camera"},
    {"+ / -", "exposure up / down"},
    {"Space", "pause / resume"},
    {"R", "restart the refinement"},
    {"F5", "reload the scene file (also done when it changes on disk)"},
    {"S", "save EXR + PNG + scene .json"},
    {"H", "help overlay"},
    {"Escape", "quit"},
};

/// Per light: colour (max channel 1) and power (the max channel), edited apart.
struct LightUi {
    float colour[3] = {1, 1, 1};
    float power = 1;
};
/// Per medium: the coefficients at density scale 1, and the scale.
struct MediumUi {
    float sigmaS[3] = {0, 0, 0};
    float sigmaA[3] = {0, 0, 0};
    float g = 0;
    float densityScale = 1;
    bool heterogeneous = false;
};

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}

class Viewer {
public:
    explicit Viewer(ViewerOptions& o) : m_o(o) {}
    int run();

private:
    // Input, from GLFW callbacks and from the script; coordinates in image pixels.
    void press(int button, float x, float y, int mods);
    void move(float x, float y);
    void release(int button, float x, float y);
    void doubleClick(float x, float y);
    void scroll(float x, float y, float steps);
    void key(const std::string& name);
    bool imageArea(double wx, double wy, float* x, float* y) const;

    void initEditUi();
    void startLoops();
    void reloadScene();
    void pollSceneFile();
    void pushEdits();
    void pushSettings();
    void resetControllerTo(const Camera& camera);
    void save(const std::string& stem);
    void screenshot(const std::string& path);
    void drawPanel();
    void drawHelp();
    bool stepScript(bool* acted);
    void inputArrived() { m_redraw = std::max(m_redraw, kSettleFrames); }
    bool refinedAtRest(uint64_t passes) const;
    void writeStats();

    static Viewer* self(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

    ViewerOptions& m_o;
    GLFWwindow* m_window = nullptr;
    std::unique_ptr<ImageViewGl> m_view;
    std::vector<std::unique_ptr<RenderLoop>> m_loops;
    std::vector<ViewFrame> m_frames;
    std::unique_ptr<EmbreeScene> m_picker;
    CameraController m_camera;
    Scene m_edited;  // lights and media as edited (camera: m_camera)
    std::vector<LightUi> m_lightUi;
    std::vector<MediumUi> m_mediumUi;
    float m_environmentScale = 1, m_environmentRotation = 0;  // the environment's sliders
    RenderSettings m_settings;
    int m_selectedLight = 0;
    int m_cameraIndex = 0;
    float m_exposure = 1;
    bool m_help = false;
    bool m_quit = false;
    int m_saves = 0;
    std::string m_status;
    int m_redraw = kSettleFrames;  // frames to draw whether or not a new image arrives
    uint64_t m_reloads = 0;        // reloads tried (a bad file counts: wait-reload)
    std::filesystem::file_time_type m_sceneTime{};
    double m_nextPoll = 0;

    int m_dragButton = -1, m_dragMods = 0;
    float m_lastX = 0, m_lastY = 0;
    double m_lastPressTime = -1;
    float m_lastPressX = -1e9, m_lastPressY = -1e9;

    // Script.
    std::vector<ScriptEvent> m_script;
    size_t m_scriptNext = 0;
    double m_waitUntil = 0;
    uint64_t m_waitFrames = 0;
    double m_waitPassesSince = 0;
    uint64_t m_windowReleases = 0;  // mouse-button releases from the window system (wait-input)

    // Statistics for --stats and the HUD.
    std::vector<double> m_frameSeconds;
    uint64_t m_imagesShown = 0;  // published images of the first loop taken and drawn
    // Input change -> first image of the new view: during a drag (a preview image) and on release
    // or at rest (the first refined pass).
    std::vector<double> m_latencies, m_refineLatencies;
    struct PendingChange {
        uint64_t version;
        double time;
        bool refine;
    };
    std::deque<PendingChange> m_pendingChanges;
    uint64_t m_previewImages = 0;
    std::vector<double> m_previewSetup, m_previewJob;  // per preview image: job setup, setup + passes
    double m_refinePassRate = 0, m_previewPassRate = 0;  // passes/s of the newest job of each mode
    double m_previewSeconds = 0;
    double m_previewSince = -1;
};

bool Viewer::imageArea(double wx, double wy, float* x, float* y) const {
    int gap = m_o.compare ? 4 : 0;
    float px = float(wx) - kPanelWidth, py = float(wy);
    if (m_o.compare && px >= m_o.settings.width + gap) px -= float(m_o.settings.width + gap);
    *x = px, *y = py;
    return px >= 0 && py >= 0 && px < m_o.settings.width && py < m_o.settings.height && wx >= kPanelWidth;
}

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
    nlohmann::json edits = sceneEdits(m_edited);
    if (m_o.compare) edits.erase("media");
    for (auto& loop : m_loops) {
        loop->onPublish([] { glfwPostEmptyEvent(); });  // wakes the UI thread's event wait
        loop->start(edits);
    }
}

/// The scene file again, with the camera kept and the lights and media as the file now says; a file
/// that does not load leaves the last good scene rendering and says why.
void Viewer::reloadScene() {
    ++m_reloads;
    inputArrived();
    if (!m_o.reload) {
        m_status = "reload: only a scene file reloads (not a built-in scene, nor with --compare)";
        return;
    }
    std::vector<std::string> names;
    std::vector<Camera> cameras;
    Scene scene;
    try {
        scene = m_o.reload(&names, &cameras);
    } catch (const std::exception& e) {
        m_status = std::string("reload failed, the last good scene stays: ") + e.what();
        std::fprintf(stderr, "tyndall view: %s\n", m_status.c_str());
        return;
    }
    for (auto& loop : m_loops) loop->stop();
    m_loops.clear();
    m_pendingChanges.clear();
    m_dragButton = -1;
    m_o.scene = std::move(scene);
    m_o.cameraNames = std::move(names);
    m_o.cameras = std::move(cameras);
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
    }
    if (m_edited.environment) {
        m_edited.environment->setScale(m_environmentScale);
        m_edited.environment->setRotation(m_environmentRotation);
    }
    nlohmann::json edits = sceneEdits(m_edited);
    if (m_o.compare) edits.erase("media");  // the twin's media differ: only camera and lights are shared
    m_pendingChanges.push_back({m_loops[0]->control().version() + 1, seconds(Clock::now()), m_dragButton < 0});
    for (auto& loop : m_loops) loop->setEdits(edits);
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

void Viewer::press(int button, float x, float y, int mods) {
    double t = seconds(Clock::now());
    if (button == 0 && t - m_lastPressTime < kDoubleClickSeconds && std::abs(x - m_lastPressX) < 4 &&
        std::abs(y - m_lastPressY) < 4) {
        m_lastPressTime = -1;
        doubleClick(x, y);
        return;
    }
    m_lastPressTime = t, m_lastPressX = x, m_lastPressY = y;
    m_dragButton = button, m_dragMods = mods;
    m_lastX = x, m_lastY = y;
    for (auto& loop : m_loops) loop->beginInteraction();
}

void Viewer::move(float x, float y) {
    if (m_dragButton < 0) return;
    float dx = x - m_lastX, dy = y - m_lastY;
    m_lastX = x, m_lastY = y;
    if (dx == 0 && dy == 0) return;
    if (m_dragButton == 0 && (m_dragMods & (kModShift | kModCtrl)) && !m_edited.lights.empty()) {
        SurfaceHit hit;
        bool found = m_picker->intersect(m_camera.ray(x, y), &hit);
        dragLight(m_edited.lights[size_t(m_selectedLight)], m_camera, x, y, dx, dy, found ? &hit.p : nullptr);
    } else if (m_dragButton == 0) {
        m_camera.orbit(dx, dy);
    } else {
        m_camera.pan(dx, dy);
    }
    pushEdits();
}

void Viewer::release(int button, float x, float y) {
    if (m_dragButton != button) return;
    move(x, y);
    m_dragButton = -1;
    m_pendingChanges.push_back({m_loops[0]->control().version() + 1, seconds(Clock::now()), true});
    for (auto& loop : m_loops) loop->endInteraction();
}

void Viewer::doubleClick(float x, float y) {
    SurfaceHit hit;
    if (!m_picker->intersect(m_camera.ray(x, y), &hit)) {
        m_status = "double-click: no surface under the cursor";
        return;
    }
    m_camera.setPivot(hit.p);
    m_status = "pivot set";
    if (m_camera.camera().lensRadius > 0) pushEdits();  // the focus distance changed
}

void Viewer::scroll(float, float, float steps) {
    m_camera.dolly(steps);
    pushEdits();
}

void Viewer::key(const std::string& name) {
    if (name == "escape") {
        m_quit = true;
    } else if (name == "F") {
        m_camera.frame(m_o.scene.bounds);
        pushEdits();
    } else if (name.size() == 1 && name[0] >= '1' && name[0] <= '9') {
        size_t i = size_t(name[0] - '1');
        if (i < m_o.cameras.size()) {
            m_cameraIndex = int(i);
            resetControllerTo(m_o.cameras[i]);
            pushEdits();
        } else {
            m_status = "camera " + name + ": the scene has " + std::to_string(m_o.cameras.size());
        }
    } else if (name == "plus") {
        m_exposure *= 1.25f;
    } else if (name == "minus") {
        m_exposure /= 1.25f;
    } else if (name == "space") {
        bool paused = !m_loops[0]->paused();
        for (auto& loop : m_loops) loop->setPaused(paused);
    } else if (name == "R") {
        for (auto& loop : m_loops) loop->restart();
    } else if (name == "F5") {
        reloadScene();
    } else if (name == "S") {
        save(m_o.saveStem + "-" + std::to_string(++m_saves));
    } else if (name == "H") {
        m_help = !m_help;
    }
}

void Viewer::save(const std::string& stem) {
    if (m_frames[0].serial == 0) {
        m_status = "save: nothing rendered yet";
        return;
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
}

void Viewer::screenshot(const std::string& path) {
    int w, h;
    glfwGetFramebufferSize(m_window, &w, &h);
    std::string pixels = m_view->readPixels(w, h);
    if (!stbi_write_png(path.c_str(), w, h, 4, pixels.data(), w * 4))
        throw Error("screenshot: cannot write '" + path + "'");
    std::printf("tyndall view: screenshot %s\n", path.c_str());
    std::fflush(stdout);
}

bool Viewer::refinedAtRest(uint64_t passes) const {
    for (size_t i = 0; i < m_loops.size(); ++i) {
        const ViewFrame& f = m_frames[i];
        if (f.serial == 0 || f.mode != RenderMode::Refine || f.version != m_loops[i]->control().version() ||
            f.passes < passes || m_loops[i]->control().interacting())
            return false;
    }
    return true;
}

/// Runs script events until one waits; at most one input event per UI frame, so previews
/// interleave with a drag as they do by hand. Returns false when the script says quit; *acted
/// says whether it ran an event or counts a frame (the caller then draws one).
bool Viewer::stepScript(bool* acted) {
    double t = seconds(Clock::now());
    *acted = false;
    if (m_waitFrames > 0) {
        --m_waitFrames;
        *acted = true;
        return true;
    }
    if (t < m_waitUntil) return true;
    while (m_scriptNext < m_script.size()) {
        const ScriptEvent& e = m_script[m_scriptNext];
        switch (e.op) {
            case ScriptOp::Sleep:
                m_waitUntil = t + e.value / 1000.0;
                ++m_scriptNext;
                return true;
            case ScriptOp::WaitFrames:
                m_waitFrames = uint64_t(e.value);
                ++m_scriptNext;
                *acted = true;
                return true;
            case ScriptOp::WaitPasses:
                if (m_waitPassesSince == 0) m_waitPassesSince = t;
                if (!refinedAtRest(uint64_t(e.value))) {
                    if (t - m_waitPassesSince > e.timeout)
                        throw Error(m_o.script + ": line " + std::to_string(e.line) + ": wait-passes " +
                                    std::to_string(uint64_t(e.value)) + " timed out after " +
                                    std::to_string(e.timeout) + " s");
                    return true;
                }
                m_waitPassesSince = 0;
                ++m_scriptNext;
                continue;
            case ScriptOp::WaitInput:
            case ScriptOp::WaitReload:
                if (m_waitPassesSince == 0) m_waitPassesSince = t;
                if ((e.op == ScriptOp::WaitInput ? m_windowReleases : m_reloads) < uint64_t(e.value)) {
                    if (t - m_waitPassesSince > e.timeout)
                        throw Error(m_o.script + ": line " + std::to_string(e.line) +
                                    (e.op == ScriptOp::WaitInput ? ": wait-input" : ": wait-reload") + " timed out after " +
                                    std::to_string(e.timeout) + " s");
                    return true;
                }
                m_waitPassesSince = 0;
                ++m_scriptNext;
                continue;
            case ScriptOp::Press: press(e.button, e.x, e.y, e.modifiers); break;
            case ScriptOp::Move: move(e.x, e.y); break;
            case ScriptOp::Release: release(e.button, e.x, e.y); break;
            case ScriptOp::DoubleClick: doubleClick(e.x, e.y); break;
            case ScriptOp::Scroll: scroll(e.x, e.y, float(e.value)); break;
            case ScriptOp::Key: key(e.text); break;
            case ScriptOp::Exposure: m_exposure = float(e.value); break;
            case ScriptOp::Save: save(e.text); break;
            case ScriptOp::Screenshot: screenshot(e.text); break;
            case ScriptOp::Quit: ++m_scriptNext; return false;
        }
        ++m_scriptNext;
        *acted = true;
        return true;
    }
    return true;
}

void Viewer::drawHelp() {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f + kPanelWidth * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Keys and mouse (H closes)", &m_help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
    for (const auto& b : kBindings) ImGui::Text("%-24s %s", b[0], b[1]);
    ImGui::End();
}

void Viewer::drawPanel() {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(float(kPanelWidth), io.DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Tyndall", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-110.0f);  // room for the labels
    const ViewFrame& f = m_frames[0];
    bool paused = m_loops[0]->paused();
    ImGui::Text("%s", m_o.scene.name.c_str());
    ImGui::Text("%s", paused ? "paused" : f.mode == RenderMode::Preview ? "preview (drag)" : "refining");
    double rate = f.elapsedSeconds > 0 ? double(f.passes) / f.elapsedSeconds : 0;
    ImGui::Text("passes %llu   %.2f passes/s", (unsigned long long)f.passes, rate);
    ImGui::Text("elapsed %.1f s   photon paths %llu", f.elapsedSeconds, (unsigned long long)f.totals.photonPaths);
    float r = f.radii.beamRadiusOf(f.passes * f.settings.photonsPerPass);
    float depth = std::max(dot(m_camera.pivot() - m_camera.eye(), m_camera.forward()), 1e-6f);
    float pixel = m_camera.pixelSize(depth) * float(m_o.settings.height) / float(std::max(f.settings.height, 1));
    ImGui::Text("beam radius %.4g (%.2f px at the pivot)", r, pixel > 0 ? r / pixel : 0.0f);
    std::string gl = m_loops[0]->glDescription();
    ImGui::TextWrapped("splat: %s", gl.empty() ? "CPU" : ("GL, " + gl).c_str());
    if (m_o.compare) ImGui::TextWrapped("left: density grid, right: homogeneous twin");
    if (!m_status.empty()) ImGui::TextWrapped("%s", m_status.c_str());
    ImGui::Separator();
    ImGui::SliderFloat("exposure", &m_exposure, 0.01f, 100.0f, "%.3f", ImGuiSliderFlags_Logarithmic);
    int photons = int(m_settings.photonsPerPass);
    if (ImGui::SliderInt("photons/pass", &photons, 100, 200000, "%d", ImGuiSliderFlags_Logarithmic))
        m_settings.photonsPerPass = uint32_t(std::max(photons, 1));
    if (ImGui::IsItemDeactivatedAfterEdit()) pushSettings();
    float alpha = float(m_settings.alpha);
    if (ImGui::SliderFloat("alpha", &alpha, 0.05f, 0.95f, "%.2f")) m_settings.alpha = alpha;
    if (ImGui::IsItemDeactivatedAfterEdit()) pushSettings();
    if (ImGui::Button(paused ? "Resume" : "Pause")) key("space");
    ImGui::SameLine();
    if (ImGui::Button("Restart")) key("R");
    ImGui::SameLine();
    if (ImGui::Button("Save")) key("S");

    // A slider held is an interaction (preview passes); its release refines.
    auto interactive = [&](bool edited) {
        if (ImGui::IsItemActivated())
            for (auto& loop : m_loops) loop->beginInteraction();
        if (edited) pushEdits();
        if (ImGui::IsItemDeactivated()) {
            for (auto& loop : m_loops) loop->endInteraction();
        }
    };
    if (!m_edited.lights.empty() && ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t i = 0; i < m_edited.lights.size(); ++i) {
            ImGui::PushID(int(i));
            ImGui::RadioButton(m_edited.lights[i].name.c_str(), &m_selectedLight, int(i));
            ImGui::SameLine();
            interactive(ImGui::ColorEdit3("##colour", m_lightUi[i].colour, ImGuiColorEditFlags_NoInputs));
            interactive(ImGui::DragFloat("power", &m_lightUi[i].power, 0.01f * std::max(m_lightUi[i].power, 0.1f),
                                         0.0f, 1e9f, "%.3g"));
            ImGui::PopID();
        }
    }
    if (m_edited.environment && ImGui::CollapsingHeader("Environment", ImGuiTreeNodeFlags_DefaultOpen)) {
        interactive(ImGui::DragFloat("intensity", &m_environmentScale, 0.01f * std::max(m_environmentScale, 0.1f), 0.0f,
                                     1e9f, "%.3g"));
        interactive(ImGui::SliderFloat("rotation", &m_environmentRotation, -180.0f, 180.0f, "%.0f deg"));
    }
    if (!m_o.compare && !m_edited.media.empty() && ImGui::CollapsingHeader("Media", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t i = 0; i < m_edited.media.size(); ++i) {
            MediumUi& u = m_mediumUi[i];
            ImGui::PushID(1000 + int(i));
            ImGui::Text("%s%s", m_edited.media[i].name.c_str(), u.heterogeneous ? " (grid)" : "");
            if (!u.heterogeneous) {
                // A grid medium's extinction must stay grey (docs/scene-format.md): only scale and g.
                interactive(ImGui::DragFloat3("sigma_s", u.sigmaS, 0.001f, 0.0f, 1e4f, "%.4g"));
                interactive(ImGui::DragFloat3("sigma_a", u.sigmaA, 0.001f, 0.0f, 1e4f, "%.4g"));
            }
            interactive(ImGui::SliderFloat("g", &u.g, -0.95f, 0.95f, "%.2f"));
            interactive(ImGui::DragFloat("density scale", &u.densityScale, 0.01f, 0.001f, 1e3f, "%.3f"));
            ImGui::PopID();
        }
    }
    if (ImGui::CollapsingHeader("Cameras", ImGuiTreeNodeFlags_DefaultOpen)) {
        for (size_t i = 0; i < m_o.cameraNames.size(); ++i) {
            std::string label = std::to_string(i + 1) + "  " + m_o.cameraNames[i];
            if (ImGui::Selectable(label.c_str(), m_cameraIndex == int(i)) && i < 9)
                key(std::string(1, char('1' + i)));
        }
    }
    if (ImGui::CollapsingHeader("Keys and mouse")) {
        for (const auto& b : kBindings) ImGui::TextWrapped("%s: %s", b[0], b[1]);
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

void Viewer::writeStats() {
    if (m_o.statsPath.empty()) return;
    nlohmann::json j;
    j["frames"] = m_frameSeconds.size();
    j["images_shown"] = m_imagesShown;
    j["refine_passes"] = m_frames[0].mode == RenderMode::Refine ? m_frames[0].passes : 0;
    j["frame_ms_p50"] = 1000 * percentile(m_frameSeconds, 0.5);
    j["frame_ms_p95"] = 1000 * percentile(m_frameSeconds, 0.95);
    j["frame_ms_max"] = 1000 * percentile(m_frameSeconds, 1.0);
    j["preview_images"] = m_previewImages;
    j["preview_seconds"] = m_previewSeconds;
    j["preview_images_per_s"] = m_previewSeconds > 0 ? double(m_previewImages) / m_previewSeconds : 0.0;
    j["refine_passes_per_s"] = m_refinePassRate;
    j["preview_passes_per_s"] = m_previewPassRate;
    j["preview_setup_ms_p50"] = 1000 * percentile(m_previewSetup, 0.5);
    j["preview_job_ms_p50"] = 1000 * percentile(m_previewJob, 0.5);
    j["latency_ms_p50"] = 1000 * percentile(m_latencies, 0.5);
    j["latency_ms_p95"] = 1000 * percentile(m_latencies, 0.95);
    j["latency_events"] = m_latencies.size();
    j["refine_latency_ms"] = nlohmann::json::array();
    for (double l : m_refineLatencies) j["refine_latency_ms"].push_back(1000 * l);
    std::ofstream(m_o.statsPath) << j.dump(2) << "\n";
}

int Viewer::run() {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display)
        throw Error("view: no display (DISPLAY is not set): the viewer needs a window; use `tyndall render` to "
                    "render to a file");
    if (!m_o.script.empty()) m_script = loadViewScript(m_o.script);
    glfwSetErrorCallback([](int, const char*) {});
    if (!glfwInit())
        throw Error(std::string("view: cannot open display '") + display +
                    "' (GLFW could not initialize); use `tyndall render` to render to a file");
    struct GlfwGuard {
        ~GlfwGuard() { glfwTerminate(); }
    } glfwGuard;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    const int w = m_o.settings.width, h = m_o.settings.height, gap = m_o.compare ? 4 : 0;
    const int windowW = kPanelWidth + w + (m_o.compare ? gap + w : 0), windowH = std::max(h, 200);
    std::string title = "tyndall view - " + m_o.scene.name + (m_o.compare ? " (compare)" : "");
    m_window = glfwCreateWindow(windowW, windowH, title.c_str(), nullptr, nullptr);
    if (!m_window) {
        const char* why = nullptr;
        glfwGetError(&why);
        throw Error(std::string("view: no OpenGL 3.3 core context on display '") + display + "' (" +
                    (why ? why : "unknown reason") + "); use `tyndall render` to render to a file");
    }
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(0);  // paced below: a swap that does not block (Xvfb) must not spin a core
    m_view = std::make_unique<ImageViewGl>([](const char* name) { return (void*)glfwGetProcAddress(name); });

    // The scene as edited: everything the renderers read goes through applySceneEdits.
    m_edited = m_o.scene;
    m_settings = m_o.settings;
    m_exposure = m_o.exposure;
    initEditUi();
    m_picker = std::make_unique<EmbreeScene>(m_o.scene);
    for (size_t i = 0; i < m_o.cameras.size(); ++i)
        if (m_o.cameras[i].position.x == m_o.scene.camera.position.x &&
            m_o.cameras[i].position.y == m_o.scene.camera.position.y &&
            m_o.cameras[i].position.z == m_o.scene.camera.position.z)
            m_cameraIndex = int(i);
    resetControllerTo(m_o.scene.camera);
    startLoops();
    if (!m_o.scenePath.empty()) {
        std::error_code ec;
        m_sceneTime = std::filesystem::last_write_time(m_o.scenePath, ec);
    }

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    glfwSetWindowUserPointer(m_window, this);
    glfwSetMouseButtonCallback(m_window, [](GLFWwindow* win, int button, int action, int mods) {
        Viewer* v = self(win);
        v->inputArrived();
        if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse && v->m_dragButton < 0) return;
        double cx, cy;
        glfwGetCursorPos(win, &cx, &cy);
        float x, y;
        bool inside = v->imageArea(cx, cy, &x, &y);
        int b = button == GLFW_MOUSE_BUTTON_LEFT ? 0 : button == GLFW_MOUSE_BUTTON_RIGHT ? 1 : 2;
        int m = (mods & GLFW_MOD_SHIFT ? kModShift : 0) | (mods & GLFW_MOD_CONTROL ? kModCtrl : 0) |
                (mods & GLFW_MOD_ALT ? kModAlt : 0);
        if (action == GLFW_PRESS && inside && v->m_dragButton < 0) v->press(b, x, y, m);
        if (action == GLFW_RELEASE) v->release(b, x, y), ++v->m_windowReleases;
    });
    glfwSetCursorPosCallback(m_window, [](GLFWwindow* win, double cx, double cy) {
        Viewer* v = self(win);
        v->inputArrived();
        float x, y;
        v->imageArea(cx, cy, &x, &y);
        v->move(x, y);
    });
    glfwSetScrollCallback(m_window, [](GLFWwindow* win, double, double dy) {
        Viewer* v = self(win);
        v->inputArrived();
        if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
        double cx, cy;
        glfwGetCursorPos(win, &cx, &cy);
        float x, y;
        if (v->imageArea(cx, cy, &x, &y)) v->scroll(x, y, float(dy));
    });
    glfwSetKeyCallback(m_window, [](GLFWwindow* win, int key, int, int action, int) {
        Viewer* v = self(win);
        v->inputArrived();
        if (action != GLFW_PRESS || (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard)) return;
        switch (key) {
            case GLFW_KEY_ESCAPE: v->key("escape"); break;
            case GLFW_KEY_F: v->key("F"); break;
            case GLFW_KEY_R: v->key("R"); break;
            case GLFW_KEY_S: v->key("S"); break;
            case GLFW_KEY_H: v->key("H"); break;
            case GLFW_KEY_F5: v->key("F5"); break;
            case GLFW_KEY_SPACE: v->key("space"); break;
            case GLFW_KEY_KP_ADD: v->key("plus"); break;
            case GLFW_KEY_KP_SUBTRACT: v->key("minus"); break;
            default:
                if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) v->key(std::string(1, char('1' + key - GLFW_KEY_1)));
        }
    });
    glfwSetCharCallback(m_window, [](GLFWwindow* win, unsigned c) {
        Viewer* v = self(win);
        v->inputArrived();
        if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
        if (c == '+') v->key("plus");
        if (c == '-') v->key("minus");
    });
    // Exposed, focused, entered: the window needs a frame too.
    glfwSetWindowRefreshCallback(m_window, [](GLFWwindow* win) { self(win)->inputArrived(); });
    glfwSetWindowFocusCallback(m_window, [](GLFWwindow* win, int) { self(win)->inputArrived(); });
    glfwSetCursorEnterCallback(m_window, [](GLFWwindow* win, int) { self(win)->inputArrived(); });
    // ImGui's backend chains to the callbacks installed above.
    ImGui_ImplGlfw_InitForOpenGL(m_window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    int exitCode = 0;
    try {
        while (!m_quit && !glfwWindowShouldClose(m_window)) {
            // Sleep in the event queue until input, a published pass (glfwPostEmptyEvent from the
            // render thread) or the script's next time; draw only when something is new.
            if (m_redraw > 0) {
                glfwPollEvents();
            } else {
                double wait = kIdleWakeSeconds;
                if (m_scriptNext < m_script.size() && m_waitUntil > 0)
                    wait = std::clamp(m_waitUntil - seconds(Clock::now()), 1e-3, wait);
                glfwWaitEventsTimeout(wait);
            }
            auto frameStart = Clock::now();
            pollSceneFile();
            bool draw = m_redraw > 0;
            bool acted = false;
            if (!m_script.empty() && !stepScript(&acted)) m_quit = true;
            if (acted) draw = true, m_redraw = std::max(m_redraw, 1);
            for (size_t i = 0; i < m_loops.size(); ++i) {
                std::string err = m_loops[i]->error();
                if (!err.empty()) throw Error("view: rendering failed: " + err);
                if (m_loops[i]->latest(&m_frames[i])) {
                    m_view->upload(int(i), m_frames[i].mean);
                    draw = true;
                    if (i == 0) {
                        ++m_imagesShown;
                        double t = seconds(Clock::now());
                        while (!m_pendingChanges.empty() && m_pendingChanges.front().version <= m_frames[0].version) {
                            const PendingChange& c = m_pendingChanges.front();
                            (c.refine ? m_refineLatencies : m_latencies).push_back(t - c.time);
                            // Changes superseded before their own image arrived count from this image too.
                            m_pendingChanges.pop_front();
                        }
                        const ViewFrame& f = m_frames[0];
                        double rate = f.elapsedSeconds > 0 ? double(f.passes) / f.elapsedSeconds : 0;
                        if (f.mode == RenderMode::Preview) ++m_previewImages, m_previewSetup.push_back(f.setupSeconds),
                                                           m_previewJob.push_back(f.elapsedSeconds);
                        // A job's first pass also carries its setup; rates from the second on.
                        if (f.passes >= 2) (f.mode == RenderMode::Preview ? m_previewPassRate : m_refinePassRate) = rate;
                    }
                }
            }
            bool previewing = m_loops[0]->control().interacting();
            double tNow = seconds(Clock::now());
            if (previewing && m_previewSince < 0) m_previewSince = tNow;
            if (!previewing && m_previewSince >= 0) m_previewSeconds += tNow - m_previewSince, m_previewSince = -1;
            if (!draw || m_quit) continue;
            if (m_redraw > 0) --m_redraw;

            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            drawPanel();
            if (m_help) drawHelp();
            ImGui::Render();

            int fbW, fbH;
            glfwGetFramebufferSize(m_window, &fbW, &fbH);
            float sx = float(fbW) / float(windowW), sy = float(fbH) / float(windowH);
            m_view->clear(fbW, fbH);
            for (size_t i = 0; i < m_loops.size(); ++i) {
                int x0 = kPanelWidth + int(i) * (w + gap);
                m_view->draw(int(i), int(x0 * sx), int((windowH - h) * sy), int(w * sx), int(h * sy), m_exposure);
            }
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            glfwSwapBuffers(m_window);
            m_frameSeconds.push_back(std::chrono::duration<double>(Clock::now() - frameStart).count());
            // At most 60 frames a second, however fast passes arrive (a swap that does not block,
            // as on Xvfb, must not spin a core).
            std::this_thread::sleep_until(
                frameStart + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kFrameSeconds)));
        }
    } catch (...) {
        for (auto& loop : m_loops) loop->stop();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
        m_view.reset();
        glfwDestroyWindow(m_window);
        throw;
    }
    if (m_previewSince >= 0) m_previewSeconds += seconds(Clock::now()) - m_previewSince;
    for (auto& loop : m_loops) loop->stop();
    writeStats();
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    m_view.reset();
    glfwDestroyWindow(m_window);
    return exitCode;
}
}  // namespace

int runViewer(ViewerOptions& options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace tyndall
