#pragma once
// One PPB pass on the CPU, as separate stages so a scheduler can overlap them and swap the
// primary-segment splatter for the GL one:
//   tracePhotons(i)                 -> PhotonMap          (step 1)
//   traceCamera(i, photons)         -> CameraPassResult   (steps 2-4 except primary media)
//   splatPrimary(camera, photons)   -> Image              (step 3, primary segments)
//   renderPass(i) = traceCamera.radiance + splatPrimary   (step 5's pass image)
// A pass is a pure function of (scene, settings, seed, pass index). Thread-safe: passes may run
// concurrently on one PassRenderer.
#include <memory>

#include "core/image.h"
#include "core/settings.h"
#include "cpu/beam_bvh.h"
#include "cpu/beam_rasterizer.h"
#include "cpu/camera_tracer.h"
#include "cpu/embree_scene.h"
#include "cpu/photon_tracer.h"

namespace tyndall {

struct PassStats {
    uint64_t photonPaths = 0;
    uint64_t beams = 0;
    uint64_t surfacePhotons = 0;
    uint64_t cameraRays = 0;
    uint64_t beamQueries = 0;
    uint64_t beamHits = 0;
    uint64_t rasterTests = 0;
    double photonSeconds = 0;
    double cameraSeconds = 0;
    double splatSeconds = 0;

    PassStats& operator+=(const PassStats& o);
};

class PassRenderer {
public:
    PassRenderer(const Scene& scene, const RenderSettings& settings, BeamBvh::Kind beamBvh = BeamBvh::Kind::FlatCurves);

    PhotonMap tracePhotons(uint64_t pass) const;
    CameraPassResult traceCamera(uint64_t pass, const PhotonMap& photons) const;
    Image splatPrimary(const CameraPassResult& camera, const PhotonMap& photons, RasterStats* stats = nullptr) const;
    Image renderPass(uint64_t pass, PassStats* stats = nullptr) const;

    const Scene& scene() const { return m_scene; }
    const RenderSettings& settings() const { return m_settings; }
    const RadiusSetup& radii() const { return m_radii; }
    const EmbreeScene& rayTracer() const { return *m_rt; }

private:
    const Scene& m_scene;
    RenderSettings m_settings;
    RadiusSetup m_radii;
    BeamBvh::Kind m_bvhKind;
    std::unique_ptr<EmbreeScene> m_rt;
    std::unique_ptr<PhotonTracer> m_photons;
    std::unique_ptr<CameraTracer> m_camera;
    BeamRasterizer m_rasterizer;
};

}  // namespace tyndall
