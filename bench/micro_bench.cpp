// Microbenchmarks (Google Benchmark) of the innermost PPB routines: the beam x ray estimator, HG
// sampling, the radius schedule, free-flight sampling (homogeneous and density-grid media), texture
// lookups and building the surface kernel's boundary (SurfaceBoundary: feature half-edges, their
// layer probe, the pre-check grid and the point-query BVH) for the largest glTF asset.
// Whole-stage throughput (photon tracing, gathers, passes/s) is `tyndall bench` and
// build/bench/tyndall_stages; these isolate the per-call cost of what those stages call millions
// of times. Not run by ctest.
//
// Run (Release build):
//   cmake --build build --target micro_bench && build/bench/micro_bench
//   build/bench/micro_bench --benchmark_filter=FreeFlight --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include <atomic>
#include <vector>

#include "core/beam_estimator.h"
#include "loading/default_smoke_scene.h"
#include "core/phase.h"
#include "core/radius_schedule.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/texture.h"
#include "cpu/embree_scene.h"
#include "cpu/free_flight.h"
#include "cpu/surface_boundary.h"
#include "loading/scene_file.h"

namespace tyndall {
namespace {

Vec3 randomDirection(Rng& rng) {
    return sampleUniformSphere(rng.uniform(), rng.uniform());
}

/// Beams and camera segments crossing a unit box, so most pairs are tested but few contribute
/// (as in a gather, where the BVH has already culled the far ones).
struct EstimatorInputs {
    std::vector<PhotonBeam> beams;
    std::vector<Ray> segments;
    explicit EstimatorInputs(size_t n) {
        Rng rng(7, 1);
        for (size_t i = 0; i < n; ++i) {
            PhotonBeam b;
            b.origin = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
            b.dir = randomDirection(rng);
            b.tMax = 1.0f;
            b.radius = 0.05f;
            b.power = Rgb(0.01f);
            b.medium = 0;
            beams.push_back(b);
            Ray r{Vec3(rng.uniform(), rng.uniform(), rng.uniform()), randomDirection(rng)};
            r.tMax = 1.0f;
            segments.push_back(r);
        }
    }
};

void BM_BeamRayEstimator(benchmark::State& state) {
    const EstimatorInputs in(1024);
    const Rgb sigmaS(0.3f), tr(0.8f);
    size_t i = 0, hits = 0;
    Rgb sum;
    for (auto _ : state) {
        const Ray& r = in.segments[i & 1023];
        const PhotonBeam& b = in.beams[(i * 7 + 3) & 1023];
        BeamRayHit hit;
        if (intersectBeamRay(r.o, r.d, r.tMax, b, &hit)) {
            sum += beamRadiance(hit, b, sigmaS, 0.5f, tr, tr);
            ++hits;
        }
        ++i;
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(int64_t(state.iterations()));
    state.counters["hit_fraction"] = double(hits) / double(std::max<size_t>(i, 1));
}
BENCHMARK(BM_BeamRayEstimator);

void BM_SampleHg(benchmark::State& state) {
    const float g = float(state.range(0)) / 10.0f;
    Rng rng(3, 2);
    Vec3 d(0, 0, 1), acc(0.0f);
    for (auto _ : state) {
        d = sampleHg(d, g, rng.uniform(), rng.uniform());
        acc += d;
    }
    benchmark::DoNotOptimize(acc);
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_SampleHg)->Arg(0)->Arg(5)->Arg(-9);  // g = 0, 0.5, -0.9

void BM_RadiusSchedule(benchmark::State& state) {
    // Offset 0 starts on the lgamma branch (n < 1000); the default offset runs the asymptotic series.
    const RadiusSchedule schedule(0.5, uint64_t(state.range(0)));
    uint64_t j = 0;
    double sum = 0;
    for (auto _ : state) sum += schedule.beamFactor(j++ & 511);
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_RadiusSchedule)->Arg(0)->Arg(1000);

void BM_FreeFlightHomogeneous(benchmark::State& state) {
    Medium fog;
    fog.sigmaS = Rgb(0.5f, 0.6f, 0.7f);
    fog.sigmaA = Rgb(0.05f);
    Rng rng(5, 3);
    const Ray ray{Vec3(0.0f), Vec3(0, 0, 1)};
    float sum = 0;
    for (auto _ : state) {
        FreeFlight ff = sampleFreeFlight(fog, ray, 2.0f, rng);
        sum += ff.t + ff.weight.r;
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_FreeFlightHomogeneous);

/// Collision distances through the built-in smoke scene's grid (delta tracking over the majorant
/// grid), along rays across its bounds.
void BM_FreeFlightGrid(benchmark::State& state) {
    static const Scene scene = [] {
        Scene s = makeDefaultSmokeScene();
        s.validate();
        return s;
    }();
    const Medium* smoke = nullptr;
    for (const Medium& m : scene.media)
        if (!m.homogeneous()) smoke = &m;
    if (!smoke) {
        state.SkipWithError("the default smoke scene has no grid medium");
        return;
    }
    const Bounds3 box = smoke->density->bounds();
    const Vec3 extent = box.hi - box.lo;
    std::vector<Ray> rays;
    Rng setup(11, 4);
    for (int i = 0; i < 256; ++i) {
        Vec3 o(box.lo.x + setup.uniform() * extent.x, box.lo.y + setup.uniform() * extent.y,
               box.lo.z + setup.uniform() * extent.z);
        rays.push_back(Ray{o, randomDirection(setup)});
    }
    const float tEnd = length(extent);
    Rng rng(13, 5);
    size_t i = 0;
    float sum = 0;
    for (auto _ : state) sum += sampleCollisionDistance(*smoke, rays[i++ & 255], tEnd, rng);
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_FreeFlightGrid);

// Texture lookups through the TextureSystem (core/texture.h): a 1024x1024 RGBA texture, random uv,
// footprint 0 (finest level, bilinear) and 1/256 (a few texels: trilinear); items/s = lookups/s.
// Baseline in the same run: Arg 0 reads the same values from a std::vector (no filtering).
void BM_TextureLookup(benchmark::State& state) {
    static TextureStore store;
    static int id = [] {
        std::vector<float> px(1024 * 1024 * 4);
        Rng rng = Rng::forKey(1, 0, 0, StreamPurpose::Test);
        for (float& v : px) v = rng.uniform();
        return store.addPixels(1024, 1024, 4, px, TextureEncoding::Srgb, TextureWrap::Repeat, TextureWrap::Repeat,
                               "bench");
    }();
    static std::vector<float> plain(1024 * 1024 * 4, 0.5f);
    Rng rng = Rng::forKey(2, 0, 0, StreamPurpose::Test);
    float width = state.range(0) == 2 ? 1.0f / 256 : 0.0f;
    float sum = 0;
    for (auto _ : state) {
        Vec2 uv{rng.uniform(), rng.uniform()};
        if (state.range(0) == 0) {
            size_t at = (size_t(uv.y * 1023) * 1024 + size_t(uv.x * 1023)) * 4;
            sum += plain[at];
        } else {
            sum += store.lookup(id, uv, width)[0];
        }
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(state.iterations());
    TextureStats st = store.stats();
    state.counters["cacheMB"] = double(st.cacheBytes) / (1024.0 * 1024.0);
    state.counters["fileMB"] = double(st.fileBytes) / (1024.0 * 1024.0);
}
BENCHMARK(BM_TextureLookup)->Arg(0)->Arg(1)->Arg(2);  // 0: plain array baseline, 1: width 0, 2: width 1/256

// SurfaceBoundary's construction (cpu/surface_boundary.h) on the largest glTF asset (by file size;
// Arg 1: the one with the most triangles), ../shared/assets relative to the working directory (run
// from the project root). Counters: feature half-edges, the pre-check's cells, and the memory it
// keeps: the edges and the grid, plus the bytes Embree allocated for its BVH (the device's memory
// monitor, while building).
void BM_SurfaceBoundaryBuild(benchmark::State& state) {
    const char* files[] = {"../shared/assets/gltf/GlassVaseFlowers/GlassVaseFlowers.glb",
                           "../shared/assets/gltf/TransmissionRoughnessTest/TransmissionRoughnessTest.glb"};
    SceneFile file;
    try {
        file = loadSceneFile(files[state.range(0)]);
    } catch (const std::exception& e) {
        state.SkipWithError((std::string("asset not found (run from the project root): ") + e.what()).c_str());
        return;
    }
    const EmbreeScene rt(file.scene);
    static std::atomic<int64_t> embreeBytes{0};
    rtcSetDeviceMemoryMonitorFunction(
        rt.device()->get(), [](void*, ssize_t bytes, bool) { embreeBytes += bytes; return true; }, nullptr);
    int64_t peak = 0;
    size_t edges = 0, cells = 0, kept = 0;
    for (auto _ : state) {
        embreeBytes = 0;
        SurfaceBoundary b(file.scene, rt);
        peak = std::max<int64_t>(peak, embreeBytes.load());
        edges = b.featureEdgeCount(), cells = b.clearanceGrid().cellCount(), kept = b.memoryBytes();
        benchmark::DoNotOptimize(b);
    }
    rtcSetDeviceMemoryMonitorFunction(rt.device()->get(), nullptr, nullptr);
    size_t triangles = 0;
    for (const TriangleMesh& m : file.scene.meshes) triangles += m.triangleCount();
    state.counters["triangles"] = double(triangles);
    state.counters["featureEdges"] = double(edges);
    state.counters["gridCells"] = double(cells);
    state.counters["keptKiB"] = double(kept) / 1024.0;
    state.counters["embreeKiB"] = double(peak) / 1024.0;
}
BENCHMARK(BM_SurfaceBoundaryBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace tyndall

BENCHMARK_MAIN();
