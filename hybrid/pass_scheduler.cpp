#include "hybrid/pass_scheduler.h"

#include <chrono>
#include <deque>
#include <future>

#include "core/error.h"
#include "gpu/beam_splatter.h"
#include "hybrid/gl_thread.h"

namespace tyndall {

namespace {
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}
}  // namespace

/// One pass between its CPU stages and the accumulator.
struct PassScheduler::Flight {
    uint64_t pass = 0;
    PassStats stats;
    /// GL: the primary-segment images of the batches still being splatted, in batch order, and
    /// their seconds.
    std::deque<std::future<std::pair<Image, double>>> splats;
    Image splatSum;  // GL: the sum of the batches' splats collected so far, in batch order
    Image image;     // the secondary stage's radiance (GL), or the finished pass image (CPU only)

    /// Waits for the oldest pending splat and adds it to splatSum.
    void collectSplat() {
        auto [image, seconds] = splats.front().get();
        splats.pop_front();
        stats.splatSeconds += seconds;
        if (splatSum.pixels.empty())
            splatSum = std::move(image);
        else
            splatSum += image;
    }
    void waitSplats() {
        for (auto& s : splats)
            if (s.valid()) s.wait();
    }
};

namespace {
/// Adds `part` to `sum` (moves it in for the first batch: one pass of one batch is unchanged).
void addBatch(Image& sum, Image&& part) {
    if (sum.pixels.empty())
        sum = std::move(part);
    else
        sum += part;
}
}  // namespace

PassScheduler::PassScheduler(GpuMode mode, SchedulerOptions options) : m_mode(mode), m_options(options) {
    m_options.queueDepth = std::max(m_options.queueDepth, 1);
    if (mode == GpuMode::Off) return;
    try {
        m_gl = std::make_unique<GlThread>();
    } catch (const Error& e) {
        if (mode == GpuMode::On) throw Error(std::string("--gpu on: ") + e.what());
        m_notice = std::string("--gpu auto: rendering on the CPU: ") + e.what();
        return;
    }
    m_glDescription = m_gl->description();
    if (mode == GpuMode::Auto && m_gl->isSoftware() && !m_options.autoAcceptsSoftwareGl) {
        m_notice = "--gpu auto: rendering on the CPU: OpenGL here is a software rasterizer (" + m_glDescription +
                   ") that would take its cores from the CPU passes (--gpu on forces it)";
        m_gl.reset();
        m_glDescription.clear();
    }
}

PassScheduler::~PassScheduler() {
    if (m_gl && m_splatter) m_gl->submit([this](GlContext&) { m_splatter.reset(); }).wait();
}

void PassScheduler::bind(const Scene& scene) {
    if (!m_gl) return;
    if (m_boundScene == &scene && m_splatter) {
        reloadMedia();
        return;
    }
    try {
        m_gl->submit([this, &scene](GlContext& ctx) {
                m_splatter.reset();
                m_splatter = std::make_shared<GlBeamSplatter>(ctx, scene);
            })
            .get();
        m_boundScene = &scene;
        m_glUsable = true;
        m_notice.clear();
    } catch (const Error& e) {
        m_boundScene = nullptr;
        m_glUsable = false;
        if (m_mode == GpuMode::On) throw Error(std::string("--gpu on: ") + e.what());
        m_notice = std::string("--gpu auto: rendering on the CPU: ") + e.what();
    }
}

void PassScheduler::reloadMedia() {
    if (m_glUsable) m_gl->submit([this](GlContext&) { m_splatter->reloadMedia(); }).get();
}

RenderProgress PassScheduler::run(PassRenderer& renderer, Accumulator& acc, uint64_t firstPass,
                                  RenderDisplay& display) {
    bind(renderer.scene());
    const RenderSettings& s = renderer.settings();
    std::deque<Flight> flights;
    RenderProgress progress;
    auto start = Clock::now();
    uint64_t next = firstPass;
    m_peakPassesHeld = 0;

    auto wantMore = [&] {
        if (s.timeBudget > 0) return secondsSince(start) < s.timeBudget;
        return next - firstPass < s.passes;
    };
    auto interrupted = [&] { return m_resetRequested.load() || m_exitRequested.load(); };
    // Waits for the oldest pass's splat, adds the pass, asks the display.
    auto finishOldest = [&] {
        Flight f = std::move(flights.front());
        flights.pop_front();
        if (m_glUsable) {
            while (!f.splats.empty()) f.collectSplat();
            f.splatSum += f.image;
            f.image = std::move(f.splatSum);
        }
        acc.addPass(f.image);
        progress.totals += f.stats;
        progress.pass = f.pass;
        progress.passesDone++;
        progress.elapsedSeconds = secondsSince(start);
        return display.passAdded(acc, progress);
    };
    // Passes in flight are thrown away; their splats still finish (they read their inputs).
    auto discardFlights = [&] {
        for (Flight& f : flights) f.waitSplats();
        flights.clear();
    };
    // The CPU stages of one pass, with each photon batch's splat submitted before its secondary
    // stage; returns Continue with the pass queued, or what a display or request said meanwhile
    // (the pass is then dropped at the next stage or batch boundary). Batches: the GL side splats
    // batch b while the CPU gathers it and traces batch b + 1, so at most two batches are held
    // (MemoryPlan::kBatchesHeld); each is freed once both sides are done with it.
    auto startPass = [&] {
        Flight f;
        f.pass = next++;
        const uint32_t batches = renderer.memoryPlan().batches;
        auto t0 = Clock::now();
        auto photons = std::make_shared<const PhotonMap>(renderer.tracePhotons(f.pass, 0));
        f.stats.add(*photons);
        f.stats.photonSeconds = secondsSince(t0);
        if (interrupted()) return DisplayCommand::Continue;
        auto t1 = Clock::now();
        auto primary = std::make_shared<const PrimaryPass>(renderer.tracePrimary(f.pass));
        CameraPassStats camera;
        camera.rays = primary->rays;
        f.stats.cameraSeconds = secondsSince(t1);
        if (interrupted()) return DisplayCommand::Continue;
        m_peakPassesHeld = std::max(m_peakPassesHeld, int(flights.size()) + 1);
        while (int(flights.size()) >= m_options.queueDepth) {
            DisplayCommand command = finishOldest();
            if (command != DisplayCommand::Continue) return command;
        }
        for (uint32_t batch = 0;;) {
            auto t2 = Clock::now();
            if (m_glUsable) {
                while (!f.splats.empty()) f.collectSplat();  // the batch before last is freed
                f.splats.push_back(m_gl->submit([this, primary, photons](GlContext&) mutable {
                    auto t = Clock::now();
                    Image image = m_splatter->splat(primary->segments, *photons);
                    photons.reset();  // free the batch now, not when the future is read
                    return std::make_pair(std::move(image), secondsSince(t));
                }));
                addBatch(f.image, renderer.traceSecondary(*primary, *photons, &camera, batch == 0));
                f.stats.cameraSeconds += secondsSince(t2);
            } else {
                Image radiance = renderer.traceSecondary(*primary, *photons, &camera, batch == 0);
                f.stats.cameraSeconds += secondsSince(t2);
                auto t3 = Clock::now();
                if (!interrupted()) {
                    Image part = renderer.splatPrimary(primary->segments, *photons);
                    part += radiance;
                    addBatch(f.image, std::move(part));
                }
                f.stats.splatSeconds += secondsSince(t3);
            }
            photons.reset();
            if (++batch == batches || interrupted()) break;
            auto t4 = Clock::now();
            photons = std::make_shared<const PhotonMap>(renderer.tracePhotons(f.pass, batch));
            f.stats.add(*photons);
            f.stats.photonSeconds += secondsSince(t4);
        }
        f.stats.add(camera);
        flights.push_back(std::move(f));
        // Without GL nothing overlaps: the pass is finished at once (unless the loop is about to
        // throw it away).
        return m_glUsable || interrupted() ? DisplayCommand::Continue : finishOldest();
    };

    try {
        for (;;) {
            DisplayCommand command = DisplayCommand::Continue;
            if (wantMore())
                command = startPass();
            else if (!flights.empty())
                command = finishOldest();
            else
                break;
            if (m_resetRequested.exchange(false) && command == DisplayCommand::Continue)
                command = DisplayCommand::Reset;
            if (m_exitRequested) command = DisplayCommand::Exit;
            if (command == DisplayCommand::Exit) break;
            if (command == DisplayCommand::Reset) {
                discardFlights();
                acc.reset();
                display.restarting();
                renderer.sceneChanged();
                reloadMedia();
                next = firstPass;
                progress = RenderProgress();
                start = Clock::now();
            }
        }
    } catch (...) {
        discardFlights();
        throw;
    }
    discardFlights();
    m_exitRequested = false;
    return progress;
}

}  // namespace tyndall
