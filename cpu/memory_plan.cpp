#include "cpu/memory_plan.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "core/photon_beam.h"
#include "cpu/beam_cone.h"
#include "core/primary_segments.h"
#include "cpu/camera_tracer.h"

namespace tyndall {

namespace {
constexpr uint64_t kMiB = 1024 * 1024;
// Rows per band of the CPU beam rasterizer (cpu/beam_rasterizer.cpp): a beam is binned once per
// band its footprint reaches.
constexpr uint64_t kRasterBand = 8;
// Beam-BVH pieces per beam at most (cpu/beam_bvh.cpp) and the bytes each costs: the Piece record
// (12, doubled by vector growth), two curve vertices (32) and an index (4) in Embree's buffers,
// and Embree's BVH nodes and build references (measured: ~100 per primitive).
constexpr uint64_t kPiecesPerBeam = 8;
constexpr uint64_t kBytesPerPiece = 24 + 32 + 4 + 100;
// Float images (12 B/pixel) a pass in flight may hold: its secondary radiance and pass image, the
// CPU splat, the GL splat sum and the two pending GL splats, and their sums.
constexpr uint64_t kImagesPerPass = 8;
// AOV layers: LayerAccumulator's double sums (beauty, its three components, the beauty squares).
constexpr uint64_t kAovAccumulators = 5;
// Float images an AOV pass adds (PassRenderer::renderPassLayers, the render driver's MPI rounds):
// its three component images, the secondary stage's three parts, and the packed, gathered and
// unpacked copies of its four images.
constexpr uint64_t kAovImagesPerPass = 3 + 3 + 3 * 4;
// A checkpoint's JSON header (the resolved settings, paths) and layer records: a few KiB.
constexpr uint64_t kCheckpointHeaderBytes = 64 * 1024;
}  // namespace

uint64_t accumulatorBytes(const RenderSettings& s, bool aovLayers) {
    return uint64_t(s.width) * uint64_t(s.height) * 3 * sizeof(double) * (aovLayers ? kAovAccumulators : 1);
}

ImageBuffers imageBuffers(const RenderSettings& s, int freeFlights, bool aovLayers) {
    const uint64_t pixels = uint64_t(s.width) * uint64_t(s.height);
    const uint64_t ff = 4 * uint64_t(freeFlights);
    const uint64_t perPass = sizeof(PrimaryRay) + ff + sizeof(PrimaryHit) + kImagesPerPass * sizeof(Rgb);
    ImageBuffers b;
    b.sums = accumulatorBytes(s, aovLayers);
    // A checkpoint holds a copy of the sums (the Checkpoint's layers) and its serialized bytes (the
    // sums again, the JSON header, the layer names). Counted whether or not --checkpoint is given:
    // asking for checkpoints (and so resuming) never changes the batches, nor the image's rounding.
    b.checkpoint = 2 * b.sums + kCheckpointHeaderBytes;
    if (!aovLayers) {
        const uint64_t passesInFlight = 2;  // the scheduler's queue (1) and the pass being traced
        b.passes = pixels * passesInFlight * perPass;
        b.output = pixels * (sizeof(Rgb) + 16);               // the mean and the writer's converted copy
        b.gl = pixels * (16 + sizeof(PrimaryRay) + ff);      // RGBA32F target, uploaded rays and distances
    } else {
        // AOV layers: one pass at a time on the CPU (with GL a second pass may wait for its splat;
        // its images are not counted here); the EXR writer holds the mean, the four layer images
        // and the 15 interleaved channels.
        b.passes = pixels * (perPass + kAovImagesPerPass * sizeof(Rgb));
        b.output = pixels * (sizeof(Rgb) * (1 + 4) + 15 * sizeof(float));
    }
    return b;
}

uint64_t imageBufferBytes(const RenderSettings& s, int freeFlights, bool aovLayers) {
    return imageBuffers(s, freeFlights, aovLayers).total();
}

uint64_t photonPathBytes(const RenderSettings& s, int freeFlights) {
    const uint64_t ff = 4 * uint64_t(freeFlights);
    const uint64_t bands = (uint64_t(s.height) + kRasterBand - 1) / kRasterBand;
    // Per-block parts (capacity up to 2x) and the merged batch: 3 copies of every record.
    const uint64_t beam = 3 * (sizeof(PhotonBeam) + ff) + kPiecesPerBeam * kBytesPerPiece +
                          32 /* footprint */ + 2 * 4 * bands /* band bins, doubled by growth */ +
                          (s.photonPlanes ? 3 * sizeof(PhotonPlane) + 64 /* its quad in the plane BVH */ : 0) +
                          (s.mediumPointMfp > 0 ? RenderSettings::kMediumPointsPerBeam *
                                                      (3 * sizeof(MediumPoint) + 64 /* its box in the point BVH */)
                                                : 0);
    const uint64_t photon = 3 * sizeof(SurfacePhoton) + 4 + 4 + 16 /* hash grid */;
    // The photon cone (cpu/beam_cone.h) adds at most kConePieces beams to a path.
    return uint64_t(std::max(s.maxPhotonBounces, 1)) * (beam + photon) + uint64_t(kConePieces) * beam;
}

std::string formatBytes(uint64_t bytes) {
    char text[32];
    if (bytes >= 1024 * kMiB)
        std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1024 * kMiB));
    else if (bytes >= kMiB)
        std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(kMiB));
    else
        std::snprintf(text, sizeof text, "%.0f KiB", double(bytes) / 1024.0);
    return text;
}

MemoryPlan MemoryPlan::resolve(const RenderSettings& s, int freeFlights, bool aovLayers) {
    MemoryPlan plan;
    plan.budgetBytes = s.memoryMiB * kMiB;
    plan.imageBytes = imageBufferBytes(s, freeFlights, aovLayers);
    plan.bytesPerPath = photonPathBytes(s, freeFlights);

    const std::string size = std::to_string(s.width) + "x" + std::to_string(s.height);
    struct rlimit as {};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY && plan.budgetBytes > uint64_t(as.rlim_cur))
        throw Error("--memory " + formatBytes(plan.budgetBytes) + " is more than this process's address-space limit " +
                    "(ulimit -v) of " + formatBytes(uint64_t(as.rlim_cur)) +
                    ": lower --memory to well under it (the program itself needs a few hundred MiB)");
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    if (pages > 0 && pageSize > 0 && plan.budgetBytes > uint64_t(pages) * uint64_t(pageSize))
        throw Error("--memory " + formatBytes(plan.budgetBytes) + " is more than this machine's physical memory (" +
                    formatBytes(uint64_t(pages) * uint64_t(pageSize)) + "): lower --memory");
    // The smallest batch worth splatting: below it the per-batch work (the camera's secondary
    // stage, a BVH build) would dominate.
    const uint64_t minPaths = std::min<uint64_t>(256, s.photonsPerPass);
    const uint64_t minBytes = plan.imageBytes + uint64_t(kBatchesHeld) * minPaths * plan.bytesPerPath;
    if (minBytes > plan.budgetBytes)
        throw Error("--size " + size + " needs " + formatBytes(plan.imageBytes) +
                    " of image buffers (accumulator" + std::string(aovLayers ? " and AOV layers" : "") +
                    ", checkpoint, pass images, primary rays; " +
                    std::to_string(plan.imageBytes / (uint64_t(s.width) * s.height)) + " bytes per pixel) plus " +
                    formatBytes(minBytes - plan.imageBytes) + " for the smallest photon batches, more than --memory " +
                    formatBytes(plan.budgetBytes) + ": lower --size or raise --memory");
    const uint64_t fit = (plan.budgetBytes - plan.imageBytes) / (uint64_t(kBatchesHeld) * plan.bytesPerPath);
    plan.batchPaths = uint32_t(std::min<uint64_t>(fit, s.photonsPerPass));
    plan.batches = uint32_t((uint64_t(s.photonsPerPass) + plan.batchPaths - 1) / plan.batchPaths);
    return plan;
}

std::string MemoryPlan::describe() const {
    return "--memory " + formatBytes(budgetBytes) + ": image buffers " + formatBytes(imageBytes) + ", " +
           std::to_string(batches) + (batches == 1 ? " batch" : " batches") + " of up to " +
           std::to_string(batchPaths) + " photon paths per pass (at most " + formatBytes(bytesPerPath) +
           " each), peak " + formatBytes(peakBytes()) + " besides the scene";
}

}  // namespace tyndall
