// The viewer's panel (Dear ImGui): status, render settings, lights, environment, media, cameras,
// and the key bindings (also the H overlay).
#include "viewer/viewer_window.h"

#include <imgui.h>

namespace tyndall {

namespace {
const char* kBindings[][2] = {
    {"left drag", "orbit about the pivot"},
    {"right / middle drag", "pan"},
    {"wheel", "dolly toward / away from the pivot"},
    {"double-click", "set the pivot (and focus) on a surface"},
    {"ctrl/shift + left drag", "move the selected light (a spot aims at the cursor)"},
    {"alt + left drag", "draw a render region: only it refines"},
    {"B", "draw a region with the next left drag; with one, clear it"},
    {"F", "frame the scene"},
    {"1 - 9", "pick a camera"},
    {"+ / -", "exposure up / down"},
    {"Space", "pause / resume"},
    {"R", "restart the refinement"},
    {"F5", "reload the scene file (also done when it changes on disk)"},
    {"S", "save EXR + PNG + scene .json"},
    {"F12", "final render: save the view, `tyndall render` it in the background"},
    {"H", "help overlay"},
    {"Escape", "quit"},
};
}  // namespace

void Viewer::drawHelp() {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f + float(panelWidth()) * 0.5f, io.DisplaySize.y * 0.5f),
                            ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.85f);
    ImGui::Begin("Keys and mouse (H closes)", &m_help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
    for (const auto& b : kBindings) ImGui::Text("%-24s %s", b[0], b[1]);
    ImGui::End();
}

void Viewer::drawRegionOutline() {
    const PixelRegion& set = m_settings.region;
    if (set.whole() && !m_drawingRegion) return;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const int gap = m_o.compare ? 4 : 0;
    for (size_t i = 0; i < m_loops.size(); ++i) {
        const float x0 = float(panelWidth() + int(i) * (m_o.settings.width + gap));
        auto outline = [&](const PixelRegion& r, ImU32 colour) {
            draw->AddRect(ImVec2(x0 + float(r.x) - 1, float(r.y) - 1),
                          ImVec2(x0 + float(r.x + r.width) + 1, float(r.y + r.height) + 1), colour);
        };
        if (!set.whole()) outline(set, IM_COL32(255, 200, 60, 200));
        if (m_drawingRegion) outline(dragRegion(), IM_COL32(255, 255, 255, 230));
    }
}

void Viewer::drawPanel() {
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(float(panelWidth()), io.DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Tyndall", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-110.0f * m_uiScale);  // room for the labels
    const bool paused = m_loops[0]->paused();   // one state for the whole panel
    drawPanelStatus(paused);
    ImGui::Separator();
    drawPanelRenderControls(paused);
    drawPanelRegion();
    drawPanelFilm();
    drawPanelLights();
    drawPanelEnvironment();
    drawPanelMedia();
    drawPanelCameras();
    if (ImGui::CollapsingHeader("Keys and mouse")) {
        for (const auto& b : kBindings) ImGui::TextWrapped("%s: %s", b[0], b[1]);
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

void Viewer::drawPanelStatus(bool paused) {
    const ViewFrame& f = m_frames[0];
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
}

void Viewer::drawPanelRenderControls(bool paused) {
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
    if (ImGui::Button("Final render (F12)")) key("F12");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90.0f * m_uiScale);
    ImGui::InputInt("passes", &m_finalPasses, 16, 256);
    m_finalPasses = std::clamp(m_finalPasses, 1, 1 << 30);
    if (m_final.state() == FinalRender::State::Running)
        ImGui::TextWrapped("final render (nice +10): %s", m_finalLine.empty() ? "starting" : m_finalLine.c_str());
}

void Viewer::drawPanelRegion() {
    const PixelRegion& region = m_settings.region;
    if (region.whole()) {
        if (ImGui::Button(m_regionArmed ? "Drag on the image..." : "Draw region (B)")) key("B");
        ImGui::SameLine();
        ImGui::TextDisabled("whole image");
    } else {
        if (ImGui::Button("Clear region (B)")) key("B");
        ImGui::SameLine();
        ImGui::Text("%d %d %d x %d", region.x, region.y, region.width, region.height);
    }
}

void Viewer::drawPanelFilm() {
    bool transparent = m_settings.transparentFilm;
    if (ImGui::Checkbox("transparent film", &transparent)) setTransparent(transparent);
}

void Viewer::panelEdit(bool edited) {
    if (ImGui::IsItemActivated())
        for (auto& loop : m_loops) loop->beginInteraction();
    if (edited) pushEdits();
    if (ImGui::IsItemDeactivated()) {
        for (auto& loop : m_loops) loop->endInteraction();
    }
}

void Viewer::drawPanelLights() {
    if (m_edited.lights.empty() || !ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
    for (size_t i = 0; i < m_edited.lights.size(); ++i) {
        ImGui::PushID(int(i));
        ImGui::RadioButton(m_edited.lights[i].name.c_str(), &m_selectedLight, int(i));
        ImGui::SameLine();
        panelEdit(ImGui::ColorEdit3("##colour", m_lightUi[i].colour, ImGuiColorEditFlags_NoInputs));
        panelEdit(ImGui::DragFloat("power", &m_lightUi[i].power, 0.01f * std::max(m_lightUi[i].power, 0.1f), 0.0f, 1e9f,
                                   "%.3g"));
        ImGui::PopID();
    }
}

void Viewer::drawPanelEnvironment() {
    if (!m_edited.environment || !ImGui::CollapsingHeader("Environment", ImGuiTreeNodeFlags_DefaultOpen)) return;
    panelEdit(ImGui::DragFloat("intensity", &m_environmentScale, 0.01f * std::max(m_environmentScale, 0.1f), 0.0f, 1e9f,
                               "%.3g"));
    panelEdit(ImGui::SliderFloat("rotation", &m_environmentRotation, -180.0f, 180.0f, "%.0f deg"));
}

void Viewer::drawPanelMedia() {
    // With --compare only the emission sliders show (the twin's coefficients differ from the grid's;
    // one emission scale drives both halves: twinSceneEdits).
    bool anyEmits = false;
    for (const MediumUi& u : m_mediumUi) anyEmits |= u.emits;
    if (m_edited.media.empty() || (m_o.compare && !anyEmits) ||
        !ImGui::CollapsingHeader("Media", ImGuiTreeNodeFlags_DefaultOpen))
        return;
    if (m_o.compare) ImGui::TextWrapped("emission: both halves");
    for (size_t i = 0; i < m_edited.media.size(); ++i) {
        MediumUi& u = m_mediumUi[i];
        if (m_o.compare && !u.emits) continue;
        ImGui::PushID(1000 + int(i));
        ImGui::Text("%s%s", m_edited.media[i].name.c_str(), u.heterogeneous ? " (grid)" : "");
        if (!m_o.compare) {
            if (!u.heterogeneous) {
                // A grid medium's extinction must stay grey (docs/scene-format.md): only scale and g.
                panelEdit(ImGui::DragFloat3("sigma_s", u.sigmaS, 0.001f, 0.0f, 1e4f, "%.4g"));
                panelEdit(ImGui::DragFloat3("sigma_a", u.sigmaA, 0.001f, 0.0f, 1e4f, "%.4g"));
            }
            panelEdit(ImGui::SliderFloat("g", &u.g, -0.95f, 0.95f, "%.2f"));
            panelEdit(ImGui::DragFloat("density scale", &u.densityScale, 0.01f, 0.001f, 1e3f, "%.3f"));
        }
        if (u.emits)  // fire, glowing gas: Le times this
            panelEdit(
                ImGui::SliderFloat("emission", &u.emissionScale, 0.0f, 100.0f, "%.3g", ImGuiSliderFlags_Logarithmic));
        ImGui::PopID();
    }
}

void Viewer::drawPanelCameras() {
    if (!ImGui::CollapsingHeader("Cameras", ImGuiTreeNodeFlags_DefaultOpen)) return;
    for (size_t i = 0; i < m_o.cameraNames.size(); ++i) {
        std::string label = std::to_string(i + 1) + "  " + m_o.cameraNames[i];
        if (ImGui::Selectable(label.c_str(), m_cameraIndex == int(i)) && i < 9) key(std::string(1, char('1' + i)));
    }
}

}  // namespace tyndall
