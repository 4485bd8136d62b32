#pragma once
// One PPB pass on the CPU, as separate stages so a scheduler can overlap them and swap the
// primary-segment splatter for the GL one:
//   tracePhotons(i)                      -> PhotonMap     (step 1)
//   tracePrimary(i)                      -> PrimaryPass   (step 2, the primary segments)
//   splatPrimary(primary, photons)       -> Image         (step 3, primary segments' media)
//   traceSecondary(primary, photons)     -> Image         (steps 2-4, the rest of the paths)
//   renderPass(i) = traceSecondary + splatPrimary         (step 5's pass image)
// traceCamera(i, photons) runs both camera stages. A pass is a pure function of (scene, settings,
// seed, pass index). Thread-safe: passes may run concurrently on one PassRenderer.
//
// Bounded memory: renderPass (and the scheduler) trace a pass's photons in memoryPlan().batches
// batches (tracePhotons(i, batch)), splat and gather each, free it and sum the images; the
// estimates are sums over beams and photons, so the sum is the pass (up to float rounding). The
// batch size comes from the settings alone (cpu/memory_plan.h). tracePhotons(i) is the whole pass
// in one map, for tests and benchmarks only.
//
// The scene is held by reference: its camera, its lights' positions, directions and powers and
// its media's coefficients may change between passes (the viewer's reset) provided
// sceneChanged() is called before the next pass; geometry, materials and the number of lights
// are baked into the ray tracer (build a new PassRenderer for those).
#include <functional>
#include <memory>

#include "core/image.h"
#include "core/settings.h"
#include "cpu/beam_bvh.h"
#include "cpu/beam_rasterizer.h"
#include "cpu/camera_tracer.h"
#include "cpu/embree_scene.h"
#include "cpu/memory_plan.h"
#include "cpu/photon_tracer.h"
#include "cpu/test_hooks.h"

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
    void add(const PhotonMap& photons);       ///< the counts of a pass's photon stage
    void add(const CameraPassStats& camera);  ///< the counts of its camera stages
    void add(const RasterStats& raster);      ///< the counts of its primary splat
};

/// One pass split by where its light comes from (the AOV layers): beauty = mediaPrimary +
/// mediaSecondary + surface up to float rounding; beauty itself has the same bits as renderPass's.
struct PassLayers {
    Image beauty;
    Image mediaPrimary;    ///< media seen directly by the camera (the primary segments: beams,
                           ///< emission, equiangular single scattering, planes)
    Image mediaSecondary;  ///< media seen through mirrors and glass
    Image surface;         ///< surface photons and emission
    /// With RenderSettings::transparentFilm (renderPass with or without layers): the coverage,
    /// in every channel (CameraTracer::traceSecondary).
    Image alpha;
};

class PassRenderer {
public:
    /// Resolves the automatic radius settings (cpu/radius_defaults.h) against the scene's camera.
    /// Throws Error when the settings' image does not fit their memory budget (MemoryPlan).
    /// `aovLayers`: the render keeps AOV layers (renderPassLayers); its buffers count in the
    /// memory plan, so fewer photon paths may go in a batch.
    PassRenderer(const Scene& scene, const RenderSettings& settings, BeamBvh::Kind beamBvh = BeamBvh::Kind::FlatCurves,
                 bool aovLayers = false);

    PhotonMap tracePhotons(uint64_t pass) const;
    /// Batch `batch` (< memoryPlan().batches) of pass `pass`'s photon paths.
    PhotonMap tracePhotons(uint64_t pass, uint32_t batch) const;
    PrimaryPass tracePrimary(uint64_t pass) const;
    /// Builds the beam BVH and surface-photon grid of `photons` (a pass or one batch of it) and
    /// traces the secondary stage. `emission`: add what the paths see of emitters (the first
    /// batch of a pass only; see CameraTracer::traceSecondary); `layers` also receives the
    /// radiance split into media and surface parts; `alpha` (with `emission`) receives the pass's
    /// coverage (CameraTracer::traceSecondary; the transparent film's alpha).
    Image traceSecondary(const PrimaryPass& primary, const PhotonMap& photons, CameraPassStats* stats = nullptr,
                         bool emission = true, SecondaryLayers* layers = nullptr, Image* alpha = nullptr) const;
    CameraPassResult traceCamera(uint64_t pass, const PhotonMap& photons) const;
    Image splatPrimary(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats = nullptr) const;
    Image renderPass(uint64_t pass, PassStats* stats = nullptr) const;
    /// renderPass with the image's components kept apart as well.
    PassLayers renderPassLayers(uint64_t pass, PassStats* stats = nullptr) const;
    /// renderPass (`layers` false: only PassLayers::beauty is filled) or renderPassLayers (true),
    /// abandoned between stages once `abandon()` says so: the result is then incomplete, for the
    /// caller to throw away (the render driver's reset and exit).
    PassLayers renderPass(uint64_t pass, bool layers, PassStats* stats, const std::function<bool()>& abandon) const;

    /// Test faults (cpu/test_hooks.h); null (the default) in normal use. Not owned; set before
    /// the first pass.
    void setTestHooks(const TestHooks* hooks) { m_hooks = hooks; }

    /// Re-reads what the photon tracer derives from the lights (their sampling distribution and
    /// the media they sit in). Not thread-safe: call with no pass running.
    void sceneChanged();

    const Scene& scene() const { return m_scene; }
    /// The settings with the automatic radii resolved for this scene and camera: plain numbers
    /// that reproduce the render bit for bit (what the EXR metadata records).
    const RenderSettings& settings() const { return m_settings; }
    const RadiusSetup& radii() const { return m_radii; }
    const MemoryPlan& memoryPlan() const { return m_memory; }
    const EmbreeScene& rayTracer() const { return *m_rt; }
    const PhotonTracer& photonTracer() const { return *m_photons; }

private:
    /// renderPass, batch by batch; with `layers`, its components are summed there too.
    Image renderBatches(uint64_t pass, PassStats* stats, PassLayers* layers, Image* alpha,
                        const std::function<bool()>& abandon = {}) const;

    const Scene& m_scene;
    std::unique_ptr<EmbreeScene> m_rt;
    RenderSettings m_settings;  // automatic radii resolved (cpu/radius_defaults.h)
    RadiusSetup m_radii;
    MemoryPlan m_memory;
    BeamBvh::Kind m_bvhKind;
    bool m_anyNonDiffuse = false;  // a camera path can have secondary segments
    std::unique_ptr<PhotonTracer> m_photons;
    std::unique_ptr<CameraTracer> m_camera;
    BeamRasterizer m_rasterizer;
    const TestHooks* m_hooks = nullptr;
};

}  // namespace tyndall
