// The viewer's window as it changes: its size (the image follows it), its content scale (the
// panel follows it) and files dropped on it (opened as the scene).
#include "viewer/viewer_window.h"

#include <imgui.h>

#include <cstdio>

namespace tyndall {

void Viewer::updateUiScale() {
    float scale = m_o.uiScale;
    if (!(scale > 0)) {
        float sx = 1, sy = 1;
        glfwGetWindowContentScale(m_window, &sx, &sy);
        // Where window coordinates are already scaled (macOS), ImGui scales by the framebuffer's
        // ratio itself: only the rest is ours.
        int winW, winH, fbW, fbH;
        glfwGetWindowSize(m_window, &winW, &winH);
        glfwGetFramebufferSize(m_window, &fbW, &fbH);
        scale = sx * float(std::max(winW, 1)) / float(std::max(fbW, 1));
    }
    m_uiScale = std::clamp(scale, 0.5f, 4.0f);
    inputArrived();
    if (!ImGui::GetCurrentContext()) return;
    ImGuiStyle& style = ImGui::GetStyle();
    style = ImGuiStyle();
    ImGui::StyleColorsDark();
    style.ScaleAllSizes(m_uiScale);
    ImGui::GetIO().FontGlobalScale = m_uiScale;
}

void Viewer::applyResize() {
    if (m_resizeAt < 0 || seconds(Clock::now()) < m_resizeAt) return;
    m_resizeAt = -1;
    int winW, winH;
    glfwGetWindowSize(m_window, &winW, &winH);
    if (winW <= 0 || winH <= 0) return;  // minimised
    const int gap = m_o.compare ? 4 : 0, halves = m_o.compare ? 2 : 1;
    const int w = std::max(16, (winW - panelWidth() - gap) / halves), h = std::max(16, winH);
    // The window as made for the image (at least 200 high) needs no new image.
    if (winW == windowWidth() && winH == windowHeight()) return;
    if (w != m_o.settings.width || h != m_o.settings.height) resizeImage(w, h);
}

void Viewer::resizeImage(int width, int height) {
    for (auto& loop : m_loops) loop->stop();
    m_loops.clear();
    m_pendingChanges.clear();
    m_o.settings.width = m_settings.width = width;
    m_o.settings.height = m_settings.height = height;
    if (!m_settings.region.fits(width, height)) m_settings.region = PixelRegion{};
    m_camera.setViewport(width, height);
    m_backdrops.clear();
    ++m_resizes;
    startLoops();
    m_status = "image " + std::to_string(width) + "x" + std::to_string(height);
    std::printf("tyndall view: image %dx%d\n", width, height);
    std::fflush(stdout);
}

void Viewer::openDropped(const std::string& path) {
    inputArrived();
    ++m_reloads;  // wait-reload counts opens too (a file that does not load as well)
    if (!m_o.load || m_o.compare) {
        m_status = "drop: --compare shows the scene it was opened with";
        return;
    }
    if (!replaceScene(path, "drop: not opened, the scene stays: ")) return;
    m_o.scenePath = m_o.base = path;
    m_o.baseCamera.clear();
    m_edited = m_o.scene;
    initEditUi();
    m_cameraIndex = 0;
    m_picker = std::make_unique<EmbreeScene>(m_o.scene);
    resetControllerTo(m_o.scene.camera);
    std::error_code ec;
    m_sceneTime = std::filesystem::last_write_time(path, ec);
    m_backdrops.clear();
    startLoops();
    m_status = "opened " + path;
    std::printf("tyndall view: opened %s\n", path.c_str());
    std::fflush(stdout);
}

}  // namespace tyndall
