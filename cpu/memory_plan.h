#pragma once
// How much memory a render's pass loop holds, and the photon batch size that keeps it under the
// budget (`--memory`, RenderSettings::memoryMiB). A pass traces its photon paths in batches of
// `batchPaths` (fixed by the settings alone: never by the thread count or the machine, so a pass
// stays a pure function of its inputs); each batch's beams and surface photons are splatted and
// gathered, then freed, and the batch estimates are summed. Peak memory is then
//   scene + image buffers + batchesHeld x batchPaths x bytesPerPath
// whatever --photons is. bytesPerPath is a bound, not an average: a photon path stores at most one
// beam and one surface photon per vertex (maxPhotonBounces), and each beam costs its record, its
// stored free flights, its beam-BVH pieces and its rasterizer footprint and bins.
//
// The image buffers (accumulator, pass images, primary rays and hits of the passes in flight, the
// GL images, a checkpoint's copies of the sums, the EXR writer's; with --aov the layers' sums and
// images) do not shrink with batching: when they alone exceed the budget, or the budget
// exceeds the address-space limit (ulimit -v) or the physical memory, resolve() throws an Error
// that names the resource and the figures, before anything is rendered.
#include <cstdint>
#include <new>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/settings.h"

namespace tyndall {

struct MemoryPlan {
    uint64_t budgetBytes = 0;      ///< --memory
    uint64_t imageBytes = 0;       ///< buffers that scale with the image (see imageBufferBytes)
    uint64_t bytesPerPath = 0;     ///< bound on one photon path's share of a batch
    uint32_t batchPaths = 0;       ///< photon paths per batch (<= photonsPerPass)
    uint32_t batches = 0;          ///< batches per pass
    static constexpr int kBatchesHeld = 2;  ///< one being splatted (GL) while the next is traced

    /// Throws Error when the image buffers do not fit the budget, or the budget does not fit the
    /// process's address-space limit or the machine's physical memory. `freeFlights`: stored
    /// distances per beam and per pixel (0 without grid media). `aovLayers`: the render keeps the
    /// AOV layers (--aov; recorded in a checkpoint, so a resumed render plans the same batches).
    static MemoryPlan resolve(const RenderSettings& settings, int freeFlights, bool aovLayers = false);

    /// Memory the pass loop may hold at its peak (image buffers + the batches held).
    uint64_t peakBytes() const { return imageBytes + uint64_t(kBatchesHeld) * batchPaths * bytesPerPath; }
    /// One line: "--memory 2048 MiB: image buffers 96 MiB, 3 batches of 34952 photon paths ...".
    std::string describe() const;
};

/// The buffers a render at settings' size holds however its photons are batched, by kind.
struct ImageBuffers {
    uint64_t sums = 0;        ///< the accumulator's double sums (accumulatorBytes)
    uint64_t checkpoint = 0;  ///< a checkpoint's copy of the sums and its serialized bytes
    uint64_t passes = 0;      ///< the passes in flight: primary rays and hits, pass and layer images
    uint64_t output = 0;      ///< the mean image and the image writer's buffers
    uint64_t gl = 0;          ///< the GL splatter's target and uploads (not with AOV layers)
    uint64_t total() const { return sums + checkpoint + passes + output + gl; }
};
ImageBuffers imageBuffers(const RenderSettings& settings, int freeFlights, bool aovLayers = false);
/// imageBuffers(...).total(). A checkpoint's buffers are always counted (asking for checkpoints must
/// not change the batches); not counted: an MPI rank 0's gathered pass images (ranks x one pass's).
uint64_t imageBufferBytes(const RenderSettings& settings, int freeFlights, bool aovLayers = false);
/// Bytes of the render's double sums (LayerAccumulator): 24 per pixel, 5 times that with AOV layers.
uint64_t accumulatorBytes(const RenderSettings& settings, bool aovLayers);
/// Bound on the bytes one photon path adds to a batch (see the header comment).
uint64_t photonPathBytes(const RenderSettings& settings, int freeFlights);
/// "1.5 GiB", "96 MiB", "12 KiB".
std::string formatBytes(uint64_t bytes);

/// Runs f(); a std::bad_alloc escaping it becomes an Error saying what was being allocated and how
/// much, and what to do: the message every out-of-memory failure of the render loop carries.
template <class F>
auto allocating(const std::string& what, uint64_t bytes, F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const std::bad_alloc&) {
        throw Error("out of memory allocating " + what + " (" + formatBytes(bytes) +
                    "): lower --memory, --size or --photons, or raise the memory limit");
    }
}

}  // namespace tyndall
