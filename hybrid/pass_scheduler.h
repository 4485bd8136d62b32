#pragma once
// The progressive render driver: every render goes through it: `tyndall render` (plain, with AOV
// layers, resumed from a checkpoint, one of several MPI ranks), `tyndall compare`, the viewer's
// preview and refinement, and the tests. It hands out the passes, renders each on the CPU or with
// its primary media splatted on GL, adds them to one progressive accumulator in pass order,
// reports to a RenderDisplay after each, and stops on the pass target or the time budget of
// renderer.settings(), the display's answer, or a request.
//
// With GL, per pass i (PPB steps 1-5): the CPU traces pass i's photons and primary camera segments
// and hands them to the GL thread, which splats them while the CPU gathers pass i's secondary
// segments (through the beam BVH) and then traces pass i+1's photons and primary segments. Pass i
// is added when both halves are in, in pass order; at most `queueDepth` passes wait for the GL
// side, so memory stays flat however many passes run. Within a pass the photons come in batches
// (PassRenderer::memoryPlan()): batch b is splatted on GL while the CPU gathers it and traces
// batch b+1, and the batch splats are summed in batch order. The steady-state rate is that of the
// slower side. With AOV layers the primary-media layer is the GL splat, the others the CPU's.
//
// Without GL (GpuMode::Off, or Auto without a usable context) each pass is PassRenderer's CPU pass
// (the CPU twin of the splat): same seed, same image up to float rounding, and bit for bit what
// PassRenderer::renderPass gives.
//
// Processes: with a PassDistribution of several ranks (hybrid/pass_distribution.h) the passes go
// out in rounds; each rank renders its pass of a round (CPU or GL, passes not overlapped), rank 0
// adds the round's passes in pass order and alone talks to the display; the image is the
// one-process image bit for bit (on the CPU).
//
// When GL fails (a lost context, a driver reset: a splat that throws), the render goes on on the
// CPU: the passes already added are kept, the failed pass and those in flight are rendered again
// on the CPU, the display hears one notice, and the scheduler stays on the CPU from then on.
//
// Reset and exit: from the display's answer after a pass, or from any thread through
// requestReset()/requestExit(). They are heard at every stage boundary (photons, primary,
// secondary, splat): the pass under way and those in flight are thrown away; a splat already
// submitted finishes first (GL work is not interrupted), so a restart starts within one stage and
// one splat. After display.restarting() the scheduler calls renderer.sceneChanged() and reloads
// the GL side's media, so a camera, light or medium change made there is rendered. A distributed
// render hears exit only (rank 0's display), at the end of a round.
//
// Threading: run() blocks its calling thread, which also runs the CPU stages (TBB inside) and calls
// the display; the GL context lives on a GlThread owned by the scheduler, kept across runs.
#include <atomic>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <utility>

#include "core/accumulator.h"
#include "core/layer_accumulator.h"
#include "core/settings.h"
#include "cpu/pass_renderer.h"
#include "cpu/test_hooks.h"
#include "hybrid/pass_distribution.h"
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
    const TestHooks* hooks = nullptr;    ///< planted faults (cpu/test_hooks.h); not owned
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
    /// The same into `layers` (with layers.aov(), the pass components too, from the GL splat as
    /// from the CPU), its passes shared among `ranks`: every rank calls it with the same
    /// arguments; rank 0's `layers` receives every pass and rank 0 alone calls the display (the
    /// others' stay empty). Returns this rank's view of the progress (rank 0: every pass).
    RenderProgress run(PassRenderer& renderer, LayerAccumulator& layers, uint64_t firstPass, RenderDisplay& display,
                       const PassDistribution& ranks = PassDistribution::single());

    /// Prepares the GL splatter for `scene` (run() does it too), after which hybrid() and
    /// notice() are settled for it: throws Error for On when its media cannot be splatted.
    void bind(const Scene& scene);

    /// Thread-safe; act between passes of the current or next run() call.
    void requestReset() { m_resetRequested = true; }
    void requestExit() { m_exitRequested = true; }

    /// True when passes are splatted on GL (after run() bound the scene: false for a scene the
    /// GL side cannot render under Auto, and after GL failed).
    bool hybrid() const { return m_glUsable; }
    /// The GL context in use ("" without one).
    const std::string& glDescription() const { return m_glDescription; }
    /// One line explaining why Auto renders on the CPU ("" otherwise); the caller prints it.
    const std::string& notice() const { return m_notice; }
    /// Most passes held at once by the last run() (the CPU stage's plus those waiting for or in
    /// the GL splat): at most queueDepth + 1, however long the render.
    int peakPassesHeld() const { return m_peakPassesHeld; }

private:
    class Run;
    void reloadMedia();
    /// Queues the splat of one photon batch on the GL thread.
    std::future<std::pair<Image, double>> submitSplat(uint64_t pass, std::shared_ptr<const PrimaryPass> primary,
                                                      std::shared_ptr<const PhotonMap> photons);
    /// After a splat failed: the CPU from now on; returns the notice line.
    std::string glFailed(uint64_t pass, const std::exception_ptr& error);

    GpuMode m_mode;
    SchedulerOptions m_options;
    std::unique_ptr<GlThread> m_gl;
    std::shared_ptr<GlBeamSplatter> m_splatter;  // used and destroyed on the GL thread only
    const Scene* m_boundScene = nullptr;
    bool m_glUsable = false;
    bool m_glFailed = false;
    std::string m_glDescription;
    std::string m_notice;
    int m_peakPassesHeld = 0;
    std::atomic<bool> m_resetRequested{false};
    std::atomic<bool> m_exitRequested{false};
};

}  // namespace tyndall
