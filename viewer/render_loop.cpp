#include "viewer/render_loop.h"

#include <chrono>
#include <limits>

#include "core/accumulator.h"
#include "core/error.h"
#include "core/layer_accumulator.h"
#include "loading/scene_edits.h"

namespace tyndall {

namespace {
double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

RenderSettings previewSettings(const RenderSettings& full, const PreviewOptions& preview) {
    RenderSettings s = full;
    int scale = std::max(preview.scale, 1);
    s.width = std::max(1, full.width / scale);
    s.height = std::max(1, full.height / scale);
    s.photonsPerPass = std::max<uint32_t>(1, full.photonsPerPass / uint32_t(std::max(preview.photonDivisor, 1)));
    s.region = PixelRegion{};  // a preview shows the whole view
    return s;
}

RenderLoop::RenderLoop(Scene scene, RenderSettings settings, GpuMode gpu, PreviewOptions preview,
                       SchedulerOptions schedulerOptions)
    : m_base(std::move(scene)), m_scene(m_base), m_settings(settings), m_preview(preview) {
    m_settings.validate();
    m_pendingSettings = m_settings;
    m_scheduler = std::make_unique<PassScheduler>(gpu, schedulerOptions);
    m_glDescription = m_scheduler->glDescription();
    m_notice = m_scheduler->notice();
}

RenderLoop::~RenderLoop() { stop(); }

void RenderLoop::start(const nlohmann::json& edits) {
    if (m_thread.joinable()) return;
    m_pendingEdits = edits;
    m_quit = false;
    m_thread = std::thread([this] { run(); });
}

void RenderLoop::stop() {
    if (!m_thread.joinable()) return;
    m_quit = true;
    m_scheduler->requestExit();
    m_wake.notify_all();
    m_thread.join();
}

void RenderLoop::changed() {
    if (m_control.changed()) m_scheduler->requestExit();
    m_wake.notify_all();
}

void RenderLoop::beginInteraction() { m_control.began(); }

void RenderLoop::endInteraction() {
    if (m_control.ended()) m_scheduler->requestExit();
    m_wake.notify_all();
}

void RenderLoop::setEdits(const nlohmann::json& edits) {
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_pendingEdits = edits;
    }
    changed();
}

void RenderLoop::setSettings(const RenderSettings& settings) {
    settings.validate();
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_pendingSettings = settings;
        m_pendingSettings.width = m_settings.width;
        m_pendingSettings.height = m_settings.height;
        m_settingsChanged = true;
    }
    changed();
}

void RenderLoop::restart() { changed(); }

void RenderLoop::setPaused(bool paused) {
    m_paused = paused;
    m_wake.notify_all();
}

bool RenderLoop::latest(ViewFrame* out) const {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (m_frame.serial <= out->serial) return false;
    *out = m_frame;
    return true;
}

std::string RenderLoop::error() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_error;
}

std::string RenderLoop::glDescription() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_glDescription;
}

std::string RenderLoop::notice() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_notice;
}

void RenderLoop::publish(const Accumulator& acc, const RenderProgress& progress, const PreviewRefine::Job& job,
                         const PassRenderer& renderer, double jobStart, const LayerAccumulator* layers) {
    ViewFrame f;
    f.setupSeconds = m_jobSetupSeconds;
    f.mean = acc.mean();
    if (layers && layers->transparent()) f.alpha = layers->alpha();
    f.passes = acc.passCount();
    f.mode = job.mode;
    f.version = job.version;
    f.elapsedSeconds = now() - jobStart;
    f.totals = progress.totals;
    f.settings = renderer.settings();
    f.radii = renderer.radii();
    f.hybrid = m_scheduler->hybrid();
    f.edits = m_jobEdits;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        f.serial = m_frame.serial + 1;
        m_frame = std::move(f);
    }
    if (m_onPublish) m_onPublish();
}

void RenderLoop::run() {
    try {
        while (!m_quit) {
            PreviewRefine::Job job = m_control.nextJob();
            double setupStart = now();
            nlohmann::json edits;
            {
                std::lock_guard<std::mutex> lock(m_mutex);
                edits = m_pendingEdits;
                if (m_settingsChanged || !m_full) {
                    m_settings = m_pendingSettings;
                    m_settingsChanged = false;
                    m_full.reset();
                    m_cheap.reset();
                }
            }
            applySceneEdits(m_scene, edits, "viewer edits");
            // Open-ended: a job runs until it is stale; the saved settings record the passes done.
            RenderSettings full = m_settings;
            full.passes = std::numeric_limits<uint64_t>::max();
            full.timeBudget = 0;
            if (!m_full) {
                m_full = std::make_unique<PassRenderer>(m_scene, full);
                m_cheap = std::make_unique<PassRenderer>(m_scene, previewSettings(full, m_preview));
            }
            PassRenderer& renderer = job.mode == RenderMode::Refine ? *m_full : *m_cheap;
            renderer.sceneChanged();
            m_jobEdits = edits;
            // A transparent film accumulates its coverage beside the image (LayerAccumulator).
            const bool transparent = renderer.settings().transparentFilm;
            Accumulator acc(renderer.settings().width, renderer.settings().height);
            LayerAccumulator layers(renderer.settings().width, renderer.settings().height, false, transparent);
            double jobStart = setupStart;
            CallbackDisplay display([&](const Accumulator& a, const RenderProgress& progress) {
                publish(a, progress, job, renderer, jobStart, transparent ? &layers : nullptr);
                if (m_quit || m_control.stale(job)) return DisplayCommand::Exit;
                if (m_paused) {
                    std::unique_lock<std::mutex> lock(m_mutex);
                    m_wake.wait(lock, [&] { return !m_paused || m_quit || m_control.stale(job); });
                    if (m_quit || m_control.stale(job)) return DisplayCommand::Exit;
                }
                return DisplayCommand::Continue;
            });
            m_scheduler->bind(m_scene);
            {
                std::lock_guard<std::mutex> lock(m_mutex);
                m_glDescription = m_scheduler->hybrid() ? m_scheduler->glDescription() : std::string();
                m_notice = m_scheduler->notice();
            }
            m_jobSetupSeconds = now() - setupStart;
            if (transparent)
                m_scheduler->run(renderer, layers, 0, display);
            else
                m_scheduler->run(renderer, acc, 0, display);
        }
    } catch (const std::exception& e) {
        {
            std::lock_guard<std::mutex> lock(m_mutex);
            m_error = e.what();
        }
        if (m_onPublish) m_onPublish();
    }
}

}  // namespace tyndall
