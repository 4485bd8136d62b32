#include "cpu/pass_renderer.h"

#include <chrono>

namespace tyndall {

namespace {
double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
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

PassRenderer::PassRenderer(const Scene& scene, const RenderSettings& settings, BeamBvh::Kind beamBvh)
    : m_scene(scene),
      m_settings(settings),
      m_radii(RadiusSetup::resolve(settings, scene)),
      m_bvhKind(beamBvh),
      m_rt(std::make_unique<EmbreeScene>(scene)),
      m_photons(std::make_unique<PhotonTracer>(*m_rt, settings, m_radii)),
      m_camera(std::make_unique<CameraTracer>(*m_rt, settings)),
      m_rasterizer(scene) {}

PhotonMap PassRenderer::tracePhotons(uint64_t pass) const {
    return m_photons->trace(pass);
}

PrimaryPass PassRenderer::tracePrimary(uint64_t pass) const {
    return m_camera->tracePrimary(pass);
}

Image PassRenderer::traceSecondary(const PrimaryPass& primary, const PhotonMap& photons, CameraPassStats* stats) const {
    BeamBvh bvh(*m_rt->device(), photons.beams, m_bvhKind);
    SurfacePhotonGrid grid(photons.surfacePhotons);
    return m_camera->traceSecondary(primary, photons, bvh, grid, stats);
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
}

Image PassRenderer::renderPass(uint64_t pass, PassStats* stats) const {
    auto t0 = std::chrono::steady_clock::now();
    PhotonMap photons = tracePhotons(pass);
    auto t1 = std::chrono::steady_clock::now();
    CameraPassResult camera = traceCamera(pass, photons);
    auto t2 = std::chrono::steady_clock::now();
    RasterStats raster;
    Image image = splatPrimary(camera.primary, photons, &raster);
    image += camera.radiance;
    if (stats) {
        stats->add(photons);
        stats->add(camera.stats);
        stats->rasterTests += raster.pixelTests;
        stats->photonSeconds += std::chrono::duration<double>(t1 - t0).count();
        stats->cameraSeconds += std::chrono::duration<double>(t2 - t1).count();
        stats->splatSeconds += secondsSince(t2);
    }
    return image;
}

PassLayers PassRenderer::renderPassLayers(uint64_t pass, PassStats* stats) const {
    auto t0 = std::chrono::steady_clock::now();
    PhotonMap photons = tracePhotons(pass);
    auto t1 = std::chrono::steady_clock::now();
    PrimaryPass primary = tracePrimary(pass);
    CameraPassStats camera;
    camera.rays = primary.rays;
    BeamBvh bvh(*m_rt->device(), photons.beams, m_bvhKind);
    SurfacePhotonGrid grid(photons.surfacePhotons);
    SecondaryLayers secondary;
    Image radiance = m_camera->traceSecondary(primary, photons, bvh, grid, &camera, &secondary);
    auto t2 = std::chrono::steady_clock::now();
    RasterStats raster;
    PassLayers layers;
    layers.mediaPrimary = splatPrimary(primary.segments, photons, &raster);
    layers.beauty = layers.mediaPrimary;
    layers.beauty += radiance;
    layers.mediaSecondary = std::move(secondary.media);
    layers.surface = std::move(secondary.surface);
    if (stats) {
        stats->add(photons);
        stats->add(camera);
        stats->rasterTests += raster.pixelTests;
        stats->photonSeconds += std::chrono::duration<double>(t1 - t0).count();
        stats->cameraSeconds += std::chrono::duration<double>(t2 - t1).count();
        stats->splatSeconds += secondsSince(t2);
    }
    return layers;
}

}  // namespace tyndall
