#include "core/layer_accumulator.h"

#include <algorithm>

#include "core/error.h"

namespace tyndall {

namespace {
const char* const kAovNames[] = {"beauty", "media_primary", "media_secondary", "surface", "beauty_squares"};
}

LayerAccumulator::LayerAccumulator(int width, int height, bool aov, bool transparent)
    : m_aov(aov), m_transparent(transparent) {
    for (int i = 0; i < (aov ? 5 : 1); ++i) m_layers.emplace_back(kAovNames[i], Accumulator(width, height));
    if (transparent) m_layers.emplace_back("alpha", Accumulator(width, height));
}

void LayerAccumulator::addPass(const Image& beauty) {
    TYNDALL_CHECK(!m_aov && !m_transparent, "an AOV render or a transparent film needs the pass's components");
    m_layers[0].second.addPass(beauty);
}

void LayerAccumulator::addPass(const Image& beauty, const Image& mediaPrimary, const Image& mediaSecondary,
                               const Image& surface, const Image& alpha) {
    m_layers[0].second.addPass(beauty);
    if (m_transparent) {
        TYNDALL_CHECK(alpha.width == beauty.width && alpha.height == beauty.height, "a transparent film needs the pass's alpha");
        m_layers.back().second.addPass(alpha);
    }
    if (!m_aov) return;
    m_layers[1].second.addPass(mediaPrimary);
    m_layers[2].second.addPass(mediaSecondary);
    m_layers[3].second.addPass(surface);
    Image squares = beauty;
    for (Rgb& p : squares.pixels) p = p * p;
    m_layers[4].second.addPass(squares);
}

ImageLayers LayerAccumulator::imageLayers() const {
    ImageLayers out;
    if (!m_aov) return out;
    for (int i = 1; i <= 3; ++i) out.emplace_back(m_layers[i].first, m_layers[i].second.mean());
    const Accumulator& sum = m_layers[0].second;
    const Accumulator& sq = m_layers[4].second;
    Image variance(sum.width(), sum.height());
    const double n = double(sum.passCount());
    if (n >= 2) {
        for (int y = 0; y < sum.height(); ++y)
            for (int x = 0; x < sum.width(); ++x)
                for (int c = 0; c < 3; ++c) {
                    double m = sum.meanAt(x, y, c), m2 = sq.meanAt(x, y, c);
                    variance.at(x, y)[c] = float(std::max(0.0, (m2 - m * m) * n / (n - 1)) / n);
                }
    }
    out.emplace_back("variance", std::move(variance));
    return out;
}

LayerAccumulator LayerAccumulator::fromNamed(std::vector<std::pair<std::string, Accumulator>> layers, bool aov,
                                             const std::string& where, bool transparent) {
    const size_t count = (aov ? 5 : 1) + (transparent ? 1 : 0);
    if (layers.size() != count)
        throw Error(where + ": holds " + std::to_string(layers.size()) + " layers, expected " + std::to_string(count) +
                    (aov ? " (an --aov render)" : "") + (transparent ? " (a transparent film)" : ""));
    for (size_t i = 0; i < count; ++i) {
        const char* name = transparent && i + 1 == count ? "alpha" : kAovNames[i];
        if (layers[i].first != name)
            throw Error(where + ": layer " + std::to_string(i) + " is '" + layers[i].first + "', expected '" + name +
                        "'");
        const Accumulator &a = layers[i].second, &b = layers[0].second;
        if (a.width() != b.width() || a.height() != b.height() || a.passCount() != b.passCount())
            throw Error(where + ": layer '" + layers[i].first + "' does not match the beauty layer");
    }
    LayerAccumulator acc(1, 1, false);
    acc.m_aov = aov;
    acc.m_transparent = transparent;
    acc.m_layers = std::move(layers);
    return acc;
}

}  // namespace tyndall
