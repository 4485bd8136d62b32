#include "hybrid/pass_scheduler.h"

#include <algorithm>
#include <deque>

#include "core/error.h"
#include "core/timing.h"
#include "gpu/beam_splatter.h"
#include "hybrid/gl_thread.h"
#include "hybrid/pass_flight.h"

namespace tyndall {

namespace {
/// What a run adds its passes to: a plain accumulator, or the layers of a render with AOVs.
struct PassSink {
    Accumulator* plain = nullptr;
    LayerAccumulator* layers = nullptr;

    bool aov() const { return layers && layers->aov(); }
    bool transparent() const { return layers && layers->transparent(); }
    const Accumulator& beauty() const { return plain ? *plain : layers->beauty(); }
    void add(const PassLayers& p) {
        if (plain)
            plain->addPass(p.beauty);
        else
            layers->addPass(p.beauty, p.mediaPrimary, p.mediaSecondary, p.surface, p.alpha);  // beauty alone without AOVs
    }
    void reset() {
        if (plain)
            plain->reset();
        else
            *layers = LayerAccumulator(layers->beauty().width(), layers->beauty().height(), layers->aov(),
                                       layers->transparent());
    }
};

/// A pass's images as one float block for the gather: beauty, then (AOV) media primary, media
/// secondary, surface, then (transparent film) the alpha.
std::vector<float> pack(const PassLayers& p, bool aov, bool transparent) {
    std::vector<const Image*> images = {&p.beauty};
    if (aov) images.insert(images.end(), {&p.mediaPrimary, &p.mediaSecondary, &p.surface});
    if (transparent) images.push_back(&p.alpha);
    std::vector<float> out;
    out.reserve(p.beauty.pixels.size() * 3 * images.size());
    for (const Image* image : images)
        for (const Rgb& c : image->pixels) out.insert(out.end(), {c.r, c.g, c.b});
    return out;
}

PassLayers unpack(const float* data, int w, int h, bool aov, bool transparent) {
    auto image = [&](int i) {
        Image img(w, h);
        const float* d = data + size_t(i) * img.pixels.size() * 3;
        for (size_t k = 0; k < img.pixels.size(); ++k) img.pixels[k] = Rgb(d[3 * k], d[3 * k + 1], d[3 * k + 2]);
        return img;
    };
    PassLayers p;
    p.beauty = image(0);
    if (aov) p.mediaPrimary = image(1), p.mediaSecondary = image(2), p.surface = image(3);
    if (transparent) p.alpha = image(aov ? 4 : 1);
    return p;
}
}  // namespace

/// One call of run(): the passes handed out, in flight and added.
class PassScheduler::Run {
public:
    Run(PassScheduler& s, PassRenderer& renderer, PassSink sink, uint64_t firstPass, RenderDisplay& display,
        const PassDistribution& ranks)
        : m_s(s), m_renderer(renderer), m_settings(renderer.settings()), m_sink(sink), m_display(display),
          m_ranks(ranks), m_first(firstPass), m_next(firstPass) {}
    RenderProgress go();

private:
    /// Passes in the next round (rank 0 decides, every rank hears): 0 = no more.
    uint64_t planRound();
    /// One process: starts the next pass (finishing older ones to make room for it).
    DisplayCommand startPass();
    /// Several processes: this rank's pass of a round of `n`, gathered and added on rank 0.
    DisplayCommand distributedRound(uint64_t n);
    /// The CPU stages of a GL pass before its splats: the first photon batch and the primary
    /// segments. False when abandoned.
    bool traceGlFirst(PassFlight& f);
    /// Each photon batch's splat submitted to GL, its secondary stage on the CPU, the next traced.
    void traceGlBatches(PassFlight& f);
    /// The whole pass on the CPU; abandoned between stages on a reset or exit when `abandonable`.
    void renderOnCpu(PassFlight& f, bool abandonable);
    DisplayCommand finishOldest();
    /// The finished pass of `f`: the GL splats collected, or (GL failed) rendered on the CPU.
    PassLayers complete(PassFlight& f);
    DisplayCommand add(const PassLayers& pass, uint64_t index, const PassStats& stats);
    bool interrupted() const { return m_s.m_resetRequested.load() || m_s.m_exitRequested.load(); }
    void discardFlights();
    void restart();

    PassScheduler& m_s;
    PassRenderer& m_renderer;
    const RenderSettings& m_settings;
    PassSink m_sink;
    RenderDisplay& m_display;
    const PassDistribution& m_ranks;
    const uint64_t m_first;
    uint64_t m_next;
    bool m_stopped = false;
    std::deque<PassFlight> m_flights;
    // The GL pass between traceGlFirst and traceGlBatches.
    std::shared_ptr<const PhotonMap> m_photons;
    std::shared_ptr<const PrimaryPass> m_primary;
    CameraPassStats m_camera;
    RenderProgress m_progress;
    Clock::time_point m_start = Clock::now();
};

RenderProgress PassScheduler::Run::go() {
    try {
        for (;;) {
            const uint64_t n = planRound();
            if (n == 0 && (m_stopped || m_flights.empty())) break;
            DisplayCommand command = n == 0 ? finishOldest() : m_ranks.distributed() ? distributedRound(n) : startPass();
            if (m_s.m_resetRequested.exchange(false) && command == DisplayCommand::Continue)
                command = DisplayCommand::Reset;
            if (m_s.m_exitRequested) command = DisplayCommand::Exit;
            if (command == DisplayCommand::Exit || (command == DisplayCommand::Reset && m_ranks.distributed()))
                m_stopped = true;
            else if (command == DisplayCommand::Reset)
                restart();
        }
    } catch (...) {
        discardFlights();
        throw;
    }
    discardFlights();
    m_s.m_exitRequested = false;
    return m_progress;
}

uint64_t PassScheduler::Run::planRound() {
    std::vector<uint64_t> plan{0};
    if (m_ranks.rank() == 0 && !m_stopped) {
        const uint64_t ranks = uint64_t(m_ranks.size());
        if (m_settings.timeBudget > 0)
            plan[0] = secondsSince(m_start) < m_settings.timeBudget ? ranks : 0;
        else
            plan[0] = std::min(ranks, m_settings.passes - std::min(m_settings.passes, m_next - m_first));
    }
    m_ranks.broadcast(plan);
    return plan[0];
}

DisplayCommand PassScheduler::Run::startPass() {
    PassFlight f;
    f.pass = m_next++;
    f.gl = m_s.m_glUsable;
    if (!f.gl) {
        // Nothing overlaps: the pass is finished at once (unless the loop is about to throw it away).
        renderOnCpu(f, true);
        if (interrupted()) return DisplayCommand::Continue;
        m_s.m_peakPassesHeld = std::max(m_s.m_peakPassesHeld, int(m_flights.size()) + 1);
        m_flights.push_back(std::move(f));
        return finishOldest();
    }
    if (!traceGlFirst(f)) return DisplayCommand::Continue;
    m_s.m_peakPassesHeld = std::max(m_s.m_peakPassesHeld, int(m_flights.size()) + 1);
    while (int(m_flights.size()) >= m_s.m_options.queueDepth) {
        DisplayCommand command = finishOldest();
        if (command != DisplayCommand::Continue) return command;  // the pass is dropped at the loop's boundary
    }
    traceGlBatches(f);
    m_flights.push_back(std::move(f));
    return DisplayCommand::Continue;
}

DisplayCommand PassScheduler::Run::distributedRound(uint64_t n) {
    const uint64_t r = uint64_t(m_ranks.rank());
    const bool aov = m_sink.aov();
    const int w = m_settings.width, h = m_settings.height;
    std::vector<float> mine, all;
    PassStats stats;
    if (r < n) {
        PassFlight f;
        f.pass = m_next + r;
        f.gl = m_s.m_glUsable;
        if (!f.gl)
            renderOnCpu(f, false);
        else if (traceGlFirst(f))
            traceGlBatches(f);
        mine = pack(complete(f), aov, m_sink.transparent());
        stats = f.stats;
    } else {
        mine.assign(size_t(w) * h * 3 * (aov ? 4 : 1), 0.0f);
    }
    std::vector<uint64_t> counts{stats.photonPaths, stats.beams}, allCounts;
    m_ranks.gather(mine, &all);
    m_ranks.gather(counts, &allCounts);
    DisplayCommand command = DisplayCommand::Continue;
    if (m_ranks.rank() == 0)
        for (uint64_t k = 0; k < n; ++k) {
            PassStats s;
            s.photonPaths = allCounts[2 * k];
            s.beams = allCounts[2 * k + 1];
            if (add(unpack(all.data() + k * mine.size(), w, h, aov, m_sink.transparent()), m_next + k, s) != DisplayCommand::Continue)
                command = DisplayCommand::Exit;  // after the round: every rank hears it at the next plan
        }
    m_next += n;
    return command;
}

bool PassScheduler::Run::traceGlFirst(PassFlight& f) {
    auto t0 = Clock::now();
    m_photons = std::make_shared<const PhotonMap>(m_renderer.tracePhotons(f.pass, 0));
    f.stats.add(*m_photons);
    f.stats.photonSeconds = secondsSince(t0);
    if (interrupted()) return false;
    auto t1 = Clock::now();
    m_primary = std::make_shared<const PrimaryPass>(m_renderer.tracePrimary(f.pass));
    m_camera = CameraPassStats();
    m_camera.rays = m_primary->rays;
    f.stats.cameraSeconds = secondsSince(t1);
    return !interrupted();
}

void PassScheduler::Run::traceGlBatches(PassFlight& f) {
    // The GL side splats batch b while the CPU gathers it and traces batch b + 1, so at most two
    // batches are held (MemoryPlan::kBatchesHeld); each is freed once both sides are done with it.
    const uint32_t batches = m_renderer.memoryPlan().batches;
    const bool layers = m_sink.aov();
    for (uint32_t batch = 0; m_s.m_glUsable;) {  // GL failed meanwhile: complete() renders it on the CPU
        auto t2 = Clock::now();
        while (!f.splats.empty()) f.collectSplat();  // the batch before last is freed
        f.splats.push_back(m_s.submitSplat(f.pass, m_primary, m_photons));
        SecondaryLayers secondary;
        addBatch(f.image.beauty,
                 m_renderer.traceSecondary(*m_primary, *m_photons, &m_camera, batch == 0, layers ? &secondary : nullptr,
                                           m_renderer.settings().transparentFilm ? &f.image.alpha : nullptr));
        if (layers) {
            addBatch(f.image.mediaPrimary, std::move(secondary.mediaPrimary));  // the GL splat adds its beams
            addBatch(f.image.mediaSecondary, std::move(secondary.media));
            addBatch(f.image.surface, std::move(secondary.surface));
        }
        f.stats.cameraSeconds += secondsSince(t2);
        m_photons.reset();
        if (++batch == batches || interrupted()) break;
        auto t4 = Clock::now();
        m_photons = std::make_shared<const PhotonMap>(m_renderer.tracePhotons(f.pass, batch));
        f.stats.add(*m_photons);
        f.stats.photonSeconds += secondsSince(t4);
    }
    f.stats.add(m_camera);
    m_photons.reset();
    m_primary.reset();
}

void PassScheduler::Run::renderOnCpu(PassFlight& f, bool abandonable) {
    f.gl = false;
    f.stats = PassStats();
    std::function<bool()> abandon;
    if (abandonable) abandon = [this] { return interrupted(); };
    f.image = m_renderer.renderPass(f.pass, m_sink.aov(), &f.stats, abandon);
}

DisplayCommand PassScheduler::Run::finishOldest() {
    PassFlight f = std::move(m_flights.front());
    m_flights.pop_front();
    PassLayers image = complete(f);
    return add(image, f.pass, f.stats);
}

PassLayers PassScheduler::Run::complete(PassFlight& f) {
    if (!f.gl) return std::move(f.image);
    if (m_s.m_glUsable) {
        try {
            return f.finishGl();
        } catch (...) {
            m_display.notice(m_s.glFailed(f.pass, std::current_exception()));
        }
    }
    f.waitSplats();
    renderOnCpu(f, false);
    return std::move(f.image);
}

DisplayCommand PassScheduler::Run::add(const PassLayers& pass, uint64_t index, const PassStats& stats) {
    m_sink.add(pass);
    m_progress.totals += stats;
    m_progress.pass = index;
    m_progress.passesDone++;
    m_progress.elapsedSeconds = secondsSince(m_start);
    return m_display.passAdded(m_sink.beauty(), m_progress);
}

void PassScheduler::Run::discardFlights() {
    // Their splats still finish first: they read the flights' inputs.
    for (PassFlight& f : m_flights) f.waitSplats();
    m_flights.clear();
}

void PassScheduler::Run::restart() {
    discardFlights();
    m_sink.reset();
    m_display.restarting();
    m_renderer.sceneChanged();
    m_s.reloadMedia();
    m_next = m_first;
    m_progress = RenderProgress();
    m_start = Clock::now();
}

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
    if (!m_gl || m_glFailed) return;
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

std::future<std::pair<Image, double>> PassScheduler::submitSplat(uint64_t pass,
                                                                 std::shared_ptr<const PrimaryPass> primary,
                                                                 std::shared_ptr<const PhotonMap> photons) {
    return m_gl->submit([this, pass, primary = std::move(primary), photons = std::move(photons)](GlContext&) mutable {
        auto t = Clock::now();
        if (m_options.hooks && m_options.hooks->failGlSplat(pass)) throw Error("GL context lost (planted by a test)");
        Image image = m_splatter->splat(primary->segments, *photons);
        photons.reset();  // free the batch now, not when the future is read
        return std::make_pair(std::move(image), secondsSince(t));
    });
}

std::string PassScheduler::glFailed(uint64_t pass, const std::exception_ptr& error) {
    std::string what = "unknown error";
    try {
        std::rethrow_exception(error);
    } catch (const std::exception& e) {
        what = e.what();
    } catch (...) {
    }
    m_glUsable = false;
    m_glFailed = true;
    return "the GL splat failed at pass " + std::to_string(pass + 1) + " (" + what +
           "): that pass and the rest render on the CPU; the " + std::to_string(pass) + " passes before it are kept";
}

RenderProgress PassScheduler::run(PassRenderer& renderer, Accumulator& acc, uint64_t firstPass,
                                  RenderDisplay& display) {
    bind(renderer.scene());
    m_peakPassesHeld = 0;
    PassSink sink;
    sink.plain = &acc;
    return Run(*this, renderer, sink, firstPass, display, PassDistribution::single()).go();
}

RenderProgress PassScheduler::run(PassRenderer& renderer, LayerAccumulator& layers, uint64_t firstPass,
                                  RenderDisplay& display, const PassDistribution& ranks) {
    bind(renderer.scene());
    m_peakPassesHeld = 0;
    PassSink sink;
    sink.layers = &layers;
    return Run(*this, renderer, sink, firstPass, display, ranks).go();
}

}  // namespace tyndall
