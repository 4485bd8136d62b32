#include "app/render_rounds.h"

#include <chrono>

namespace tyndall::app {

namespace {
/// A pass's images as one float block: beauty, then (AOV) media primary, media secondary, surface.
void pack(const PassLayers& layers, bool aov, std::vector<float>* out) {
    const Image* images[4] = {&layers.beauty, &layers.mediaPrimary, &layers.mediaSecondary, &layers.surface};
    out->clear();
    for (int i = 0; i < (aov ? 4 : 1); ++i)
        for (const Rgb& p : images[i]->pixels) out->insert(out->end(), {p.r, p.g, p.b});
}
Image unpack(const float* data, int w, int h) {
    Image img(w, h);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = Rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
    return img;
}
}  // namespace

RenderProgress renderRounds(const PassRenderer& renderer, LayerAccumulator& acc, uint64_t firstPass,
                            RoundLimits limits, const Ranks& ranks, const PassAddedFn& passAdded) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
    const int w = renderer.settings().width, h = renderer.settings().height;
    const size_t block = size_t(w) * h * 3 * (acc.aov() ? 4 : 1);
    const uint64_t K = uint64_t(ranks.size());
    RenderProgress progress;
    bool stop = false;
    std::vector<float> mine, all;
    std::vector<uint64_t> counts(2), allCounts;
    for (uint64_t next = firstPass;;) {
        std::vector<uint64_t> round{0};
        if (ranks.rank() == 0 && !stop) {
            if (limits.seconds > 0)
                round[0] = elapsed() < limits.seconds ? K : 0;
            else
                round[0] = std::min<uint64_t>(K, firstPass + limits.passes - next);
        }
        ranks.broadcast(round);
        if (round[0] == 0) break;
        const uint64_t r = uint64_t(ranks.rank());
        PassStats stats;
        if (r < round[0]) {
            if (acc.aov()) {
                pack(renderer.renderPassLayers(next + r, &stats), true, &mine);
            } else {
                PassLayers beauty;
                beauty.beauty = renderer.renderPass(next + r, &stats);
                pack(beauty, false, &mine);
            }
        } else {
            mine.assign(block, 0.0f);
        }
        counts = {stats.photonPaths, stats.beams};
        ranks.gather(mine, &all);
        ranks.gather(counts, &allCounts);
        if (ranks.rank() == 0) {
            for (uint64_t k = 0; k < round[0]; ++k) {
                const float* p = all.data() + k * block;
                const size_t img = size_t(w) * h * 3;
                if (acc.aov())
                    acc.addPass(unpack(p, w, h), unpack(p + img, w, h), unpack(p + 2 * img, w, h),
                                unpack(p + 3 * img, w, h));
                else
                    acc.addPass(unpack(p, w, h));
                progress.pass = next + k;
                progress.passesDone++;
                progress.totals.photonPaths += allCounts[2 * k];
                progress.totals.beams += allCounts[2 * k + 1];
                progress.elapsedSeconds = elapsed();
                if (passAdded && !passAdded(acc, progress)) stop = true;
            }
        }
        next += round[0];
    }
    progress.elapsedSeconds = elapsed();
    return progress;
}

}  // namespace tyndall::app
