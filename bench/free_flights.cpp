#include "bench/free_flights.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>

#include "app/stage_rates.h"
#include "core/rng.h"
#include "core/timing.h"
#include "cpu/free_flight.h"

namespace tyndall::bench {

namespace {

/// A density grid seen through a looser majorant, counting density lookups per thread.
class MajorantView : public DensityGrid {
public:
    MajorantView(std::shared_ptr<const DensityGrid> grid, MajorantMode mode) : m_grid(std::move(grid)), m_mode(mode) {}
    float density(const Vec3& p) const override {
        if (m_counting) ++m_lookups.local();
        return m_grid->density(p);
    }
    Bounds3 bounds() const override { return m_grid->bounds(); }
    float majorant(const Ray& ray) const override {
        return m_mode == MajorantMode::Global ? m_grid->maxDensity() : m_grid->majorant(ray);
    }
    const MajorantGrid* majorantGrid() const override {
        return m_mode == MajorantMode::Grid ? m_grid->majorantGrid() : nullptr;
    }
    float maxDensity() const override { return m_grid->maxDensity(); }
    float meanDensity() const override { return m_grid->meanDensity(); }
    void setCounting(bool on) { m_counting = on; }
    uint64_t lookups() const {
        uint64_t n = 0;
        for (uint64_t c : m_lookups) n += c;
        return n;
    }

private:
    std::shared_ptr<const DensityGrid> m_grid;
    MajorantMode m_mode;
    bool m_counting = false;
    mutable tbb::enumerable_thread_specific<uint64_t> m_lookups{0};
};
}  // namespace

FreeFlightRate measureFreeFlights(const PassRenderer& renderer, uint64_t samples, MajorantMode mode, int perSegment) {
    perSegment = std::clamp(perSegment, 1, kMaxFreeFlights);
    const Scene& scene = renderer.scene();
    PhotonMap photons = renderer.tracePhotons(0);
    CameraPassResult camera = renderer.traceCamera(0, photons);
    std::vector<PrimaryRay> rays;
    for (const PrimaryRay& r : camera.primary.rays)
        if (r.medium != kVacuum && r.tMax > 0 && !scene.media[r.medium].homogeneous()) rays.push_back(r);
    FreeFlightRate rate;
    rate.segments = rays.size();
    if (rays.empty()) return rate;

    // Every mode reads the grid through the same view (one extra virtual call each), so the timings
    // compare the majorants alone; lookups are counted in a second, untimed run.
    std::vector<Medium> media = scene.media;
    std::vector<std::shared_ptr<MajorantView>> views(media.size());
    for (size_t i = 0; i < media.size(); ++i) {
        if (media[i].homogeneous()) continue;
        views[i] = std::make_shared<MajorantView>(media[i].density, mode);
        media[i].density = views[i];
    }
    auto sampleRange = [&](const std::vector<Medium>& m, uint64_t begin, uint64_t end) {
        float sink = 0, d[kMaxFreeFlights];
        for (uint64_t i = begin; i < end; i += uint64_t(perSegment)) {
            const PrimaryRay& r = rays[(i * 7919) % rays.size()];
            Rng rng = Rng::forKey(7, 0, i, StreamPurpose::Transmittance);
            if (perSegment == 1) {
                d[0] = sampleCollisionDistance(m[r.medium], Ray{r.origin, r.dir}, r.tMax, rng);
            } else {
                sampleCollisionDistances(m[r.medium], Ray{r.origin, r.dir}, r.tMax, rng, perSegment, d);
            }
            for (int k = 0; k < perSegment; ++k) sink += d[k] < kInfinity ? d[k] : 0.0f;
        }
        return sink;
    };
    samples = (samples + uint64_t(perSegment) - 1) / uint64_t(perSegment) * uint64_t(perSegment);
    const uint64_t block = 1024 * uint64_t(perSegment), blocks = (samples + block - 1) / block;
    auto t0 = Clock::now();
    tbb::parallel_for(uint64_t(0), blocks, [&](uint64_t b) {
        volatile float sink = sampleRange(media, b * block, std::min(samples, (b + 1) * block));
        (void)sink;
    });
    double seconds = secondsSince(t0);
    rate.samplesPerSecond = double(samples) / seconds;

    for (const auto& v : views)
        if (v) v->setCounting(true);
    const uint64_t counted = std::min<uint64_t>(samples, 200000 / block * block + block);
    tbb::parallel_for(uint64_t(0), (counted + block - 1) / block, [&](uint64_t b) {
        volatile float sink = sampleRange(media, b * block, std::min(counted, (b + 1) * block));
        (void)sink;
    });
    uint64_t lookups = 0;
    for (const auto& v : views)
        if (v) lookups += v->lookups();
    rate.densityLookupsPerSample = double(lookups) / double(counted);
    return rate;
}

}  // namespace tyndall::bench
