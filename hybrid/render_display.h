#pragma once
// What the render loop tells whoever shows its progress (the CLI's progress line, the future
// interactive viewer, a test), and what it hears back: continue, reset (the camera or a light
// moved: throw the passes away and start again) or exit. The loop knows nothing about windows.
#include <functional>

#include "core/accumulator.h"
#include "cpu/progressive_render.h"

namespace tyndall {

enum class DisplayCommand { Continue, Reset, Exit };

class RenderDisplay {
public:
    virtual ~RenderDisplay() = default;

    /// Pass `progress.pass` was just added to `acc`. Called on the thread running the loop, in
    /// pass order, while later passes may already be in flight: read `acc` (mean(), passCount())
    /// but do not change the scene here. Reset discards the passes in flight and restarts.
    virtual DisplayCommand passAdded(const Accumulator& acc, const RenderProgress& progress) = 0;

    /// After a reset, with no pass in flight and `acc` cleared, just before the first pass of the
    /// new render: the one moment where the scene the renderer reads may change: the camera, the
    /// lights' positions, directions and powers, the media's coefficients (the loop then calls
    /// PassRenderer::sceneChanged). Geometry and materials are baked into the PassRenderer's ray
    /// tracer: for those, build a new one and run again.
    virtual void restarting() {}
};

/// A RenderDisplay from a function (a progress printer, a test).
class CallbackDisplay : public RenderDisplay {
public:
    using PassAdded = std::function<DisplayCommand(const Accumulator&, const RenderProgress&)>;
    explicit CallbackDisplay(PassAdded passAdded, std::function<void()> restarting = {})
        : m_passAdded(std::move(passAdded)), m_restarting(std::move(restarting)) {}
    DisplayCommand passAdded(const Accumulator& acc, const RenderProgress& p) override {
        return m_passAdded ? m_passAdded(acc, p) : DisplayCommand::Continue;
    }
    void restarting() override {
        if (m_restarting) m_restarting();
    }

private:
    PassAdded m_passAdded;
    std::function<void()> m_restarting;
};

}  // namespace tyndall
