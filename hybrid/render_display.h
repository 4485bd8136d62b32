#pragma once
// What the render driver (hybrid/pass_scheduler.h) tells whoever shows its progress (the CLI's
// progress line and checkpoints, the viewer, a test), and what it hears back: continue, reset (the
// camera or a light moved: throw the passes away and start again) or exit. The driver knows
// nothing about windows or terminals.
#include <cstdint>
#include <functional>
#include <string>

#include "core/accumulator.h"
#include "cpu/pass_renderer.h"

namespace tyndall {

/// Where a run of the driver stands after a pass.
struct RenderProgress {
    uint64_t pass = 0;         ///< index of the pass just added
    uint64_t passesDone = 0;   ///< passes added by this run
    double elapsedSeconds = 0;
    PassStats totals;
};

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

    /// One line the user should read about how the render goes on (the GL splatter failed and
    /// the CPU takes over), on the driver's thread; `tyndall render` prints it.
    virtual void notice(const std::string& /*line*/) {}
};

/// A RenderDisplay from a function (a progress printer, a test).
class CallbackDisplay : public RenderDisplay {
public:
    using PassAdded = std::function<DisplayCommand(const Accumulator&, const RenderProgress&)>;
    using Notice = std::function<void(const std::string&)>;
    explicit CallbackDisplay(PassAdded passAdded, std::function<void()> restarting = {}, Notice notice = {})
        : m_passAdded(std::move(passAdded)), m_restarting(std::move(restarting)), m_notice(std::move(notice)) {}
    DisplayCommand passAdded(const Accumulator& acc, const RenderProgress& p) override {
        return m_passAdded ? m_passAdded(acc, p) : DisplayCommand::Continue;
    }
    void restarting() override {
        if (m_restarting) m_restarting();
    }
    void notice(const std::string& line) override {
        if (m_notice) m_notice(line);
    }

private:
    PassAdded m_passAdded;
    std::function<void()> m_restarting;
    Notice m_notice;
};

}  // namespace tyndall
