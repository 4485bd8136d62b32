#pragma once
// The hybrid render loop: overlaps the CPU passes with the GL splatter and feeds one progressive
// accumulator.
//
// Per pass i (PPB steps 1-5): the CPU traces pass i's photons and primary camera segments and
// hands them to the GL thread, which splats them while the CPU gathers pass i's secondary
// segments (through the beam BVH) and then traces pass i+1's photons and primary segments. Pass i
// is added to the accumulator when both halves are in, in pass order; at most `queueDepth` passes
// wait for the GL side, so memory stays flat however many passes run. Within a pass the photons
// come in batches (PassRenderer::memoryPlan()): batch b is splatted on GL while the CPU gathers it
// and traces batch b+1, and the batch splats are summed in batch order, so memory stays flat
// however many photons a pass has. The steady-state rate is that of the slower side.
//
// Without GL (`--gpu off`, or `auto` without a usable context) the same stages run one after the
// other with the CPU twin of the splat (PassRenderer::splatPrimary): same seed, same image up to
// float rounding.
//
// Reset and exit: from the display's answer after a pass, or from any thread through
// requestReset()/requestExit(). They are heard at every stage boundary (photons, primary,
// secondary, splat): the pass under way and those in flight are thrown away; a splat already
// submitted finishes first (GL work is not interrupted), so a restart starts within one stage and
// one splat. After display.restarting() the scheduler calls renderer.sceneChanged() and reloads
// the GL side's media, so a camera, light or medium change made there is rendered.
//
// Threading: run() blocks its calling thread, which also runs the CPU stages (TBB inside) and calls
// the display; the GL context lives on a GlThread owned by the scheduler, kept across runs.
#include <atomic>
#include <memory>
#include <string>

#include "core/accumulator.h"
#include "cpu/pass_renderer.h"
#include "hybrid/render_display.h"

namespace tyndall {

class GlThread;
class GlBeamSplatter;

/// GpuMode (core/settings.h) here: Off never touches GL; On needs the GL splatter (Error
/// otherwise); Auto uses it when a hardware GL context exists and the scene's media can be
/// splatted, else the CPU, with a one-line notice (a software rasterizer such as llvmpipe would
/// take its cores from the CPU passes and run the splat slower than the CPU twin: see
/// docs/performance.md).
struct SchedulerOptions {
    int queueDepth = 1;                  ///< passes that may wait for the GL splat (>= 1)
    bool autoAcceptsSoftwareGl = false;  ///< let Auto use llvmpipe & co. (tests, benchmarks)
};

class PassScheduler {
public:
    /// Starts the GL thread for On (throws Error when there is no context) and Auto.
    explicit PassScheduler(GpuMode mode, SchedulerOptions options = {});
    ~PassScheduler();

    /// Renders passes firstPass, firstPass+1, ... into `acc` until renderer.settings().passes
    /// were added (or its time budget is spent), or the display or a request says exit.
    /// With GL: throws Error for On when the scene's media cannot be splatted (Auto falls back).
    RenderProgress run(PassRenderer& renderer, Accumulator& acc, uint64_t firstPass, RenderDisplay& display);

    /// Prepares the GL splatter for `scene` (run() does it too), after which hybrid() and
    /// notice() are settled for it: throws Error for On when its media cannot be splatted.
    void bind(const Scene& scene);

    /// Thread-safe; act between passes of the current or next run() call.
    void requestReset() { m_resetRequested = true; }
    void requestExit() { m_exitRequested = true; }

    /// True when passes are splatted on GL (after run() bound the scene: false for a scene the
    /// GL side cannot render under Auto).
    bool hybrid() const { return m_glUsable; }
    /// The GL context in use ("" without one).
    const std::string& glDescription() const { return m_glDescription; }
    /// One line explaining why Auto renders on the CPU ("" otherwise); the caller prints it.
    const std::string& notice() const { return m_notice; }
    /// Most passes held at once by the last run() (the CPU stage's plus those waiting for or in
    /// the GL splat): at most queueDepth + 1, however long the render.
    int peakPassesHeld() const { return m_peakPassesHeld; }

private:
    struct Flight;
    void reloadMedia();

    GpuMode m_mode;
    SchedulerOptions m_options;
    std::unique_ptr<GlThread> m_gl;
    std::shared_ptr<GlBeamSplatter> m_splatter;  // used and destroyed on the GL thread only
    const Scene* m_boundScene = nullptr;
    bool m_glUsable = false;
    std::string m_glDescription;
    std::string m_notice;
    int m_peakPassesHeld = 0;
    std::atomic<bool> m_resetRequested{false};
    std::atomic<bool> m_exitRequested{false};
};

}  // namespace tyndall
