// The transmittance estimators of grid media on a scene's own rays: plain ratio tracking against
// residual ratio tracking (cpu/free_flight.h), their variance and CPU time per estimate.
//
//   build/bench/transmittance_study SCENE [--rays N] [--repeats R] [--seed S]
//
// Rays: N camera rays through a 64x64 film (a pixel and its jitter at random), each to its first
// surface (the camera's segments), and from a point uniform on each such segment inside a grid
// medium to each point and spot light (shadow rays / the equiangular estimator's light legs, the
// scene's surfaces ignored: only the medium's transmittance). Each ray gets R estimates per
// estimator; printed per kind of ray: the mean relative variance (sum of per-ray variances over
// the sum of squared means), the density lookups and the CPU seconds per estimate, and their
// product relative to ratio tracking (the inefficiency: lower is better at equal time).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "core/rng.h"
#include "cpu/embree_scene.h"
#include "cpu/free_flight.h"
#include "loading/scene_file.h"

using namespace tyndall;

namespace {
double cpuSeconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

struct StudyRay {
    MediumId medium;
    Ray ray;
    float tEnd;
};

struct Row {
    double var = 0, meanSq = 0, seconds = 0;
    long estimates = 0;
};
}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: transmittance_study SCENE [--rays N] [--repeats R] [--seed S]\n");
        return 2;
    }
    int nRays = 2000, repeats = 64;
    uint64_t seed = 1;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--rays")) nRays = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--repeats")) repeats = std::atoi(argv[i + 1]);
        if (!std::strcmp(argv[i], "--seed")) seed = std::strtoull(argv[i + 1], nullptr, 10);
    }
    SceneFile file = loadSceneFile(argv[1]);
    const Scene& scene = file.scene;
    EmbreeScene rt(scene);
    std::vector<StudyRay> camera, light;
    Rng pick = Rng::forKey(seed, 0, 0, StreamPurpose::Transmittance);
    for (int r = 0; r < nRays; ++r) {
        const Ray cam = scene.camera.generateRay(pick.uniform() * 64.0f, pick.uniform() * 64.0f, 64, 64, Vec2{0.5f, 0.5f});
        SurfaceHit hit;
        const float tHit = rt.intersect(cam, &hit) ? hit.t : kInfinity;
        const MediumId id = rt.mediumAt(cam.o);
        if (id == kVacuum || scene.media[id].homogeneous()) continue;
        Ray seg;
        if (!rt.mediumSegment(cam.o, cam.d, tHit, &seg)) continue;
        camera.push_back({id, seg, seg.tMax});
        const Vec3 x = seg.o + seg.d * (pick.uniform() * seg.tMax);
        for (const Light& l : scene.lights) {
            if (l.type != LightType::Point && l.type != LightType::Spot) continue;
            const Vec3 to = l.position - x;
            const float dist = length(to);
            Ray s;
            if (!(dist > 0) || !rt.mediumSegment(x, to / dist, dist, &s)) continue;
            light.push_back({id, s, s.tMax});
        }
    }
    std::printf("%s: %zu camera segments, %zu light legs, %d estimates each\n", argv[1], camera.size(), light.size(),
                repeats);
    struct Estimator {
        const char* name;
        int k;  // GRIDTR_K is read once; variants by setting it per run instead
    };
    const char* names[2] = {"ratio tracking", "residual ratio tracking"};
    for (const auto* set : {&camera, &light}) {
        Row rows[2];
        for (int e = 0; e < 2; ++e) {
            const double start = cpuSeconds();
            for (size_t r = 0; r < set->size(); ++r) {
                const StudyRay& sr = (*set)[r];
                const Medium& med = scene.media[sr.medium];
                double s = 0, s2 = 0;
                for (int k = 0; k < repeats; ++k) {
                    Rng rng = Rng::forKey(seed + 1, uint64_t(k), r, StreamPurpose::Transmittance);
                    const float t = e == 0 ? ratioTrackingTransmittance(med, sr.ray, sr.tEnd, rng).r
                                           : residualTransmittance(med, sr.ray, sr.tEnd, rng);
                    s += t;
                    s2 += double(t) * t;
                }
                const double mean = s / repeats;
                rows[e].var += std::max(0.0, s2 / repeats - mean * mean) * repeats / (repeats - 1);
                rows[e].meanSq += mean * mean;
                rows[e].estimates += repeats;
            }
            rows[e].seconds = cpuSeconds() - start;
        }
        std::printf("%s:\n", set == &camera ? "camera segments" : "light legs");
        for (int e = 0; e < 2; ++e) {
            const double rel = rows[e].var / rows[e].meanSq, us = 1e6 * rows[e].seconds / rows[e].estimates;
            const double ineff = rel * us / (rows[0].var / rows[0].meanSq * 1e6 * rows[0].seconds / rows[0].estimates);
            std::printf("  %-26s relative variance %.4f, %.3f us per estimate, variance x time %.3f of ratio tracking's\n",
                        names[e], rel, us, ineff);
        }
    }
    return 0;
}
