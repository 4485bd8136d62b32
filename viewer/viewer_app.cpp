// `tyndall view`: the window's life (open, frame loop, close), its screenshot and its statistics.
#include "viewer/viewer_window.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <stb/stb_image_write.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "core/error.h"

namespace tyndall {

namespace {
double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
}
}  // namespace

void Viewer::screenshot(const std::string& path) {
    int w, h;
    glfwGetFramebufferSize(m_window, &w, &h);
    std::string pixels = m_view->readPixels(w, h);
    if (!stbi_write_png(path.c_str(), w, h, 4, pixels.data(), w * 4))
        throw Error("screenshot: cannot write '" + path + "'");
    std::printf("tyndall view: screenshot %s\n", path.c_str());
    std::fflush(stdout);
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

void Viewer::openWindow() {
    const char* display = std::getenv("DISPLAY");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    // The panel's scale before the window exists: the primary monitor's content scale.
    float sx = 1, sy = 1;
    if (GLFWmonitor* monitor = glfwGetPrimaryMonitor()) glfwGetMonitorContentScale(monitor, &sx, &sy);
    m_uiScale = m_o.uiScale > 0 ? m_o.uiScale : std::clamp(sx, 0.5f, 4.0f);
    std::string title = "tyndall view - " + m_o.scene.name + (m_o.compare ? " (compare)" : "");
    m_window = glfwCreateWindow(windowWidth(), windowHeight(), title.c_str(), nullptr, nullptr);
    if (!m_window) {
        const char* why = nullptr;
        glfwGetError(&why);
        throw Error(std::string("view: no OpenGL 3.3 core context on display '") + display + "' (" +
                    (why ? why : "unknown reason") + "); use `tyndall render` to render to a file");
    }
    glfwMakeContextCurrent(m_window);
    glfwSwapInterval(0);  // paced in run(): a swap that does not block (Xvfb) must not spin a core
    m_view = std::make_unique<ImageViewGl>([](const char* name) { return (void*)glfwGetProcAddress(name); });
}

void Viewer::startScene() {
    // The scene as edited: everything the renderers read goes through applySceneEdits.
    m_edited = m_o.scene;
    m_settings = m_o.settings;
    m_exposure = m_o.exposure;
    m_finalPasses = int(std::min<uint64_t>(m_o.finalPasses, 1u << 30));
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
}

void Viewer::waitForEvents() {
    // Sleep in the event queue until input, a published pass (glfwPostEmptyEvent from the render
    // thread) or the script's next time.
    if (m_redraw > 0) {
        glfwPollEvents();
        return;
    }
    double wait = kIdleWakeSeconds;
    if (m_scriptNext < m_script.size() && m_waitUntil > 0)
        wait = std::clamp(m_waitUntil - seconds(Clock::now()), 1e-3, wait);
    if (m_resizeAt > 0) wait = std::clamp(m_resizeAt - seconds(Clock::now()), 1e-3, wait);
    glfwWaitEventsTimeout(wait);
}

bool Viewer::takeImages() {
    bool arrived = false;
    for (size_t i = 0; i < m_loops.size(); ++i) {
        std::string err = m_loops[i]->error();
        if (!err.empty()) throw Error("view: rendering failed: " + err);
        if (!m_loops[i]->latest(&m_frames[i])) continue;
        m_view->upload(int(i), displayImage(i));
        arrived = true;
        if (i == 0) countImage();
    }
    return arrived;
}

void Viewer::countImage() {
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
    if (f.mode == RenderMode::Preview)
        ++m_previewImages, m_previewSetup.push_back(f.setupSeconds), m_previewJob.push_back(f.elapsedSeconds);
    // A job's first pass also carries its setup; rates from the second on.
    if (f.passes >= 2) (f.mode == RenderMode::Preview ? m_previewPassRate : m_refinePassRate) = rate;
}

void Viewer::notePreviewTime() {
    bool previewing = m_loops[0]->control().interacting();
    double t = seconds(Clock::now());
    if (previewing && m_previewSince < 0) m_previewSince = t;
    if (!previewing && m_previewSince >= 0) m_previewSeconds += t - m_previewSince, m_previewSince = -1;
}

void Viewer::drawFrame(Clock::time_point frameStart) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    drawPanel();
    drawRegionOutline();
    if (m_help) drawHelp();
    ImGui::Render();

    const int w = m_o.settings.width, h = m_o.settings.height, gap = m_o.compare ? 4 : 0;
    int fbW, fbH, winW, winH;
    glfwGetFramebufferSize(m_window, &fbW, &fbH);
    glfwGetWindowSize(m_window, &winW, &winH);
    float sx = float(fbW) / float(std::max(winW, 1)), sy = float(fbH) / float(std::max(winH, 1));
    m_view->clear(fbW, fbH);
    for (size_t i = 0; i < m_loops.size(); ++i) {
        // Image pixel (x, y) at window (panel + x, y): the top-left, until a resize re-renders.
        int x0 = panelWidth() + int(i) * (w + gap);
        m_view->draw(int(i), int(x0 * sx), int((winH - h) * sy), int(w * sx), int(h * sy), m_exposure);
    }
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    glfwSwapBuffers(m_window);
    m_frameSeconds.push_back(std::chrono::duration<double>(Clock::now() - frameStart).count());
    // At most 60 frames a second, however fast passes arrive (a swap that does not block, as on
    // Xvfb, must not spin a core).
    std::this_thread::sleep_until(
        frameStart + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(kFrameSeconds)));
}

void Viewer::closeWindow() {
    m_final.stop();  // a final render still running writes the passes it has (SIGTERM)
    for (auto& loop : m_loops) loop->stop();
    if (ImGui::GetCurrentContext()) {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    m_view.reset();
    if (m_window) glfwDestroyWindow(m_window);
    m_window = nullptr;
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
    try {
        openWindow();
        startScene();
        installCallbacks();
        while (!m_quit && !glfwWindowShouldClose(m_window)) {
            waitForEvents();
            auto frameStart = Clock::now();
            pollSceneFile();
            pollFinalRender();
            applyResize();
            bool draw = m_redraw > 0;
            bool acted = false;
            if (!m_script.empty() && !stepScript(&acted)) m_quit = true;
            if (acted) draw = true, m_redraw = std::max(m_redraw, 1);
            if (takeImages()) draw = true;
            notePreviewTime();
            if (!draw || m_quit) continue;
            if (m_redraw > 0) --m_redraw;
            drawFrame(frameStart);
        }
    } catch (...) {
        closeWindow();
        throw;
    }
    if (m_previewSince >= 0) m_previewSeconds += seconds(Clock::now()) - m_previewSince;
    for (auto& loop : m_loops) loop->stop();
    writeStats();
    closeWindow();
    return 0;
}

int runViewer(ViewerOptions& options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace tyndall
