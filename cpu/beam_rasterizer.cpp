#include "cpu/beam_rasterizer.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>

#include "core/beam_estimator.h"
#include "core/transmittance.h"
#include "cpu/beam_splat_simd.h"

namespace tyndall {

namespace {
constexpr int kBand = 8;  // rows per band: the unit of parallel work
static_assert(kBand <= SplatRows::kMaxRows, "a band's columns are found at once");

struct CameraSpace {
    float x, y, z;
};
}  // namespace

RasterStats& RasterStats::operator+=(const RasterStats& o) {
    pixelTests += o.pixelTests;
    binned += o.binned;
    return *this;
}

// Which pixels can accept a beam: the estimator pairs a ray point Q = o + s d (s >= 0, so depth
// z_Q >= 0) with an axis point C at distance u < r. For a thin lens, o is within `lens` of the
// camera centre and d aims at the focus plane (depth fd), so Q lies in the pinhole frustum widened
// by lens |1 - z/fd| <= lens (1 + z/fd): tangents tx + lens/fd, ty + lens/fd, planes moved out by
// lens (beyond 2 fd the lens rays leave the pinhole frustum by more than the lens radius). C must
// lie within r of that set: clip the axis to it widened by r, plane by plane. On the film, Q lands
// within the projected radius of C's projection, shifted by f |o| |1/fd - 1/z_Q| for the lens,
// with z_Q in [zMin - r, zMax + r]. gpu/shaders/beam_footprint.glsl is the GLSL twin.
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
    const float cx = 0.5f * float(width), cy = 0.5f * float(height);
    fp.ax = cx + f * c0.x / c0.z;
    fp.ay = cy - f * c0.y / c0.z;
    fp.bx = cx + f * c1.x / c1.z;
    fp.by = cy - f * c1.y / c1.z;
    // Off-axis stretch 1/cos(theta) = sqrt(1 + |p - centre|^2 / f^2): largest at an end of the
    // projected segment, and no larger than at the film's corner.
    auto stretchAt = [&](float px, float py) {
        float dx = std::min(std::abs(px - cx), cx), dy = std::min(std::abs(py - cy), cy);
        return std::sqrt(1.0f + (dx * dx + dy * dy) / (f * f));
    };
    float stretch = std::max(stretchAt(fp.ax, fp.ay), stretchAt(fp.bx, fp.by));
    float coc = 0.0f;
    if (lens > 0) {
        float invF = 1.0f / cam.focusDistance;
        coc = f * lens * std::max(std::abs(invF - 1.0f / (zMin - r)), std::abs(invF - 1.0f / (zMax + r)));
    }
    const float margin = coc + 0.75f;  // 0.75 > half the pixel diagonal: any jittered film position
    fp.ra = f * r / (c0.z - r) * stretch + margin;
    fp.rb = f * r / (c1.z - r) * stretch + margin;
    // Degenerate input (NaN, or coordinates too large to bin as ints): be safe, not fast.
    const float limit = 1e7f;
    for (float v : {fp.ax, fp.ay, fp.bx, fp.by, fp.ra, fp.rb})
        if (!(std::abs(v) < limit)) fp.fullScreen = true;
    return fp;
}

FootprintSides footprintSides(const BeamFootprint& fp) {
    FootprintSides sides;
    if (fp.fullScreen) return sides;
    float dx = fp.bx - fp.ax, dy = fp.by - fp.ay;
    float len = std::sqrt(dx * dx + dy * dy);
    if (!(len > std::abs(fp.ra - fp.rb))) return sides;
    // The hull's straight sides touch the discs where the outward normal is
    // n cos(phi) + u sin(phi), sin(phi) = (ra - rb) / len.
    sides.present = true;
    float ux = dx / len, uy = dy / len, nx = -uy, ny = ux;
    float sinPhi = (fp.ra - fp.rb) / len, cosPhi = std::sqrt(std::max(0.0f, 1.0f - sinPhi * sinPhi));
    for (int side = 0; side < 2; ++side) {
        float s = side == 0 ? 1.0f : -1.0f;
        float ox = s * nx * cosPhi + ux * sinPhi, oy = s * ny * cosPhi + uy * sinPhi;
        sides.quad[side == 0 ? 0 : 3][0] = fp.ax + fp.ra * ox;
        sides.quad[side == 0 ? 0 : 3][1] = fp.ay + fp.ra * oy;
        sides.quad[side == 0 ? 1 : 2][0] = fp.bx + fp.rb * ox;
        sides.quad[side == 0 ? 1 : 2][1] = fp.by + fp.rb * oy;
    }
    return sides;
}

namespace {
/// footprintRowSpan with the footprint's sides already found (footprintSides).
bool rowSpan(const BeamFootprint& fp, const FootprintSides& sides, float y, float* x0, float* x1) {
    if (fp.fullScreen) {
        *x0 = -kInfinity;
        *x1 = kInfinity;
        return true;
    }
    float lo = kInfinity, hi = -kInfinity;
    auto disc = [&](float cx, float cy, float r) {
        float dy = y - cy;
        float h2 = r * r - dy * dy;
        if (h2 < 0) return;
        float h = std::sqrt(h2);
        lo = std::min(lo, cx - h);
        hi = std::max(hi, cx + h);
    };
    disc(fp.ax, fp.ay, fp.ra);
    disc(fp.bx, fp.by, fp.rb);
    if (sides.present) {
        for (int e = 0; e < 4; ++e) {
            const float* p = sides.quad[e];
            const float* q = sides.quad[(e + 1) % 4];
            if ((p[1] - y) * (q[1] - y) > 0) continue;
            float x = p[1] == q[1] ? p[0] : p[0] + (q[0] - p[0]) * (y - p[1]) / (q[1] - p[1]);
            lo = std::min(lo, x);
            hi = std::max(hi, x);
            if (p[1] == q[1]) {
                lo = std::min(lo, q[0]);
                hi = std::max(hi, q[0]);
            }
        }
    }
    *x0 = lo;
    *x1 = hi;
    return lo <= hi;
}
}  // namespace

bool footprintRowSpan(const BeamFootprint& fp, float y, float* x0, float* x1) {
    return rowSpan(fp, footprintSides(fp), y, x0, x1);
}

namespace {

// The estimator of core/beam_estimator.h for one beam against many pixels, with the per-beam
// constants hoisted and the homogeneous case specialised: the HG denominator uses
// cos = -dot(w_c, w_b) directly, and a grey medium needs one exp. Agrees with
// intersectBeamRay + beamRadiance to float rounding (tests/cpu/beam_rasterizer_test.cpp).
class BeamPixelEvaluator {
public:
    BeamPixelEvaluator(const Scene& scene, const PhotonMap& photons, uint32_t b)
        : m_photons(photons), m_beam(photons.beams[b]), m_index(b) {
        if (m_beam.medium == kVacuum) return;
        m_medium = &scene.media[m_beam.medium];
        const float r = m_beam.radius;
        m_r2 = r * r;
        m_kernelScale = (15.0f / 16.0f) / r;
        const float g = m_medium->g;
        m_hgA = kInv4Pi * (1.0f - g * g);
        m_hgB = 1.0f + g * g;
        m_hgC = 2.0f * g;
        m_sigmaT = m_medium->sigmaT();
        m_grey = m_sigmaT.r == m_sigmaT.g && m_sigmaT.r == m_sigmaT.b;
        m_scaledPower = m_beam.power * m_medium->sigmaS;
    }

    Rgb operator()(const PrimarySegments& primary, size_t pixel) const {
        const PrimaryRay& ray = primary.rays[pixel];
        if (ray.medium != m_beam.medium || ray.medium == kVacuum) return Rgb();
        if (!m_medium->homogeneous()) return heterogeneous(primary, pixel);
        const Vec3 w0 = ray.origin - m_beam.origin;
        const float b = dot(ray.dir, m_beam.dir);
        const float sin2 = 1.0f - b * b;
        if (sin2 < 1e-12f) return Rgb();
        const float d = dot(ray.dir, w0), e = dot(m_beam.dir, w0);
        const float s = (b * e - d) / sin2, t = (e - b * d) / sin2;
        if (s < 0.0f || s > ray.tMax || t < 0.0f || t > m_beam.tMax) return Rgb();
        const Vec3 between = w0 + ray.dir * s - m_beam.dir * t;
        const float u2 = dot(between, between);
        if (u2 >= m_r2) return Rgb();
        // The kernel exactly as beamKernel() forms it, so coverage at the rim matches the GLSL twin.
        const float x = std::sqrt(u2) / m_beam.radius;
        const float a = 1.0f - x * x;
        if (!(a > 0.0f)) return Rgb();
        const float denom = m_hgB + m_hgC * b;  // 1 + g^2 - 2 g cos, cos = dot(w_b, -w_c) = -b
        const float phase = m_hgA / (denom * std::sqrt(std::max(denom, 1e-12f)));
        const float weight = m_kernelScale * a * a * phase / std::max(std::sqrt(sin2), kMinSinTheta);
        const float l = s + t;
        if (m_grey) return m_scaledPower * (weight * std::exp(-m_sigmaT.r * l));
        return m_scaledPower * exp(Rgb(-m_sigmaT.r * l, -m_sigmaT.g * l, -m_sigmaT.b * l)) * weight;
    }

private:
    Rgb heterogeneous(const PrimarySegments& primary, size_t pixel) const {
        const PrimaryRay& ray = primary.rays[pixel];
        BeamRayHit hit;
        if (!intersectBeamRay(ray.origin, ray.dir, ray.tMax, m_beam, &hit)) return Rgb();
        int nc = primary.freeFlightsPerRay, nb = m_photons.freeFlightsPerBeam;
        float trCam = storedTransmittance(&primary.freeFlights[pixel * nc], nc, hit.s);
        float trBeam = storedTransmittance(&m_photons.freeFlights[size_t(m_index) * nb], nb, hit.t);
        if (trCam == 0 || trBeam == 0) return Rgb();
        return beamRadiance(hit, m_beam, m_medium->sigmaSAt(ray.origin + ray.dir * hit.s), m_medium->g, Rgb(trCam),
                            Rgb(trBeam));
    }

    const PhotonMap& m_photons;
    const PhotonBeam& m_beam;
    uint32_t m_index;
    const Medium* m_medium = nullptr;
    float m_r2 = 0, m_kernelScale = 0, m_hgA = 0, m_hgB = 0, m_hgC = 0;
    Rgb m_sigmaT, m_scaledPower;
    bool m_grey = false;
};

/// The SIMD kernels' constants for beam `b`, hoisted as BeamPixelEvaluator hoists them.
SplatBeam splatBeam(const Scene& scene, const PhotonMap& photons, uint32_t b) {
    const PhotonBeam& beam = photons.beams[b];
    const Medium& medium = scene.media[beam.medium];
    SplatBeam sb;
    sb.origin = beam.origin;
    sb.dir = beam.dir;
    sb.tMax = beam.tMax;
    sb.radius = beam.radius;
    sb.r2 = beam.radius * beam.radius;
    sb.kernelScale = (15.0f / 16.0f) / beam.radius;
    sb.g = medium.g;
    sb.hgA = kInv4Pi * (1.0f - medium.g * medium.g);
    sb.hgB = 1.0f + medium.g * medium.g;
    sb.hgC = 2.0f * medium.g;
    sb.sigmaT = medium.sigmaT();
    sb.grey = sb.sigmaT.r == sb.sigmaT.g && sb.sigmaT.r == sb.sigmaT.b;
    sb.scaledPower = beam.power * medium.sigmaS;
    sb.medium = beam.medium;
    if (!medium.homogeneous()) {
        sb.freeFlightsPerBeam = photons.freeFlightsPerBeam;
        sb.freeFlights = &photons.freeFlights[size_t(b) * photons.freeFlightsPerBeam];
    }
    return sb;
}

struct SimdScratch {
    SplatBlock block;
    SplatHits hits;
};

/// Copies rows [y0, y1) of the primary rays into `block` (structure of arrays, row-major).
void fillBlock(const PrimarySegments& primary, int y0, int y1, SplatBlock* block) {
    const size_t first = size_t(y0) * primary.width, count = size_t(y1 - y0) * primary.width;
    const int nff = primary.freeFlightsPerRay;
    block->reset(count, nff);
    for (size_t i = 0; i < count; ++i) {
        const PrimaryRay& r = primary.rays[first + i];
        block->ox[i] = r.origin.x, block->oy[i] = r.origin.y, block->oz[i] = r.origin.z;
        block->dx[i] = r.dir.x, block->dy[i] = r.dir.y, block->dz[i] = r.dir.z;
        block->tMax[i] = r.tMax;
        block->medium[i] = r.medium;
        for (int k = 0; k < nff; ++k) block->freeFlights[k * block->capacity + i] = primary.freeFlights[(first + i) * nff + k];
    }
}

}  // namespace

Image BeamRasterizer::rasterize(const PrimarySegments& primary, const PhotonMap& photons, RasterStats* stats) const {
    const int w = primary.width, h = primary.height;
    const int bands = (h + kBand - 1) / kBand;
    // The render region (the whole image without one): beams and rows outside it are skipped, its
    // pixels get exactly what they get in the whole image (each sums its beams in index order).
    const PixelRegion region = primary.region.whole() ? PixelRegion{0, 0, w, h} : primary.region;
    const int firstBand = region.y / kBand, endBand = (region.y + region.height + kBand - 1) / kBand;
    Image out(w, h);
    const std::vector<PhotonBeam>& beams = photons.beams;

    std::vector<BeamFootprint> fps(beams.size());
    std::vector<FootprintSides> sides(beams.size());
    tbb::parallel_for(size_t(0), beams.size(), [&](size_t i) {
        fps[i] = beams[i].medium == kVacuum ? BeamFootprint{} : beamFootprint(m_scene.camera, w, h, beams[i]);
        if (fps[i].visible) sides[i] = footprintSides(fps[i]);
    });

    // Bin in beam order: a band takes a beam when the footprint's bounding box reaches it.
    std::vector<std::vector<uint32_t>> bandBeams(bands);
    uint64_t binned = 0;
    for (uint32_t i = 0; i < beams.size(); ++i) {
        const BeamFootprint& fp = fps[i];
        if (!fp.visible) continue;
        int b0 = 0, b1 = bands - 1;
        if (!fp.fullScreen) {
            float y0 = std::min(fp.ay - fp.ra, fp.by - fp.rb), y1 = std::max(fp.ay + fp.ra, fp.by + fp.rb);
            float x0 = std::min(fp.ax - fp.ra, fp.bx - fp.rb), x1 = std::max(fp.ax + fp.ra, fp.bx + fp.rb);
            if (x1 < float(region.x) || x0 > float(region.x + region.width) || y1 < float(region.y) ||
                y0 > float(region.y + region.height))
                continue;
            b0 = std::max(firstBand, int(std::floor(y0 / kBand)));
            b1 = std::min(endBand - 1, int(std::floor(y1 / kBand)));
        } else {
            b0 = firstBand, b1 = endBand - 1;
        }
        for (int b = b0; b <= b1; ++b) bandBeams[b].push_back(i);
        binned += uint64_t(b1 - b0 + 1);
    }

    std::atomic<uint64_t> tests{0};
    tbb::enumerable_thread_specific<SimdScratch> scratch;
    tbb::parallel_for(firstBand, endBand, [&](int band) {
        const int y0 = band * kBand, y1 = std::min(h, y0 + kBand);
        const int rowBegin = std::max(y0, region.y), rowEnd = std::min(y1, region.y + region.height);
        uint64_t localTests = 0;
        const bool simd = m_kernel == SplatKernel::Simd && !bandBeams[band].empty();
        SplatBlock* block = nullptr;
        SplatHits* hits = nullptr;
        if (simd) {
            SimdScratch& s = scratch.local();
            block = &s.block;
            hits = &s.hits;
            fillBlock(primary, y0, y1, block);
        }
        SplatRows rows;
        for (uint32_t b : bandBeams[band]) {
            localTests += footprintBandColumns(fps[b], sides[b], y0, rowBegin, rowEnd, region.x,
                                               region.x + region.width - 1, w, &rows);
            const Medium& medium = m_scene.media[beams[b].medium];
            if (!simd) {
                const BeamPixelEvaluator eval(m_scene, photons, b);
                for (int i = 0; i < rows.rows; ++i) {
                    const size_t row = size_t(y0 + i) * w;
                    for (int x = rows.x0[i]; x <= rows.x1[i]; ++x) out.pixels[row + x] += eval(primary, row + x);
                }
                continue;
            }
            const SplatBeam sb = splatBeam(m_scene, photons, b);
            if (medium.homogeneous()) {
                splatRowsHomogeneous(sb, *block, size_t(w), rows);
                continue;
            }
            // Grid media: sigma_s(x_w) is a density lookup per pixel, after the kernel; the
            // factors multiply in beamRadiance's order.
            for (int i = 0; i < rows.rows; ++i) {
                if (rows.x0[i] > rows.x1[i]) continue;
                splatSpanHeterogeneous(sb, *block, size_t(i) * w + rows.x0[i], size_t(rows.x1[i] - rows.x0[i] + 1), hits);
                for (size_t k = 0; k < hits->count; ++k) {
                    const size_t p = hits->pixel[k];
                    const PrimaryRay& ray = primary.rays[size_t(y0) * w + p];
                    const Rgb c = medium.sigmaSAt(ray.origin + ray.dir * hits->s[k]) * beams[b].power *
                                  Rgb(hits->trCam[k]) * Rgb(hits->trBeam[k]) * hits->weight[k];
                    block->sumR[p] += c.r, block->sumG[p] += c.g, block->sumB[p] += c.b;
                }
            }
        }
        if (simd) {
            const size_t first = size_t(y0) * w;
            for (size_t i = 0; i < size_t(y1 - y0) * w; ++i)
                out.pixels[first + i] = Rgb(block->sumR[i], block->sumG[i], block->sumB[i]);
        }
        tests += localTests;
    });
    if (stats) *stats += RasterStats{tests.load(), binned};
    return out;
}

Image BeamRasterizer::bruteForce(const PrimarySegments& primary, const PhotonMap& photons) const {
    Image out(primary.width, primary.height);
    tbb::parallel_for(size_t(0), primary.rays.size(), [&](size_t pixel) {
        for (uint32_t b = 0; b < photons.beams.size(); ++b)
            out.pixels[pixel] += BeamPixelEvaluator(m_scene, photons, b)(primary, pixel);
    });
    return out;
}

}  // namespace tyndall
