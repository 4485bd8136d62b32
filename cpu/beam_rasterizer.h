#pragma once
// The CPU twin of the GL splatter: adds the medium radiance along every pixel's primary segment
// from all beams of the pass, by rasterization instead of ray queries.
//
// Each beam's screen footprint is a tapered capsule: its axis clipped to the view frustum widened
// by radius + lens radius, projected, with a radius at each end that bounds the projected beam
// radius there (f r / (z - r), stretched by 1/cos of the off-axis angle), plus the lens's circle
// of confusion and 0.75 px for the film jitter. The projected radius is convex in screen space
// (1/z is linear there), so the linear taper is conservative. Beams are binned to bands of rows;
// each band finds a beam's exact capsule span on all its rows at once (footprintBandColumns, a
// row per SIMD lane) and evaluates the estimator against each pixel's stored primary ray in
// them. Beams are visited in index order inside a band, so the result does not depend on the
// thread count.
//
// Two kernels evaluate the estimator along a row span: the scalar one (BeamPixelEvaluator, the
// definition, one pixel at a time) and the SIMD one (cpu/beam_splat_simd.h: 8 or 16 pixels per
// instruction, the same arithmetic but for a vectorised exp; ~1e-7 relative from the scalar one).
// Both find exactly the same beam x pixel pairs.
#include <cstdint>

#include "core/camera.h"
#include "core/image.h"
#include "core/photon_beam.h"
#include "core/primary_segments.h"
#include "core/scene.h"

namespace tyndall {

struct RasterStats {
    uint64_t pixelTests = 0;  ///< beam x pixel estimator evaluations
    uint64_t binned = 0;      ///< beam x band entries

    RasterStats& operator+=(const RasterStats& o);
};

/// Screen-space bound of one beam, in film pixels: the convex hull of the discs (a, ra) and
/// (b, rb), or the whole film when the beam passes too close to the camera to project safely.
struct BeamFootprint {
    float ax = 0, ay = 0, ra = 0;
    float bx = 0, by = 0, rb = 0;
    bool fullScreen = false;
    bool visible = false;
};

BeamFootprint beamFootprint(const Camera& camera, int width, int height, const PhotonBeam& beam);

/// The x-interval [x0, x1] where the horizontal line at `y` crosses the footprint; false if it
/// misses. For a full-screen footprint, the whole line. The definition of a footprint's rows: the
/// rasterizer computes a band's rows at once (footprintBandColumns, cpu/beam_splat_simd.h), with
/// the same float operations.
bool footprintRowSpan(const BeamFootprint& fp, float y, float* x0, float* x1);

/// The straight sides of a footprint's hull (the tangents common to its two discs), which every
/// row's span needs: computed once per beam. `quad` runs a's side 0 point, b's side 0 point, b's
/// side 1 point, a's side 1 point.
struct FootprintSides {
    bool present = false;  ///< false when one disc holds the other (no straight sides)
    float quad[4][2] = {};
};

FootprintSides footprintSides(const BeamFootprint& fp);

/// Which estimator kernel the rasterizer runs (RenderSettings::simd, `--simd on|off`).
enum class SplatKernel { Scalar, Simd };

class BeamRasterizer {
public:
    explicit BeamRasterizer(const Scene& scene, SplatKernel kernel = SplatKernel::Simd)
        : m_scene(scene), m_kernel(kernel) {}

    /// The primary segments' media radiance of `photons`' beams; adds its counts to `stats`.
    Image rasterize(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats = nullptr) const;

    /// Reference for tests: every beam against every pixel, no culling.
    /// Always the scalar kernel: the definition the other paths are tested against.
    Image bruteForce(const PrimarySegments& primary, const PhotonMap& photons) const;

    SplatKernel kernel() const { return m_kernel; }

private:
    const Scene& m_scene;
    SplatKernel m_kernel;
};

}  // namespace tyndall
