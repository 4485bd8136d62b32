#pragma once
// The accumulators of one render: the beauty image always; with AOV layers also its three
// components (media seen directly, media seen through mirrors and glass, surfaces) and the
// squares of the beauty passes, from which the variance layer is estimated. Everything is a
// double-sum Accumulator, so the whole state goes into a checkpoint or across MPI ranks as is.
#include <string>
#include <utility>
#include <vector>

#include "core/accumulator.h"
#include "core/image_io.h"

namespace tyndall {

class LayerAccumulator {
public:
    /// `transparent`: the transparent film's alpha is kept too (a last layer, "alpha").
    LayerAccumulator(int width, int height, bool aov, bool transparent = false);

    /// Adds a pass without components (aov() must be false).
    void addPass(const Image& beauty);
    /// Adds a pass and its components (with aov(); without, only `beauty` is kept) and, with
    /// transparent(), its alpha (PassLayers::alpha).
    void addPass(const Image& beauty, const Image& mediaPrimary, const Image& mediaSecondary, const Image& surface,
                 const Image& alpha = Image());

    bool aov() const { return m_aov; }
    bool transparent() const { return m_transparent; }
    /// The mean alpha (its r channel), transparent() only.
    Image alpha() const { return m_layers.back().second.mean(); }
    const Accumulator& beauty() const { return m_layers[0].second; }
    uint64_t passCount() const { return beauty().passCount(); }

    /// The EXR layers after the beauty image: media_primary, media_secondary, surface, variance
    /// (empty without aov()). variance = the unbiased sample variance of the pass images divided
    /// by the pass count: the estimated variance of the running mean (0 before two passes).
    ImageLayers imageLayers() const;

    /// Named accumulators ("beauty", then with AOVs "media_primary", "media_secondary",
    /// "surface", "beauty_squares", then with a transparent film "alpha") for checkpoints and MPI.
    const std::vector<std::pair<std::string, Accumulator>>& named() const { return m_layers; }
    /// Rebuilds from named(); Error when a layer is missing or the sizes or pass counts differ.
    static LayerAccumulator fromNamed(std::vector<std::pair<std::string, Accumulator>> layers, bool aov,
                                      const std::string& where, bool transparent = false);

private:
    bool m_aov = false;
    bool m_transparent = false;
    std::vector<std::pair<std::string, Accumulator>> m_layers;
};

}  // namespace tyndall
