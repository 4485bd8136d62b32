#pragma once
// Emissive media as a photon source (PPB step 1): photons leave the fire. A medium with source term
// sigma_a(p) Le(p) (core/medium.h) emits, from each volume element, power 4 pi sigma_a Le dV,
// isotropically. Built once per scene (PhotonTracer's constructor):
//   - each emissive medium's box: its density grid's bounds (grid media) or the bounds of the
//     meshes it fills (all of the scene for the global medium), clipped to the scene's bounds;
//   - a lattice of at most kMaxCells cells over the box, each weighted by the luminance of the
//     source term at its centre; a cell is chosen with probability 0.9 w / sum(w) + 0.1 / cells
//     (the uniform part reaches every cell, so emission the centres miss is still sampled);
//   - a uniform point in the cell, an isotropic direction.
// The photon's power is 4 pi sigma_a(x) Le(x) / pdf(x), pdf(x) = P(medium) P(cell) / V(cell), and
// 0 where x is not in that medium (EmbreeScene::mediumAt, asked only when the scene has
// medium-bounding meshes): its mean over photons is the integral of 4 pi sigma_a Le over where
// the medium is, whatever the lattice. Media are chosen by the luminance of their estimated power
// (each at least 1e-3 of the largest). Safe to call from many threads.
#include <vector>

#include "core/rng.h"
#include "cpu/embree_scene.h"

namespace tyndall {

class MediumEmitters {
public:
    static constexpr size_t kMaxCells = size_t(1) << 18;

    explicit MediumEmitters(const EmbreeScene& rt);

    bool empty() const { return m_sources.empty(); }
    /// Estimated power of all emissive media together (W): what the light choice weighs.
    Rgb estimatedPower() const { return m_estimatedPower; }

    struct Photon {
        Ray ray;  ///< origin in the medium, isotropic unit direction
        Rgb power;  ///< 4 pi sigma_a Le / pdf (0 outside the medium's region)
        MediumId medium = kVacuum;
    };
    /// One photon start; draws five uniforms from `rng`. Requires !empty().
    Photon sample(Rng& rng) const;

private:
    struct Source {
        MediumId medium;
        Bounds3 box;
        int res[3];
        Vec3 cellSize;
        float cellVolume;
        std::vector<double> cdf;  // over cells, of the weighted part; empty = uniform only
        double uniformShare;      // probability of the uniform part
    };
    const EmbreeScene& m_rt;
    std::vector<Source> m_sources;
    std::vector<double> m_sourceCdf;
    Rgb m_estimatedPower;
    bool m_regionTest = false;
};

}  // namespace tyndall
