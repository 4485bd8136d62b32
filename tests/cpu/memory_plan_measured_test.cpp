// The memory plan (cpu/memory_plan.h) against the memory a pass really allocates: every operator
// new of this executable and every byte Embree's device allocates (its memory monitor: BVH nodes,
// build references, curve buffers) is counted, and the peak above what was live before the pass is
// held to the plan. The plan's own tests (batch counts, messages) check it against itself; here a
// bound that forgets a kind of allocation (the photon cone's extra beams, the beam BVH's pieces,
// the rasterizer's bins) is exceeded by the measurement.
//
// Two photon-path shapes that meet the plan's per-path bound (photonPathBytes) nearly as written:
//   - one vertex per path next to a point light: each path's only beam is cut into the photon
//     cone's pieces (kConePieces extra beams), long thin beams (the most BVH pieces);
//   - paths that never end before maxPhotonBounces: white walls, fog without absorption, so every
//     vertex stores a beam and a surface photon.
// renderPass traces one batch at a time ("One batch at a time" in PassRenderer::renderBatches), so
// its peak must fit the image buffers plus one batch; the plan's peakBytes() holds kBatchesHeld
// (the GL splat overlapping the next batch).
#include <embree3/rtcore.h>
#include <gtest/gtest.h>
#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "cpu/memory_plan.h"
#include "cpu/pass_renderer.h"
#include "loading/mesh_builders.h"

namespace {

std::atomic<int64_t> g_live{0}, g_peak{0};

void countBytes(int64_t bytes) {
    int64_t now = g_live.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    int64_t peak = g_peak.load(std::memory_order_relaxed);
    while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
    }
}

void* countedAlloc(size_t size, size_t align) {
    void* p = align > alignof(std::max_align_t) ? aligned_alloc(align, (size + align - 1) / align * align)
                                                : std::malloc(size ? size : 1);
    if (p) countBytes(int64_t(malloc_usable_size(p)));
    return p;
}
void countedFree(void* p) {
    if (!p) return;
    countBytes(-int64_t(malloc_usable_size(p)));
    std::free(p);
}

}  // namespace

// Replacements of the global allocation functions (the whole executable, its libraries included).
void* operator new(size_t n) {
    if (void* p = countedAlloc(n, 0)) return p;
    throw std::bad_alloc();
}
void* operator new[](size_t n) { return operator new(n); }
void* operator new(size_t n, std::align_val_t a) {
    if (void* p = countedAlloc(n, size_t(a))) return p;
    throw std::bad_alloc();
}
void* operator new[](size_t n, std::align_val_t a) { return operator new(n, a); }
void* operator new(size_t n, const std::nothrow_t&) noexcept { return countedAlloc(n, 0); }
void* operator new[](size_t n, const std::nothrow_t&) noexcept { return countedAlloc(n, 0); }
void* operator new(size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return countedAlloc(n, size_t(a)); }
void* operator new[](size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return countedAlloc(n, size_t(a)); }
void operator delete(void* p) noexcept { countedFree(p); }
void operator delete[](void* p) noexcept { countedFree(p); }
void operator delete(void* p, size_t) noexcept { countedFree(p); }
void operator delete[](void* p, size_t) noexcept { countedFree(p); }
void operator delete(void* p, std::align_val_t) noexcept { countedFree(p); }
void operator delete[](void* p, std::align_val_t) noexcept { countedFree(p); }
void operator delete(void* p, size_t, std::align_val_t) noexcept { countedFree(p); }
void operator delete[](void* p, size_t, std::align_val_t) noexcept { countedFree(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { countedFree(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { countedFree(p); }

namespace tyndall {
namespace {

bool embreeMonitor(void*, ssize_t bytes, bool) {
    // Embree reports each allocation once before it happens (bytes > 0) and each free once after
    // it (bytes < 0).
    countBytes(int64_t(bytes));
    return true;
}

/// A closed room of fog around a point light; the camera inside, facing a mirror on the back wall (so
/// camera paths have secondary segments, and each batch builds its beam BVH).
Scene roomWithLight(float wallAlbedo, float sigmaS, float sigmaA) {
    Scene s;
    s.name = "memory-room";
    s.source = "<test>";
    Material wall;
    wall.name = "wall";
    wall.albedo = Rgb(wallAlbedo);
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    s.materials = {wall, mirror};
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(sigmaS);
    fog.sigmaA = Rgb(sigmaA);
    s.media.push_back(fog);
    s.globalMedium = 0;
    s.meshes.push_back(makeBox("room", Vec3(-2.0f), Vec3(2.0f), 0, /*inward=*/true));
    s.meshes.push_back(makeQuad("mirror", {-1.5f, -1.5f, -1.99f}, {3, 0, 0}, {0, 3, 0}, 1));
    Light p;
    p.name = "p";
    p.type = LightType::Point;
    p.position = {0.3f, 0.5f, -0.2f};
    p.intensity = Rgb(5.0f);
    s.lights.push_back(p);
    s.camera = Camera::lookAt({0, 0, 1.9f}, {0, 0, 0}, {0, 1, 0}, 1.0f);
    s.finalize();
    s.validate();
    return s;
}

constexpr uint32_t kPhotons = 6000;

struct Measured {
    int64_t peak = 0;  ///< bytes above what was live before the pass
    MemoryPlan plan;
    PassStats stats;
};

Measured measurePass(const Scene& s, int maxBounces, uint64_t memoryMiB) {
    RenderSettings rs;
    rs.width = 48;
    rs.height = 32;
    rs.photonsPerPass = kPhotons;
    rs.maxPhotonBounces = maxBounces;
    rs.equiangular = false;  // every beam a path can store, the point light's first ones included
    rs.memoryMiB = memoryMiB;  // several batches
    rs.seed = 9;
    // Thin beams (each the beam BVH's most pieces, kMaxPieces) with a photon cone: explicit radii.
    rs.radius = 0.004f;
    rs.surfaceRadius = 0.05f;
    rs.radiusOffset = 1000;
    rs.photonAngle = 0.02f;  // the cone reaches the full radius 0.2 from the light
    PassRenderer renderer(s, rs);
    rtcSetDeviceMemoryMonitorFunction(renderer.rayTracer().device()->get(), embreeMonitor, nullptr);
    Measured m;
    m.plan = renderer.memoryPlan();
    renderer.renderPass(0);  // warm-up: thread pools, caches, first-use allocations
    const int64_t before = g_live.load();
    g_peak.store(before);
    renderer.renderPass(1, &m.stats);
    m.peak = g_peak.load() - before;
    rtcSetDeviceMemoryMonitorFunction(renderer.rayTracer().device()->get(), nullptr, nullptr);
    return m;
}

/// Two passes at budgets `lowMiB` and `highMiB` (different batch sizes): each peak within the image
/// buffers plus one batch of the plan, and the growth of the peak per photon path of a batch (the
/// image buffers cancel) within the plan's bytesPerPath.
void expectWithinPlan(const Scene& s, int maxBounces, uint64_t lowMiB, uint64_t highMiB, double minBeamsPerPath,
                      const char* what) {
    const Measured lo = measurePass(s, maxBounces, lowMiB), hi = measurePass(s, maxBounces, highMiB);
    const double beamsPerPath = double(hi.stats.beams) / double(kPhotons);
    EXPECT_GT(beamsPerPath, minBeamsPerPath) << what << ": the paths should store that many beams";
    for (const Measured* m : {&lo, &hi}) {
        const MemoryPlan& p = m->plan;
        ASSERT_GT(p.batches, 1u) << what << ": the test wants several batches";
        const double oneBatch = double(p.imageBytes) + double(p.batchPaths) * double(p.bytesPerPath);
        std::printf("%s: %u batches of %u paths, %.2f beams/path; peak %.3f MiB, plan's image buffers + one batch "
                    "%.3f MiB (ratio %.3f)\n",
                    what, p.batches, p.batchPaths, beamsPerPath, m->peak / 1048576.0, oneBatch / 1048576.0,
                    m->peak / oneBatch);
        EXPECT_LE(double(m->peak), double(p.peakBytes())) << what << ": more memory than the plan's peak";
        EXPECT_LE(double(m->peak), oneBatch) << what << ": a CPU pass holds one batch, and it outgrew the plan";
    }
    ASSERT_GT(hi.plan.batchPaths, lo.plan.batchPaths + 100);
    const double perPath = double(hi.peak - lo.peak) / double(hi.plan.batchPaths - lo.plan.batchPaths);
    std::printf("%s: %.0f bytes per photon path measured, the plan's bound %llu (ratio %.3f)\n", what, perPath,
                (unsigned long long)hi.plan.bytesPerPath, perPath / double(hi.plan.bytesPerPath));
    EXPECT_LE(perPath, double(hi.plan.bytesPerPath)) << what << ": a photon path costs more than the plan's bound";
}

TEST(MemoryPlanMeasured, OneVertexPathsCutByThePhotonCone) {
    // Nearly every path's beam starts at the light, inside the cone's reach: 1 + kConePieces beams.
    expectWithinPlan(roomWithLight(0.5f, 0.02f, 0.0f), 1, 4, 8, 2.5, "cone");
}

TEST(MemoryPlanMeasured, PathsThatRunToTheBounceLimit) {
    // White walls, no absorption: every vertex stores a beam (and, after the first, a surface photon).
    expectWithinPlan(roomWithLight(1.0f, 0.02f, 0.0f), 6, 8, 16, 6.0, "bounce limit");
}

}  // namespace
}  // namespace tyndall
