// The viewer's input: GLFW's callbacks and the script turn into presses, drags, wheel steps and
// keys on the image (image pixels), which edit the camera and the lights.
#include "viewer/viewer_window.h"

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include <cmath>

#include "core/error.h"

namespace tyndall {

bool Viewer::imageArea(double wx, double wy, float* x, float* y) const {
    int gap = m_o.compare ? 4 : 0;
    float px = float(wx) - float(panelWidth()), py = float(wy);
    if (m_o.compare && px >= m_o.settings.width + gap) px -= float(m_o.settings.width + gap);
    *x = px, *y = py;
    return px >= 0 && py >= 0 && px < m_o.settings.width && py < m_o.settings.height && wx >= panelWidth();
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
    if (button == 0 && (m_regionArmed || (mods & kModAlt))) {
        // A region drag edits no scene: no preview passes.
        m_drawingRegion = true;
        m_regionArmed = false;
        m_regionStartX = x, m_regionStartY = y;
        return;
    }
    for (auto& loop : m_loops) loop->beginInteraction();
}

void Viewer::move(float x, float y) {
    if (m_dragButton < 0) return;
    float dx = x - m_lastX, dy = y - m_lastY;
    m_lastX = x, m_lastY = y;
    if (dx == 0 && dy == 0) return;
    if (m_drawingRegion) {
        inputArrived();  // the outline follows the cursor
        return;
    }
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
    if (m_drawingRegion) {
        m_drawingRegion = false;
        PixelRegion r = dragRegion();
        if (r.width >= 2 && r.height >= 2) setRegion(r);
        else m_status = "region: drag a rectangle of at least 2 x 2 pixels";
        return;
    }
    m_pendingChanges.push_back({m_loops[0]->control().version() + 1, seconds(Clock::now()), true});
    for (auto& loop : m_loops) loop->endInteraction();
}

PixelRegion Viewer::dragRegion() const {
    const int w = m_o.settings.width, h = m_o.settings.height;
    auto clampTo = [](float v, int n) { return std::clamp(int(std::floor(v)), 0, n); };
    int x0 = clampTo(std::min(m_regionStartX, m_lastX), w), x1 = clampTo(std::max(m_regionStartX, m_lastX) + 1, w);
    int y0 = clampTo(std::min(m_regionStartY, m_lastY), h), y1 = clampTo(std::max(m_regionStartY, m_lastY) + 1, h);
    return PixelRegion{x0, y0, x1 - x0, y1 - y0};
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
    } else if (name == "F12") {
        startFinalRender();
    } else if (name == "S") {
        save(m_o.saveStem + "-" + std::to_string(++m_saves));
    } else if (name == "H") {
        m_help = !m_help;
    } else if (name == "B") {
        if (!m_settings.region.whole()) {
            setRegion(PixelRegion{});
        } else {
            m_regionArmed = !m_regionArmed;
            m_status = m_regionArmed ? "region: drag a rectangle on the image" : "";
        }
    }
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
            case ScriptOp::WaitFinal:
            case ScriptOp::WaitResize:
                if (m_waitPassesSince == 0) m_waitPassesSince = t;
                if ((e.op == ScriptOp::WaitInput    ? m_windowReleases
                     : e.op == ScriptOp::WaitReload ? m_reloads
                     : e.op == ScriptOp::WaitFinal  ? m_finalsEnded
                                                    : m_resizes) < uint64_t(e.value)) {
                    if (t - m_waitPassesSince > e.timeout)
                        throw Error(m_o.script + ": line " + std::to_string(e.line) +
                                    (e.op == ScriptOp::WaitInput    ? ": wait-input"
                                     : e.op == ScriptOp::WaitReload ? ": wait-reload"
                                     : e.op == ScriptOp::WaitFinal  ? ": wait-final"
                                                                    : ": wait-resize") +
                                    " timed out after " + std::to_string(e.timeout) + " s");
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
            case ScriptOp::Drop: openDropped(e.text); break;
            case ScriptOp::Exposure: m_exposure = float(e.value); break;
            case ScriptOp::Emission:
                if (size_t(e.medium) >= m_mediumUi.size() || !m_mediumUi[size_t(e.medium)].emits)
                    throw Error(m_o.script + ": line " + std::to_string(e.line) + ": emission: medium " +
                                std::to_string(e.medium) + " is not a medium that emits (the scene has " +
                                std::to_string(m_mediumUi.size()) + " media)");
                m_mediumUi[size_t(e.medium)].emissionScale = float(e.value);
                pushEdits();
                break;
            case ScriptOp::Transparent: setTransparent(e.value != 0); break;
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

void Viewer::installCallbacks() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;
    ImGui::StyleColorsDark();
    updateUiScale();
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
            case GLFW_KEY_B: v->key("B"); break;
            case GLFW_KEY_F5: v->key("F5"); break;
            case GLFW_KEY_F12: v->key("F12"); break;
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
    // The image follows the window's size once it settles; the panel its content scale.
    glfwSetWindowSizeCallback(m_window, [](GLFWwindow* win, int, int) {
        Viewer* v = self(win);
        v->inputArrived();
        v->m_resizeAt = seconds(Clock::now()) + kResizeSettleSeconds;
    });
    glfwSetWindowContentScaleCallback(m_window, [](GLFWwindow* win, float, float) {
        Viewer* v = self(win);
        v->updateUiScale();
        v->m_resizeAt = seconds(Clock::now()) + kResizeSettleSeconds;  // the panel's width changed
    });
    glfwSetDropCallback(m_window, [](GLFWwindow* win, int count, const char** paths) {
        Viewer* v = self(win);
        v->inputArrived();
        if (count > 0) v->openDropped(paths[0]);
    });
    // Exposed, focused, entered: the window needs a frame too.
    glfwSetWindowRefreshCallback(m_window, [](GLFWwindow* win) { self(win)->inputArrived(); });
    glfwSetWindowFocusCallback(m_window, [](GLFWwindow* win, int) { self(win)->inputArrived(); });
    glfwSetCursorEnterCallback(m_window, [](GLFWwindow* win, int) { self(win)->inputArrived(); });
    // ImGui's backend chains to the callbacks installed above.
    ImGui_ImplGlfw_InitForOpenGL(m_window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
}

}  // namespace tyndall
