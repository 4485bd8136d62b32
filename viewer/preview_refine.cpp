#include "viewer/preview_refine.h"

namespace tyndall {

bool PreviewRefine::began() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_interacting = true;
    m_changedInInteraction = false;
    return false;
}

bool PreviewRefine::changed() {
    std::lock_guard<std::mutex> lock(m_mutex);
    ++m_version;
    if (m_interacting) m_changedInInteraction = true;
    // A preview pass under way finishes (it is cheap, and restarting it on every mouse motion would
    // show nothing); a refinement of an old version stops at once.
    return m_running && m_runningJob.mode == RenderMode::Refine;
}

bool PreviewRefine::ended() {
    std::lock_guard<std::mutex> lock(m_mutex);
    if (!m_interacting) return false;
    bool changed = m_changedInInteraction;
    m_interacting = false;
    m_changedInInteraction = false;
    if (!changed) return false;
    // Refine the released view from pass 0: a version of its own, and the preview under way stops.
    ++m_version;
    return m_running;
}

PreviewRefine::Job PreviewRefine::nextJob() {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_runningJob = Job{wantedLocked(), m_version};
    m_running = true;
    return m_runningJob;
}

bool PreviewRefine::stale(const Job& job) const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return job.version != m_version || job.mode != wantedLocked();
}

bool PreviewRefine::interacting() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_interacting;
}

RenderMode PreviewRefine::wantedMode() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return wantedLocked();
}

uint64_t PreviewRefine::version() const {
    std::lock_guard<std::mutex> lock(m_mutex);
    return m_version;
}

}  // namespace tyndall
