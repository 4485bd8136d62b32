#include "cpu/pass_renderer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/timing.h"
#include "cpu/radius_defaults.h"

namespace tyndall {

namespace {
// Free-flight distances stored per beam and per pixel: only scenes with grid media store any.
int storedFreeFlights(const Scene& scene, const RenderSettings& settings) {
    for (const Medium& m : scene.media)
        if (!m.homogeneous()) return settings.freeFlightSamples;
    return 0;
}
}  // namespace

void PassStats::add(const PhotonMap& photons) {
    photonPaths += photons.pathCount;
    beams += photons.beams.size();
    surfacePhotons += photons.surfacePhotons.size();
}

void PassStats::add(const CameraPassStats& camera) {
    cameraRays += camera.rays;
    beamQueries += camera.beamQueries;
    beamHits += camera.beamHits;
}

void PassStats::add(const RasterStats& raster) {
    rasterTests += raster.pixelTests;
}

PassStats& PassStats::operator+=(const PassStats& o) {
    photonPaths += o.photonPaths;
    beams += o.beams;
    surfacePhotons += o.surfacePhotons;
    cameraRays += o.cameraRays;
    beamQueries += o.beamQueries;
    beamHits += o.beamHits;
    rasterTests += o.rasterTests;
    photonSeconds += o.photonSeconds;
    cameraSeconds += o.cameraSeconds;
    splatSeconds += o.splatSeconds;
    return *this;
}

PassRenderer::PassRenderer(const Scene& scene, const RenderSettings& settings, BeamBvh::Kind beamBvh, bool aovLayers)
    : m_scene(scene),
      m_rt(std::make_unique<EmbreeScene>(scene)),
      m_settings(resolveEquiangularSamples(resolveRadiusDefaults(settings, *m_rt))),
      m_radii(RadiusSetup::resolve(m_settings, scene)),
      m_memory(MemoryPlan::resolve(m_settings, storedFreeFlights(scene, m_settings), aovLayers)),
      m_bvhKind(beamBvh),
      m_photons(std::make_unique<PhotonTracer>(*m_rt, m_settings, m_radii)),
      m_camera(std::make_unique<CameraTracer>(*m_rt, m_settings)),
      m_rasterizer(scene, m_settings.simd ? SplatKernel::Simd : SplatKernel::Scalar) {
    for (const Material& m : scene.materials) m_anyNonDiffuse |= m.type != MaterialType::Diffuse;
}

PhotonMap PassRenderer::tracePhotons(uint64_t pass) const {
    return m_photons->trace(pass);
}

PhotonMap PassRenderer::tracePhotons(uint64_t pass, uint32_t batch) const {
    const uint64_t begin = uint64_t(batch) * m_memory.batchPaths;
    const uint64_t end = std::min<uint64_t>(begin + m_memory.batchPaths, m_settings.photonsPerPass);
    return allocating("the photon beams and surface photons of a batch of " + std::to_string(end - begin) +
                          " photon paths",
                      (end - begin) * m_memory.bytesPerPath,
                      [&] { return m_photons->traceBatch(pass, uint32_t(begin), uint32_t(end)); });
}

PrimaryPass PassRenderer::tracePrimary(uint64_t pass) const {
    return allocating("the primary camera rays of a " + std::to_string(m_settings.width) + "x" +
                          std::to_string(m_settings.height) + " pass",
                      m_memory.imageBytes / 2, [&] { return m_camera->tracePrimary(pass); });
}

Image PassRenderer::traceSecondary(const PrimaryPass& primary, const PhotonMap& photons, CameraPassStats* stats,
                                   bool emission, SecondaryLayers* layers, Image* alpha) const {
    return allocating("the beam BVH and surface-photon grid of " + std::to_string(photons.beams.size()) +
                          " beams and " + std::to_string(photons.surfacePhotons.size()) + " surface photons",
                      photons.pathCount * m_memory.bytesPerPath, [&] {
                          // Camera paths reach secondary segments only through non-diffuse
                          // surfaces: without any, no query would ever read the BVH.
                          static const std::vector<PhotonBeam> kNoBeams;
                          const std::vector<PhotonBeam>& beams = m_anyNonDiffuse ? photons.beams : kNoBeams;
                          const int pieces = beams.empty() ? 1 : BeamBvh::piecesFor(primary.nonDiffuseHits, beams.size());
                          // Wider beams after a scattering: the cache and pieces follow the others.
                          const float usual =
                              m_radii.scatteredPerMfp > 0 ? m_radii.beamRadiusOf(photons.firstPath) : 0.0f;
                          BeamBvh bvh(*m_rt->device(), beams, m_bvhKind, 0.0f, pieces, usual);
                          SurfacePhotonGrid grid(photons.surfacePhotons);
                          Image radiance = m_camera->traceSecondary(primary, photons, bvh, grid, stats, layers, emission,
                                                                   emission ? alpha : nullptr);
                          if (emission && m_hooks) m_hooks->cameraRadiance(primary.pass, radiance);
                          return radiance;
                      });
}

CameraPassResult PassRenderer::traceCamera(uint64_t pass, const PhotonMap& photons) const {
    PrimaryPass primary = tracePrimary(pass);
    CameraPassResult result;
    result.stats.rays = primary.rays;
    result.radiance = traceSecondary(primary, photons, &result.stats);
    result.primary = std::move(primary.segments);
    return result;
}

Image PassRenderer::splatPrimary(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats) const {
    return m_rasterizer.rasterize(primary, photons, stats);
}

void PassRenderer::sceneChanged() {
    m_photons = std::make_unique<PhotonTracer>(*m_rt, m_settings, m_radii);
    m_camera->lightsChanged();
}

Image PassRenderer::renderPass(uint64_t pass, PassStats* stats) const {
    return renderBatches(pass, stats, nullptr, nullptr);
}

PassLayers PassRenderer::renderPassLayers(uint64_t pass, PassStats* stats) const {
    PassLayers layers;
    layers.beauty = renderBatches(pass, stats, &layers, m_settings.transparentFilm ? &layers.alpha : nullptr);
    return layers;
}

PassLayers PassRenderer::renderPass(uint64_t pass, bool layers, PassStats* stats,
                                    const std::function<bool()>& abandon) const {
    PassLayers out;
    out.beauty = renderBatches(pass, stats, layers ? &out : nullptr, m_settings.transparentFilm ? &out.alpha : nullptr,
                               abandon);
    return out;
}

Image PassRenderer::renderBatches(uint64_t pass, PassStats* stats, PassLayers* layers, Image* alpha,
                                  const std::function<bool()>& abandon) const {
    PassStats local;
    auto t0 = Clock::now();
    const PrimaryPass primary = tracePrimary(pass);
    local.cameraRays += primary.rays;
    local.cameraSeconds += secondsSince(t0);
    Image image;
    // One batch at a time: its beams and photons are freed before the next is traced.
    for (uint32_t batch = 0; batch < m_memory.batches && !(abandon && abandon()); ++batch) {
        const bool first = batch == 0;
        auto t1 = Clock::now();
        const PhotonMap photons = tracePhotons(pass, batch);
        auto t2 = Clock::now();
        CameraPassStats camera;
        SecondaryLayers secondary;
        Image radiance = traceSecondary(primary, photons, &camera, first, layers ? &secondary : nullptr, alpha);
        auto t3 = Clock::now();
        RasterStats raster;
        Image part = splatPrimary(primary.segments, photons, &raster);
        if (layers) {
            secondary.mediaPrimary += part;  // the splat's beams and the CPU's share of the primary segments
            addBatch(layers->mediaPrimary, std::move(secondary.mediaPrimary));
            addBatch(layers->mediaSecondary, std::move(secondary.media));
            addBatch(layers->surface, std::move(secondary.surface));
        }
        part += radiance;
        addBatch(image, std::move(part));
        local.add(photons);
        local.add(camera);
        local.add(raster);
        local.photonSeconds += std::chrono::duration<double>(t2 - t1).count();
        local.cameraSeconds += std::chrono::duration<double>(t3 - t2).count();
        local.splatSeconds += secondsSince(t3);
    }
    if (stats) *stats += local;
    return image;
}

}  // namespace tyndall
