#include "cpu/pixel_footprint.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace tyndall {

namespace {
/// Median of values weighted by w (pairs of value, weight); 0 when the weights sum to 0.
double weightedMedian(std::vector<std::pair<double, double>> v) {
    double total = 0;
    for (const auto& e : v) total += e.second;
    if (!(total > 0)) return 0;
    std::sort(v.begin(), v.end());
    double acc = 0;
    for (const auto& e : v) {
        acc += e.second;
        if (acc >= 0.5 * total) return e.first;
    }
    return v.back().first;
}

/// Exit distance of `ray` from `b` (0 when it misses or starts past it).
float exitDistance(const Ray& ray, const Bounds3& b) {
    float lo = 0, hi = kInfinity;
    for (int a = 0; a < 3; ++a) {
        float o = a == 0 ? ray.o.x : (a == 1 ? ray.o.y : ray.o.z);
        float d = a == 0 ? ray.d.x : (a == 1 ? ray.d.y : ray.d.z);
        float l = a == 0 ? b.lo.x : (a == 1 ? b.lo.y : b.lo.z);
        float h = a == 0 ? b.hi.x : (a == 1 ? b.hi.y : b.hi.z);
        if (std::fabs(d) < 1e-12f) {
            if (o < l || o > h) return 0;
            continue;
        }
        float t0 = (l - o) / d, t1 = (h - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    return hi > lo ? hi : 0;
}

bool scatters(const Medium* m) {
    if (!m) return false;
    Rgb s = m->sigmaS;
    return s.r > 0 || s.g > 0 || s.b > 0;
}
}  // namespace

PixelFootprint measurePixelFootprint(const EmbreeScene& rt, const Camera& camera, int width, int height,
                                     int gridSize) {
    const Scene& scene = rt.scene();
    const double perDepth = 2.0 * std::tan(0.5 * double(camera.yFov)) / double(height);
    const int nx = std::max(1, std::min(gridSize, width)), ny = std::max(1, std::min(gridSize, height));
    const int kSteps = 32;
    std::vector<std::pair<double, double>> media, surfaces;
    int raysInMedia = 0;
    for (int y = 0; y < ny; ++y)
        for (int x = 0; x < nx; ++x) {
            Camera pinhole = camera;
            pinhole.lensRadius = 0;
            Ray ray = pinhole.generateRay((x + 0.5f) * width / nx, (y + 0.5f) * height / ny, width, height, {0.5f, 0.5f});
            float cosView = dot(ray.d, camera.forward);
            // The first visible surface: invisible medium boundaries (Interface) are passed through.
            float end = exitDistance(ray, scene.bounds);
            Ray probe = ray;
            SurfaceHit hit;
            for (int guard = 0; guard < 16 && rt.intersect(probe, &hit); ++guard) {
                float t = length(hit.p - ray.o);
                if (scene.materials[size_t(scene.meshes[size_t(hit.mesh)].material)].type != MaterialType::Interface) {
                    end = t;
                    surfaces.push_back({perDepth * t * cosView, 1.0});
                    break;
                }
                probe.o = rt.offsetOrigin(hit.p, hit.ng, ray.d);
            }
            if (!(end > 0) || !std::isfinite(end)) continue;
            bool any = false;
            for (int k = 0; k < kSteps; ++k) {
                float t = (k + 0.5f) * end / kSteps;
                if (!scatters(scene.medium(rt.mediumAt(ray.o + ray.d * t)))) continue;
                media.push_back({perDepth * t * cosView, end / kSteps});
                any = true;
            }
            raysInMedia += any;
        }
    PixelFootprint f;
    f.media = weightedMedian(std::move(media));
    f.surface = weightedMedian(std::move(surfaces));
    f.mediaFraction = double(raysInMedia) / double(nx * ny);
    return f;
}

}  // namespace tyndall
