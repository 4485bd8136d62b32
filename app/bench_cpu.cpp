#include "app/bench_cpu.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>

#include "core/rng.h"
#include "core/sampling.h"

namespace tyndall::app {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

double measureRawRayRate(const EmbreeScene& rt, uint64_t count) {
    const Bounds3 b = rt.scene().bounds;
    const uint64_t block = 4096;
    std::atomic<uint64_t> hits{0};
    auto t0 = Clock::now();
    tbb::parallel_for(uint64_t(0), (count + block - 1) / block, [&](uint64_t k) {
        Rng rng = Rng::forKey(7, 0, k, StreamPurpose::Test);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        uint64_t localHits = 0;
        for (uint64_t i = 0; i < block; ++i) {
            Vec3 o = b.lo + mul(b.diagonal(), Vec3(rng.uniform(), rng.uniform(), rng.uniform()));
            Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
            RTCRayHit rh;
            rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
            rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
            rh.ray.tnear = 0, rh.ray.tfar = kInfinity, rh.ray.mask = 0xFFFFFFFFu, rh.ray.flags = 0, rh.ray.time = 0;
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(rt.rtcScene(), &ctx, &rh);
            localHits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        hits += localHits;
    });
    double s = since(t0);
    return double(((count + block - 1) / block) * block) / s;
}

double measureReplayedPhotonRayRate(const PassRenderer& renderer, int passes) {
    std::vector<Ray> rays;
    for (int i = 0; i < passes; ++i)
        for (const PhotonBeam& b : renderer.tracePhotons(uint64_t(i)).beams) rays.push_back(Ray{b.origin, b.dir});
    if (rays.empty()) return 0.0;
    const RTCScene scene = renderer.rayTracer().rtcScene();
    const size_t block = 1024, repeats = 8;  // repeat so the timed loop runs long enough
    auto t0 = Clock::now();
    for (size_t rep = 0; rep < repeats; ++rep) {
        tbb::parallel_for(size_t(0), (rays.size() + block - 1) / block, [&](size_t k) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            for (size_t i = k * block; i < std::min(rays.size(), (k + 1) * block); ++i) {
                RTCRayHit rh;
                const Ray& r = rays[i];
                rh.ray.org_x = r.o.x, rh.ray.org_y = r.o.y, rh.ray.org_z = r.o.z;
                rh.ray.dir_x = r.d.x, rh.ray.dir_y = r.d.y, rh.ray.dir_z = r.d.z;
                rh.ray.tnear = 0, rh.ray.tfar = kInfinity, rh.ray.mask = 0xFFFFFFFFu, rh.ray.flags = 0, rh.ray.time = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &ctx, &rh);
            }
        });
    }
    return double(rays.size() * repeats) / since(t0);
}

PhotonRate measurePhotonTracing(const PassRenderer& renderer, int passes) {
    uint64_t paths = 0, beams = 0, rays = 0;
    auto t0 = Clock::now();
    for (int i = 0; i < passes; ++i) {
        PhotonMap m = renderer.tracePhotons(uint64_t(i));
        paths += m.pathCount;
        beams += m.beams.size();
        rays += m.raysTraced;
    }
    double s = since(t0);
    return {paths / s, beams / s, rays / s};
}

GatherRate measureBeamGather(const PassRenderer& renderer, BeamBvh::Kind kind, uint64_t count) {
    PhotonMap photons = renderer.tracePhotons(0);
    CameraPassResult camera = renderer.traceCamera(0, photons);
    std::vector<PrimaryRay> rays;
    for (const PrimaryRay& r : camera.primary.rays)
        if (r.medium != kVacuum && r.tMax > 0) rays.push_back(r);
    GatherRate rate;
    if (rays.empty()) return rate;
    auto tb = Clock::now();
    BeamBvh bvh(*renderer.rayTracer().device(), photons.beams, kind);
    rate.buildSeconds = since(tb);
    std::atomic<uint64_t> hits{0};
    const uint64_t block = 256;
    auto t0 = Clock::now();
    tbb::parallel_for(uint64_t(0), (count + block - 1) / block, [&](uint64_t k) {
        std::vector<BeamHitRecord> found;
        uint64_t local = 0;
        for (uint64_t i = k * block; i < std::min(count, (k + 1) * block); ++i) {
            const PrimaryRay& r = rays[(i * 7919) % rays.size()];
            bvh.query(r.origin, r.dir, r.tMax, found);
            local += found.size();
        }
        hits += local;
    });
    double s = since(t0);
    rate.queriesPerSecond = double(count) / s;
    rate.hitsPerSecond = double(hits) / s;
    return rate;
}

PassRate measurePasses(const PassRenderer& renderer, int passes) {
    PassRate r;
    renderer.renderPass(0);  // warm-up: page in, build caches
    auto t0 = Clock::now();
    for (int i = 1; i <= passes; ++i) renderer.renderPass(uint64_t(i), &r.totals);
    double s = since(t0);
    r.passes = passes;
    r.passesPerSecond = passes / s;
    return r;
}

}  // namespace tyndall::app
