#pragma once
// Restart on change, refine on release: the state machine between the viewer's input (UI thread)
// and its render loop (render thread). GLFW-free and unit-tested (tests/viewer/preview_refine_test.cpp).
//
// Every change of the view or the scene bumps a version. While an interaction that changed
// something is held (a mouse drag, a slider being dragged) the wanted mode is Preview: cheap passes of the newest version,
// one after the other; a preview pass under way is allowed to finish (the picture follows the
// mouse at the preview rate instead of restarting forever and showing nothing). On release the
// wanted mode becomes Refine: full-resolution passes from pass 0 of the newest version, and the
// pass under way is interrupted at once. A change outside an interaction (a key, a slider click)
// also restarts a refinement at once. Pressing and releasing without a change (a click) keeps the
// refinement going.
//
// Thread-safety: every member is safe to call from any thread (one mutex, never held for long).
// The UI thread calls began/changed/ended; each returns true when the job under way must be
// interrupted now (the caller then asks the scheduler to stop: PassScheduler::requestExit). The
// render thread calls nextJob() before a run and stale(job) after each pass.
#include <cstdint>
#include <mutex>

namespace tyndall {

enum class RenderMode { Preview, Refine };

class PreviewRefine {
public:
    struct Job {
        RenderMode mode = RenderMode::Refine;
        uint64_t version = 0;
    };

    /// An interaction starts (mouse button down on the image, a slider grabbed).
    bool began();
    /// The view or scene changed (during an interaction or on its own).
    bool changed();
    /// The interaction ends (button released).
    bool ended();
    /// Restart the refinement from pass 0 without a change (the R key).
    bool restart() { return changed(); }

    /// What the render thread should render now; remembers it as the job under way.
    Job nextJob();
    /// After a pass of `job`: true when the job should stop (a newer version or another mode is
    /// wanted). A preview job is stale as soon as anything changed; so is a refinement.
    bool stale(const Job& job) const;

    bool interacting() const;
    RenderMode wantedMode() const;
    uint64_t version() const;

private:
    RenderMode wantedLocked() const {
        return m_interacting && m_changedInInteraction ? RenderMode::Preview : RenderMode::Refine;
    }

    mutable std::mutex m_mutex;
    bool m_interacting = false;
    bool m_changedInInteraction = false;
    uint64_t m_version = 0;
    bool m_running = false;
    Job m_runningJob;
};

}  // namespace tyndall
