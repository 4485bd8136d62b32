#pragma once
// The viewer window behind runViewer (viewer/viewer_app.h), private to viewer/: one class whose
// parts live in viewer_app.cpp (the window's life and its frame loop), viewer_input.cpp (mouse,
// keys and the script), viewer_scene.cpp (the edited scene, its render loops, reload and save)
// and viewer_panel.cpp (the Dear ImGui panel). Everything runs on the UI thread.
#ifndef GLFW_INCLUDE_NONE
#define GLFW_INCLUDE_NONE
#endif
#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cpu/embree_scene.h"
#include "viewer/camera_controller.h"
#include "viewer/final_render.h"
#include "viewer/image_view_gl.h"
#include "viewer/view_script.h"
#include "viewer/viewer_app.h"

namespace tyndall {

using Clock = std::chrono::steady_clock;
inline double seconds(Clock::time_point t) { return std::chrono::duration<double>(t.time_since_epoch()).count(); }

constexpr int kPanelWidth = 330;  // at a content scale of 1 (panelWidth())
constexpr double kResizeSettleSeconds = 0.25;  // a window resize re-renders once it stops this long
constexpr double kFrameSeconds = 1.0 / 60.0;  // the most frames a second the window draws
// Frames drawn after an input event whatever else happens, so the panel's hover, press and release
// states settle (Dear ImGui updates them one frame late).
constexpr int kSettleFrames = 3;
// With nothing new the UI thread sleeps in the event queue; it wakes this often only to check
// script time-outs and render errors, and draws nothing unless something changed.
constexpr double kIdleWakeSeconds = 0.5;
constexpr double kScenePollSeconds = 0.5;  // how often the scene file's modification time is read
constexpr double kDoubleClickSeconds = 0.35;

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
    float emissionScale = 1;  ///< Medium::emissionScale
    bool emits = false;       ///< the medium has an emission to scale
    bool heterogeneous = false;
};

class Viewer {
public:
    explicit Viewer(ViewerOptions& o) : m_o(o) {}
    /// Opens the window, runs until quit, closes it (runViewer).
    int run();

private:
    // The steps of run(), in order (viewer_app.cpp).
    void openWindow();          ///< GLFW's window and GL context (Error without a display or GL 3.3)
    void startScene();          ///< the edited scene, the camera controller, the render loops
    void installCallbacks();    ///< GLFW input callbacks and Dear ImGui (viewer_input.cpp)
    void waitForEvents();       ///< sleeps in the event queue unless a frame is due
    bool takeImages();          ///< uploads the loops' new images; true when one arrived
    void countImage();          ///< the statistics of a new image of the first loop
    void notePreviewTime();
    void drawFrame(std::chrono::steady_clock::time_point frameStart);
    void closeWindow();         ///< stops the loops, frees ImGui and the window (safe at any step)
    /// The window's size in screen coordinates for the image size: the panel, the image (twice
    /// with compare); at least 200 high.
    int windowWidth() const { return panelWidth() + m_o.settings.width * (m_o.compare ? 2 : 1) + (m_o.compare ? 4 : 0); }
    int windowHeight() const { return std::max(m_o.settings.height, 200); }
    /// The panel's width at the UI scale.
    int panelWidth() const { return int(std::lround(kPanelWidth * m_uiScale)); }
    /// The UI scale from the window's content scale (--ui-scale overrides it): the panel's sizes
    /// and font (viewer_resize.cpp).
    void updateUiScale();
    /// After the window's size settled: the image follows it (the render loops restart at the
    /// size the window leaves right of the panel).
    void applyResize();
    /// Restarts the render loops at `width` x `height` (a region that no longer fits is cleared).
    void resizeImage(int width, int height);
    /// A file dropped on the window (or a script's `drop`): opens it as the scene.
    void openDropped(const std::string& path);

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
    bool replaceScene(const std::string& path, const char* failure);
    void pollSceneFile();
    void pushEdits();
    /// The edits render loop `loop` applies: the edited scene's (0), the compare twin's (1).
    nlohmann::json loopEdits(size_t loop) const;
    void pushSettings();
    void resetControllerTo(const Camera& camera);
    /// Writes STEM.{exr,png,json}; returns the view file's path ("" when nothing was saved).
    std::string save(const std::string& stem);
    /// F12: saves the view and starts `tyndall render` of it (viewer_final.cpp).
    void startFinalRender();
    /// Reaps a finished final render and keeps the panel's line current.
    void pollFinalRender();
    void screenshot(const std::string& path);
    /// The panel (viewer_panel.cpp): its sections top to bottom, one function each.
    void drawPanel();
    void drawPanelStatus(bool paused);          ///< scene, mode, passes, beam radius, splat, status
    void drawPanelRenderControls(bool paused);  ///< exposure, photons/pass, alpha, buttons, final render
    void drawPanelRegion();                     ///< the render region's button and extent
    void drawPanelFilm();                       ///< the transparent film's checkbox
    void drawPanelLights();
    void drawPanelEnvironment();
    void drawPanelMedia();
    void drawPanelCameras();
    /// After a scene-editing widget: its press starts an interaction (preview passes), an edit
    /// pushes the edits, its release ends the interaction (refinement).
    void panelEdit(bool edited);
    void drawHelp();
    /// The render region (RenderSettings::region): set (a new refinement of those pixels only) or
    /// cleared (PixelRegion{}); the status line says which.
    void setRegion(const PixelRegion& region);
    /// The transparent film (RenderSettings::transparentFilm) on or off: a new refinement, shown
    /// over the checkerboard when on (displayImage); the status line says which.
    void setTransparent(bool on);
    /// The rectangle of the region drag under way, in image pixels, inside the image.
    PixelRegion dragRegion() const;
    /// The region's outline (and the one being drawn) over the image.
    void drawRegionOutline();
    /// What loop i's newest frame shows: a region frame over the last whole image (viewer_scene.cpp);
    /// a transparent film's whole frame over a checkerboard (16-pixel squares, linear grey 0.18 and
    /// 0.36, added where the coverage is below 1: the colour is premultiplied).
    const Image& displayImage(size_t i);
    const Image& regionImage(size_t i);
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
    float m_uiScale = 1;          // panel scale (content scale, or --ui-scale)
    double m_resizeAt = -1;       // when a pending window resize applies (-1: none)
    uint64_t m_resizes = 0;       // image sizes changed (wait-resize)
    FinalRender m_final;
    int m_finalPasses = 64;        // the panel's pass count for the final render
    std::string m_finalOutput;     // its image
    std::string m_finalLine;       // its last progress line, as last drawn
    uint64_t m_finalsEnded = 0;    // final renders ended (done or failed: wait-final)
    std::filesystem::file_time_type m_sceneTime{};
    double m_nextPoll = 0;

    int m_dragButton = -1, m_dragMods = 0;
    // The render region: an Alt + left drag draws one, as does a left drag after B or the panel's
    // button (armed); B or the button clears one.
    bool m_regionArmed = false;
    bool m_drawingRegion = false;
    float m_regionStartX = 0, m_regionStartY = 0;
    std::vector<Image> m_backdrops;  // per loop: the last whole image shown, under a region's frames
    Image m_composite;
    Image m_checkered;
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

}  // namespace tyndall
