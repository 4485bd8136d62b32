#pragma once
// The viewer's render thread: runs PassScheduler jobs (hybrid/) on a scene the UI edits, one job
// per (mode, version) of a PreviewRefine, and publishes the running mean after every pass. The UI
// thread never waits for a pass: it submits edits and settings, and takes the newest published
// frame when there is one.
//
// A job applies the newest edits (loading/scene_edits.h: the same code a saved view file goes
// through) to the loop's scene, calls PassRenderer::sceneChanged, rebinds the GL side's media, and
// renders passes 0, 1, ... into a fresh accumulator until PreviewRefine says it is stale, the loop
// is stopped, or (paused) it waits after a pass without losing what it has. Refine jobs render at
// the full settings; preview jobs at 1/previewScale of the resolution and 1/previewPhotonDivisor of
// the photon paths (docs/viewer.md has the measured cost).
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "core/image.h"
#include "core/scene.h"
#include "core/settings.h"
#include "cpu/pass_renderer.h"
#include "hybrid/pass_scheduler.h"
#include "viewer/preview_refine.h"

namespace tyndall {

struct PreviewOptions {
    int scale = 4;           ///< preview resolution = full / scale (per axis), >= 1 (bench/viewer_bench.sh)
    int photonDivisor = 16;  ///< preview photon paths per pass = full / divisor, >= 1
};

/// The preview settings for `full` (resolution and photons reduced, everything else equal).
RenderSettings previewSettings(const RenderSettings& full, const PreviewOptions& preview);

/// One published state of a job: the running mean after `passes` passes and what made it.
struct ViewFrame {
    uint64_t serial = 0;  ///< increases with every publication (0: nothing yet)
    Image mean;           ///< linear running mean (preview frames are smaller)
    Image alpha;          ///< RenderSettings::transparentFilm: the coverage's running mean (r), else empty
    uint64_t passes = 0;
    RenderMode mode = RenderMode::Refine;
    uint64_t version = 0;      ///< the PreviewRefine version it shows
    double elapsedSeconds = 0; ///< since the job started
    double setupSeconds = 0;   ///< of that, the job's setup before its first pass (edits, renderers)
    PassStats totals;          ///< summed over the job's passes
    RenderSettings settings;   ///< the job's settings (resolved radii: see `radii`)
    RadiusSetup radii;         ///< resolved first radii and schedule
    nlohmann::json edits;      ///< the edits the job's scene was made with
    bool hybrid = false;       ///< splatted on GL
};

class RenderLoop {
public:
    /// `scene` is the base the edits apply to (copied); `settings` validated. Starts no thread.
    RenderLoop(Scene scene, RenderSettings settings, GpuMode gpu, PreviewOptions preview = {},
               SchedulerOptions schedulerOptions = {});
    ~RenderLoop();
    RenderLoop(const RenderLoop&) = delete;
    RenderLoop& operator=(const RenderLoop&) = delete;

    /// Starts the render thread (with `edits` as the first job's edits).
    void start(const nlohmann::json& edits);
    /// Set before start: called on the render thread after each publication and on an error (the UI
    /// wakes on it).
    void onPublish(std::function<void()> wake) { m_onPublish = std::move(wake); }
    /// Stops the job under way within one stage and joins.
    void stop();

    // UI thread; none of these waits for a pass.
    /// An interaction (drag) begins / ends (PreviewRefine::began/ended).
    void beginInteraction();
    void endInteraction();
    /// New edits (a snapshot of the editable fields, or a part of them) for the next job.
    void setEdits(const nlohmann::json& edits);
    /// New settings (photons, alpha, ...; size stays) for the next job.
    void setSettings(const RenderSettings& settings);
    void restart();
    void setPaused(bool paused);
    bool paused() const { return m_paused; }

    /// Copies the newest frame into `out` when its serial is newer than out->serial.
    bool latest(ViewFrame* out) const;
    /// The first error the render thread met ("" while none); the thread stops on it.
    std::string error() const;

    const RenderSettings& settings() const { return m_settings; }
    const Scene& baseScene() const { return m_base; }
    /// The GL context used for splatting ("" for the CPU) and the scheduler's notice.
    std::string glDescription() const;
    std::string notice() const;
    PreviewRefine& control() { return m_control; }

private:
    void run();
    void changed();
    void publish(const Accumulator& acc, const RenderProgress& progress, const PreviewRefine::Job& job,
                 const PassRenderer& renderer, double jobStart, const LayerAccumulator* layers);

    Scene m_base;
    Scene m_scene;  // the render thread's edited copy
    RenderSettings m_settings;
    PreviewOptions m_preview;
    PreviewRefine m_control;
    std::unique_ptr<PassScheduler> m_scheduler;
    std::unique_ptr<PassRenderer> m_full, m_cheap;
    nlohmann::json m_jobEdits;  // the edits of the job under way (render thread only)
    double m_jobSetupSeconds = 0;

    mutable std::mutex m_mutex;  // guards the fields below
    std::condition_variable m_wake;
    nlohmann::json m_pendingEdits;
    RenderSettings m_pendingSettings;
    bool m_settingsChanged = false;
    ViewFrame m_frame;
    std::string m_error;
    std::string m_glDescription, m_notice;

    std::function<void()> m_onPublish;
    std::atomic<bool> m_paused{false};
    std::atomic<bool> m_quit{false};
    std::thread m_thread;
};

}  // namespace tyndall
