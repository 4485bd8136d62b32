#pragma once
// Camera paths (PPB step 2 and the CPU half of step 3/4): one jittered path per pixel per pass.
// The first segment (camera -> first surface) is the primary segment: it is only recorded here,
// and its medium radiance is added by a beam splatter (CPU rasterizer or GL). The path continues
// through mirrors and glass (Fresnel choice); every later segment inside a medium gathers the
// pass's beams through the BeamBvh; a diffuse hit ends the path with the surface-photon estimate;
// emissive surfaces add their emission.
//
// Deterministic: pixel p of pass i draws its film/lens jitter from Rng::forKey(seed, i, p,
// PixelJitter) and the rest of its path from (seed, i, p, CameraPath).
#include <cstdint>

#include "core/image.h"
#include "core/photon_beam.h"
#include "core/primary_segments.h"
#include "core/settings.h"
#include "cpu/beam_bvh.h"
#include "cpu/embree_scene.h"
#include "cpu/surface_photon_grid.h"

namespace tyndall {

struct CameraPassStats {
    uint64_t rays = 0;          ///< surface rays traced
    uint64_t beamQueries = 0;   ///< secondary segments gathered through the BVH
    uint64_t beamHits = 0;      ///< beam x ray pairs found by those queries
};

struct CameraPassResult {
    Image radiance;             ///< everything except the primary segments' medium radiance
    PrimarySegments primary;
    CameraPassStats stats;
};

class CameraTracer {
public:
    CameraTracer(const EmbreeScene& rt, const RenderSettings& settings);

    CameraPassResult trace(uint64_t pass, const PhotonMap& photons, const BeamBvh& beams,
                           const SurfacePhotonGrid& surface) const;

    MediumId cameraMedium() const { return m_cameraMedium; }

private:
    const EmbreeScene& m_rt;
    const Scene& m_scene;
    RenderSettings m_settings;
    MediumId m_cameraMedium;
    bool m_anyHeterogeneous = false;
};

/// Medium radiance gathered from `beams` along the segment o + s d, s in [0, sMax], inside
/// `medium`, before the camera path's throughput. `segmentFreeFlights` (n distances from `o`) are
/// the segment's own stored transmittance samples for grid media (ignored for homogeneous ones).
Rgb gatherBeams(const Scene& scene, const PhotonMap& photons, const std::vector<BeamHitRecord>& hits,
                MediumId medium, const Vec3& o, const Vec3& d, const float* segmentFreeFlights, int n);

}  // namespace tyndall
