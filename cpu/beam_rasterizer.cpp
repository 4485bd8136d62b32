#include "cpu/beam_rasterizer.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "core/beam_estimator.h"
#include "core/transmittance.h"

namespace tyndall {

namespace {
constexpr int kTile = 16;

struct CameraSpace {
    float x, y, z;
};
}  // namespace

// Which pixels can accept a beam: the estimator pairs a ray point Q = o + s d (s >= 0, so depth
// z_Q >= 0) with an axis point C at distance u < r. For a thin lens, o is within `lens` of the
// camera centre and d aims at the focus plane (depth fd), so Q lies in the pinhole frustum widened
// by lens |1 - z/fd| <= lens (1 + z/fd): tangents tx + lens/fd, ty + lens/fd, planes moved out by
// lens. C must lie within r of that set: clip the axis to it widened by r (conservative per plane).
// On the film, Q lands within f r sqrt(1 + |t_C|^2) / (z_C - r) of C's pinhole projection (t_C =
// C.xy/C.z, largest at an end of the clipped axis), shifted by f |o| |1/fd - 1/z_Q| for the lens,
// and the pixel centre is within sqrt(1/2) pixel of the jittered film position (margin 1.5).
// gpu/shaders/beam_footprint.glsl is the GLSL twin.
BeamFootprint beamFootprint(const Camera& cam, int width, int height, const PhotonBeam& beam) {
    BeamFootprint fp;
    const float tanHalf = std::tan(0.5f * cam.yFov);
    const float tx = tanHalf * float(width) / float(height), ty = tanHalf;
    const float f = 0.5f * float(height) / tanHalf;  // focal length in pixels
    const float r = beam.radius, lens = cam.lensRadius;
    auto toCamera = [&](const Vec3& p) {
        Vec3 v = p - cam.position;
        return CameraSpace{dot(v, cam.right), dot(v, cam.up), dot(v, cam.forward)};
    };
    CameraSpace a = toCamera(beam.origin), b = toCamera(beam.origin + beam.dir * beam.tMax);

    // Each plane is g(p) >= 0, linear in p.
    float lo = 0.0f, hi = 1.0f;
    auto clip = [&](float ga, float gb) {
        if (ga < 0 && gb < 0) return false;
        if (ga < 0) lo = std::max(lo, ga / (ga - gb));
        else if (gb < 0) hi = std::min(hi, ga / (ga - gb));
        return lo <= hi;
    };
    const float spread = lens > 0 ? lens / cam.focusDistance : 0.0f;
    const float lx = tx + spread, ly = ty + spread;
    const float sx = lens + r * std::sqrt(1.0f + lx * lx), sy = lens + r * std::sqrt(1.0f + ly * ly);
    if (!clip(a.z + r, b.z + r)) return fp;
    if (!clip(a.z * lx - a.x + sx, b.z * lx - b.x + sx)) return fp;
    if (!clip(a.z * lx + a.x + sx, b.z * lx + b.x + sx)) return fp;
    if (!clip(a.z * ly - a.y + sy, b.z * ly - b.y + sy)) return fp;
    if (!clip(a.z * ly + a.y + sy, b.z * ly + b.y + sy)) return fp;
    fp.visible = true;
    auto lerp = [](const CameraSpace& p, const CameraSpace& q, float t) {
        return CameraSpace{p.x + (q.x - p.x) * t, p.y + (q.y - p.y) * t, p.z + (q.z - p.z) * t};
    };
    CameraSpace c0 = lerp(a, b, lo), c1 = lerp(a, b, hi);
    float zMin = std::min(c0.z, c1.z), zMax = std::max(c0.z, c1.z);
    if (zMin <= 2.0f * (r + lens)) {  // passes right by the camera: every pixel may see it
        fp.fullScreen = true;
        return fp;
    }
    fp.ax = 0.5f * float(width) + f * c0.x / c0.z;
    fp.ay = 0.5f * float(height) - f * c0.y / c0.z;
    fp.bx = 0.5f * float(width) + f * c1.x / c1.z;
    fp.by = 0.5f * float(height) - f * c1.y / c1.z;
    float tan2 = std::max((c0.x * c0.x + c0.y * c0.y) / (c0.z * c0.z), (c1.x * c1.x + c1.y * c1.y) / (c1.z * c1.z));
    float coc = 0.0f;
    if (lens > 0) {
        float invF = 1.0f / cam.focusDistance;
        coc = f * lens * std::max(std::abs(invF - 1.0f / (zMin - r)), std::abs(invF - 1.0f / (zMax + r)));
    }
    fp.radius = f * r * std::sqrt(1.0f + tan2) / (zMin - r) + coc + 1.5f;
    return fp;
}

Rgb BeamRasterizer::pixelRadiance(const PrimarySegments& primary, size_t pixel, const PhotonMap& photons,
                                  uint32_t b) const {
    const PrimaryRay& ray = primary.rays[pixel];
    const PhotonBeam& beam = photons.beams[b];
    if (beam.medium != ray.medium || ray.medium == kVacuum) return Rgb();
    BeamRayHit hit;
    if (!intersectBeamRay(ray.origin, ray.dir, ray.tMax, beam, &hit)) return Rgb();
    const Medium& med = m_scene.media[ray.medium];
    if (med.homogeneous()) {
        Rgb st = med.sigmaT();
        float l = hit.s + hit.t;
        return beamRadiance(hit, beam, med.sigmaS, med.g, exp(Rgb(-st.r * l, -st.g * l, -st.b * l)), Rgb(1.0f));
    }
    int nc = primary.freeFlightsPerRay, nb = photons.freeFlightsPerBeam;
    float trCam = storedTransmittance(&primary.freeFlights[pixel * nc], nc, hit.s);
    float trBeam = storedTransmittance(&photons.freeFlights[size_t(b) * nb], nb, hit.t);
    if (trCam == 0 || trBeam == 0) return Rgb();
    return beamRadiance(hit, beam, med.sigmaSAt(ray.origin + ray.dir * hit.s), med.g, Rgb(trCam), Rgb(trBeam));
}

Image BeamRasterizer::rasterize(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats) const {
    const int w = primary.width, h = primary.height;
    const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile;
    Image out(w, h);
    const std::vector<PhotonBeam>& beams = photons.beams;

    std::vector<BeamFootprint> fps(beams.size());
    tbb::parallel_for(size_t(0), beams.size(), [&](size_t i) {
        fps[i] = beams[i].medium == kVacuum ? BeamFootprint{} : beamFootprint(m_scene.camera, w, h, beams[i]);
    });

    // Bin in beam order: a tile takes a beam when the 2D capsule reaches the tile's rectangle.
    std::vector<std::vector<uint32_t>> tiles(size_t(tilesX) * tilesY);
    uint64_t binned = 0;
    const float halfDiag = 0.5f * std::sqrt(2.0f) * kTile;
    for (uint32_t i = 0; i < beams.size(); ++i) {
        const BeamFootprint& fp = fps[i];
        if (!fp.visible) continue;
        int tx0 = 0, ty0 = 0, tx1 = tilesX - 1, ty1 = tilesY - 1;
        if (!fp.fullScreen) {
            tx0 = std::max(0, int(std::floor((std::min(fp.ax, fp.bx) - fp.radius) / kTile)));
            ty0 = std::max(0, int(std::floor((std::min(fp.ay, fp.by) - fp.radius) / kTile)));
            tx1 = std::min(tilesX - 1, int(std::floor((std::max(fp.ax, fp.bx) + fp.radius) / kTile)));
            ty1 = std::min(tilesY - 1, int(std::floor((std::max(fp.ay, fp.by) + fp.radius) / kTile)));
        }
        float dx = fp.bx - fp.ax, dy = fp.by - fp.ay, len2 = dx * dx + dy * dy;
        for (int ty = ty0; ty <= ty1; ++ty)
            for (int tx = tx0; tx <= tx1; ++tx) {
                if (!fp.fullScreen) {
                    float cx = (tx + 0.5f) * kTile, cy = (ty + 0.5f) * kTile;
                    float t = len2 > 0 ? clampValue(((cx - fp.ax) * dx + (cy - fp.ay) * dy) / len2, 0.0f, 1.0f) : 0.0f;
                    float ex = fp.ax + t * dx - cx, ey = fp.ay + t * dy - cy;
                    float reachT = fp.radius + halfDiag;
                    if (ex * ex + ey * ey > reachT * reachT) continue;
                }
                tiles[size_t(ty) * tilesX + tx].push_back(i);
                ++binned;
            }
    }

    std::atomic<uint64_t> tests{0};
    tbb::parallel_for(0, tilesX * tilesY, [&](int tile) {
        const std::vector<uint32_t>& list = tiles[tile];
        if (list.empty()) return;
        const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
        const int x1 = std::min(w, x0 + kTile), y1 = std::min(h, y0 + kTile);
        uint64_t localTests = 0;
        for (uint32_t b : list) {
            const BeamFootprint& fp = fps[b];
            float dx = fp.bx - fp.ax, dy = fp.by - fp.ay, len2 = dx * dx + dy * dy;
            float r2 = fp.radius * fp.radius;
            for (int y = y0; y < y1; ++y) {
                float py = y + 0.5f;
                for (int x = x0; x < x1; ++x) {
                    if (!fp.fullScreen) {
                        float px = x + 0.5f;
                        float t = len2 > 0 ? clampValue(((px - fp.ax) * dx + (py - fp.ay) * dy) / len2, 0.0f, 1.0f) : 0.0f;
                        float ex = fp.ax + t * dx - px, ey = fp.ay + t * dy - py;
                        if (ex * ex + ey * ey > r2) continue;
                    }
                    ++localTests;
                    size_t pixel = size_t(y) * w + x;
                    out.pixels[pixel] += pixelRadiance(primary, pixel, photons, b);
                }
            }
        }
        tests += localTests;
    });
    if (stats) {
        stats->pixelTests = tests;
        stats->binned = binned;
    }
    return out;
}

Image BeamRasterizer::bruteForce(const PrimarySegments& primary, const PhotonMap& photons) const {
    Image out(primary.width, primary.height);
    tbb::parallel_for(size_t(0), primary.rays.size(), [&](size_t pixel) {
        for (uint32_t b = 0; b < photons.beams.size(); ++b) out.pixels[pixel] += pixelRadiance(primary, pixel, photons, b);
    });
    return out;
}

}  // namespace tyndall
