#pragma once
// The CPU twin of the GL splatter: adds the medium radiance along every pixel's primary segment
// from all beams of the pass, by tiled rasterization instead of ray queries. Each beam's screen
// footprint (its segment clipped to the view frustum widened by radius + lens, projected and
// dilated by the projected radius, the lens's circle of confusion and one pixel of jitter) is
// binned to 16x16 tiles; each tile walks, per row, the pixels inside that footprint and evaluates
// the exact beam x ray estimator against the pixel's stored primary ray. Beams are visited in index
// order inside a tile, so the result is independent of the thread count.
#include <cstdint>

#include "core/image.h"
#include "core/photon_beam.h"
#include "core/primary_segments.h"
#include "core/scene.h"

namespace tyndall {

struct RasterStats {
    uint64_t pixelTests = 0;  ///< beam x pixel estimator evaluations
    uint64_t binned = 0;      ///< beam x tile entries
};

/// Screen-space bound of one beam: the 2D capsule (a, b, radius) in film pixels, or the whole
/// film when the beam passes too close to the camera to project safely.
struct BeamFootprint {
    float ax = 0, ay = 0, bx = 0, by = 0;
    float radius = 0;
    bool fullScreen = false;
    bool visible = false;
};

BeamFootprint beamFootprint(const Camera& camera, int width, int height, const PhotonBeam& beam);

class BeamRasterizer {
public:
    explicit BeamRasterizer(const Scene& scene) : m_scene(scene) {}

    Image rasterize(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats = nullptr) const;

    /// Reference for tests: every beam against every pixel, no culling.
    Image bruteForce(const PrimarySegments& primary, const PhotonMap& photons) const;

private:
    Rgb pixelRadiance(const PrimarySegments& primary, size_t pixel, const PhotonMap& photons, uint32_t beam) const;

    const Scene& m_scene;
};

}  // namespace tyndall
