#include "bench/stage_studies.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "core/timing.h"

namespace tyndall::bench {

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
            initRayHit(rh, o, d);  // the photon tracer's ray setup
            rtcIntersect1(rt.rtcScene(), &ctx, &rh);
            localHits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        hits += localHits;
    });
    double s = secondsSince(t0);
    return double(((count + block - 1) / block) * block) / s;
}

namespace {
/// Seconds to trace `rays` through rtcIntersect1 alone, in parallel blocks of 1024.
double replaySeconds(const EmbreeScene& rt, const std::vector<Ray>& rays) {
    const size_t block = 1024;
    auto t0 = Clock::now();
    tbb::parallel_for(size_t(0), (rays.size() + block - 1) / block, [&](size_t k) {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (size_t i = k * block; i < std::min(rays.size(), (k + 1) * block); ++i) {
            RTCRayHit rh;
            initRayHit(rh, rays[i].o, rays[i].d, rays[i].tMin, rays[i].tMax);  // as the tracer sets it up
            rtcIntersect1(rt.rtcScene(), &ctx, &rh);
        }
    });
    return secondsSince(t0);
}
}  // namespace

PhotonStageRate measurePhotonStage(const PassRenderer& renderer, int passes, int rounds) {
    PhotonStageRate r;
    std::vector<Ray> rays, beamRays;
    for (int i = 0; i < passes; ++i)
        for (const PhotonBeam& b : renderer.photonTracer().traceRecordingRays(uint64_t(i), &rays).beams)
            beamRays.push_back(Ray{b.origin, b.dir});
    r.rays = rays.size();
    r.beamRays = beamRays.size();
    if (rays.empty()) return r;
    for (int round = 0; round < rounds; ++round) {
        PhotonRate tracing = app::measurePhotonTracing(renderer, passes, 1);
        if (tracing.raysPerSecond > r.tracing.raysPerSecond) r.tracing = tracing;
        r.replayRaysPerSecond =
            std::max(r.replayRaysPerSecond, double(rays.size()) / replaySeconds(renderer.rayTracer(), rays));
        r.beamReplayRaysPerSecond = std::max(r.beamReplayRaysPerSecond,
                                             double(beamRays.size()) / replaySeconds(renderer.rayTracer(), beamRays));
    }
    return r;
}

std::vector<GatherRate> measureBeamGather(const PassRenderer& renderer, const std::vector<BeamBvh::Kind>& kinds,
                                          uint64_t count, int rounds) {
    std::vector<GatherRate> best(kinds.size());
    PhotonMap photons = renderer.tracePhotons(0);
    CameraPassResult camera = renderer.traceCamera(0, photons);
    std::vector<PrimaryRay> rays;
    for (const PrimaryRay& r : camera.primary.rays)
        if (r.medium != kVacuum && r.tMax > 0) rays.push_back(r);
    if (rays.empty()) return best;
    const uint64_t perRound = std::max<uint64_t>(1, count / uint64_t(std::max(rounds, 1)));
    for (int round = 0; round < rounds; ++round) {
        for (size_t k = 0; k < kinds.size(); ++k) {
            auto tb = Clock::now();
            BeamBvh bvh(*renderer.rayTracer().device(), photons.beams, kinds[k]);
            const double build = secondsSince(tb);
            std::atomic<uint64_t> hits{0};
            const uint64_t block = 256;
            auto t0 = Clock::now();
            tbb::parallel_for(uint64_t(0), (perRound + block - 1) / block, [&](uint64_t b) {
                std::vector<BeamHitRecord> found;
                uint64_t local = 0;
                for (uint64_t i = b * block; i < std::min(perRound, (b + 1) * block); ++i) {
                    const PrimaryRay& r = rays[(i * 7919) % rays.size()];
                    bvh.query(r.origin, r.dir, r.tMax, found);
                    local += found.size();
                }
                hits += local;
            });
            const double s = secondsSince(t0);
            GatherRate& g = best[k];
            if (round == 0 || build < g.buildSeconds) g.buildSeconds = build;
            if (double(perRound) / s > g.queriesPerSecond) {
                g.queriesPerSecond = double(perRound) / s;
                g.hitsPerSecond = double(hits) / s;
            }
        }
    }
    return best;
}

void measurePassesAlternating(const PassRenderer& a, const PassRenderer& b, int passes, PassRate* rateA,
                              PassRate* rateB) {
    a.renderPass(0);
    b.renderPass(0);
    double sa = 0, sb = 0;
    for (int i = 1; i <= passes; ++i) {
        auto t0 = Clock::now();
        a.renderPass(uint64_t(i), &rateA->totals);
        sa += secondsSince(t0);
        auto t1 = Clock::now();
        b.renderPass(uint64_t(i), &rateB->totals);
        sb += secondsSince(t1);
    }
    rateA->passes = rateB->passes = passes;
    rateA->passesPerSecond = passes / sa;
    rateB->passesPerSecond = passes / sb;
}

SplatRate measureSplatKernels(const PassRenderer& renderer, int passes, int rounds) {
    struct Input {
        PhotonMap photons;
        PrimarySegments primary;
    };
    std::vector<Input> inputs;
    for (int i = 1; i <= passes; ++i) {
        Input in;
        in.photons = renderer.tracePhotons(uint64_t(i));
        in.primary = renderer.tracePrimary(uint64_t(i)).segments;
        inputs.push_back(std::move(in));
    }
    const BeamRasterizer scalar(renderer.scene(), SplatKernel::Scalar), simd(renderer.scene(), SplatKernel::Simd);
    SplatRate r;
    auto round = [&](const BeamRasterizer& raster) {
        RasterStats stats;
        auto t0 = Clock::now();
        for (const Input& in : inputs) raster.rasterize(in.primary, in.photons, &stats);
        r.evalsPerRound = stats.pixelTests;
        return double(stats.pixelTests) / secondsSince(t0);
    };
    for (int k = 0; k < rounds; ++k) {
        r.scalarEvalsPerSecond = std::max(r.scalarEvalsPerSecond, round(scalar));
        r.simdEvalsPerSecond = std::max(r.simdEvalsPerSecond, round(simd));
    }
    return r;
}

double measurePrimaryRayReplay(const PassRenderer& renderer, uint64_t pass, int rounds) {
    const RenderSettings& s = renderer.settings();
    const Camera& camera = renderer.scene().camera;
    const int w = s.width, h = s.height;
    std::vector<Ray> rays(size_t(w) * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const uint64_t pixel = uint64_t(y) * w + x;
            Rng jitter = Rng::forKey(s.seed, pass, pixel, StreamPurpose::PixelJitter);
            float jx = jitter.uniform(), jy = jitter.uniform();
            Vec2 lens{jitter.uniform(), jitter.uniform()};
            rays[pixel] = camera.generateRay(float(x) + jx, float(y) + jy, w, h, lens);
        }
    double best = 0;
    for (int k = 0; k < rounds; ++k) {
        auto t0 = Clock::now();
        tbb::parallel_for(0, h, [&](int y) {
            RTCIntersectContext ctx;
            rtcInitIntersectContext(&ctx);
            for (int x = 0; x < w; ++x) {
                const Ray& ray = rays[size_t(y) * w + x];
                RTCRayHit rh;
                initRayHit(rh, ray.o, ray.d);
                rtcIntersect1(renderer.rayTracer().rtcScene(), &ctx, &rh);
            }
        });
        best = std::max(best, double(rays.size()) / secondsSince(t0));
    }
    return best;
}

}  // namespace tyndall::bench
