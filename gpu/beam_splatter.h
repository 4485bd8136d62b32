#pragma once
// The GL beam splatter: the primary-segment medium radiance of a pass (PPB step 3) on OpenGL, the
// twin of the CPU BeamRasterizer (cpu/beam_rasterizer.h) with the same inputs and output.
//
// Every photon beam is drawn as one camera-facing billboard: the film-space rectangle around its
// footprint capsule (gpu/shaders/beam_footprint.glsl, the twin of beamFootprint(): conservative
// for beams end-on, beams passing by or behind the camera, and the thin lens). The fragment
// shader reads its pixel's stored primary ray (origin, direction, tMax = distance to the first
// surface, medium, stored free flights) and evaluates the exact beam x ray estimator
// (gpu/shaders/beam_estimator.glsl, twin of core/beam_estimator.h); results are blended
// additively (ONE, ONE) into an RGBA32F target. Occlusion is the ray's tMax, never a depth buffer.
// Primitives are blended in beam order, as the CPU rasterizer sums them, so the two agree up to
// float rounding (llvmpipe's fp32 blending is exact).
//
// Media: homogeneous media analytically; grid media through their dense volume
// (core/density_volume.h), sampled in GLSL by the same trilinear rule. A grid without a dense
// form makes the constructor throw (the caller keeps the splat on the CPU).
//
// Threading: one thread, the GL context's; the context and the scene must outlive the splatter.
#include <cstdint>
#include <memory>

#include "core/image.h"
#include "core/photon_beam.h"
#include "core/primary_segments.h"
#include "core/scene.h"
#include "gpu/gl_context.h"

namespace tyndall {

struct GlSplatStats {
    double uploadSeconds = 0;    ///< rays, free flights, beams into storage buffers
    double drawSeconds = 0;      ///< the draw, to glFinish
    double readbackSeconds = 0;  ///< glReadPixels and conversion to an Image
    uint64_t fragments = 0;      ///< fragment shader invocations (when counting, see countFragments)
    uint64_t beams = 0;

    GlSplatStats& operator+=(const GlSplatStats& o);
};

class GlBeamSplatter {
public:
    /// Compiles the shaders and uploads the scene's media. Throws Error when the context lacks
    /// what the splatter needs or a grid medium has no dense volume.
    GlBeamSplatter(GlContext& context, const Scene& scene);
    ~GlBeamSplatter();
    GlBeamSplatter(const GlBeamSplatter&) = delete;
    GlBeamSplatter& operator=(const GlBeamSplatter&) = delete;

    /// Re-uploads the scene's media after they changed (the camera is read at every splat).
    void reloadMedia();

    /// The primary-segment media radiance of one pass: `primary` as traced with the scene's
    /// current camera, `photons` the pass's beams. Same size as `primary`.
    Image splat(const PrimarySegments& primary, const PhotonMap& photons, GlSplatStats* stats = nullptr);

    /// Counts fragment shader invocations into GlSplatStats::fragments (a pipeline-statistics
    /// query; false when the driver has none).
    bool countFragments(bool on);

    /// Largest total voxel count of the dense volumes (the storage-buffer size limit).
    size_t maxVoxels() const { return m_maxVoxels; }

private:
    struct Buffers;
    void resizeTarget(int width, int height);

    GlContext& m_context;
    const GlFunctions& m_gl;
    const Scene& m_scene;
    size_t m_maxVoxels = 0;
    bool m_canCountFragments = false;
    bool m_countFragments = false;
    std::unique_ptr<Buffers> m_buffers;
};

}  // namespace tyndall
