#pragma once
// What `tyndall render --checkpoint` saves besides the accumulators, and the checks `--resume`
// makes before touching anything: the checkpoint's header (JSON) holds the scene file, the camera
// option, a hash of the scene, the resolved render settings (the original target included), the
// output path and exposure, whether AOV layers are kept, the passes done and the seconds spent.
#include <cstdint>
#include <functional>
#include <string>

#include "core/checkpoint.h"
#include "core/layer_accumulator.h"
#include "core/scene.h"
#include "core/settings.h"

namespace tyndall::app {

/// The render a checkpoint belongs to.
struct RenderRecord {
    std::string scenePath;  ///< "" = the built-in default scene
    std::string camera;     ///< --camera as given
    uint64_t sceneHash = 0;
    RenderSettings settings;  ///< resolved; passes / time are the render's target
    std::string output;
    float exposure = 1.0f;
    bool aov = false;
    double elapsed = 0;  ///< seconds rendered before the checkpoint, all runs together
    std::string environment;  ///< --environment as given ("" = none)
};

/// Hash of what the passes read from the scene: the scene file's bytes (for .json and .gltf),
/// then the loaded geometry (catches a changed glTF buffer or .glb), materials' and media's
/// coefficients (g and emission included), the light count, and for grid media the whole density
/// grid and emission field (DensityGrid::contentHash: every stored voxel of an OpenVDB grid, so a
/// VDB file, or its emission or temperature grid, changed behind an unchanged scene file is seen,
/// down to one voxel).
uint64_t sceneHash(const std::string& scenePath, const Scene& scene);
std::string hashText(uint64_t hash);

/// The checkpoint of `record` and `layers` (LayerAccumulator::named(), or a beauty-only
/// {"beauty", ...}); holds them as given (moved in: one copy of the sums, as the memory plan counts).
Checkpoint makeCheckpoint(const RenderRecord& record, std::vector<std::pair<std::string, Accumulator>> layers);
inline Checkpoint makeCheckpoint(const RenderRecord& record, const LayerAccumulator& acc) {
    return makeCheckpoint(record, acc.named());
}
/// The checkpoint writes of one render. A write that fails (a full disk, a missing folder) leaves
/// the previous checkpoint as it was (writes are atomic: core/checkpoint.h); the first failure is
/// reported in one line on stderr, later ones are counted, and the render goes on.
class CheckpointWrites {
public:
    explicit CheckpointWrites(std::string path) : m_path(std::move(path)) {}
    /// Saves `checkpoint` (`passes` done); false when the write failed.
    bool save(const Checkpoint& checkpoint, uint64_t passes, const std::function<void()>& midWrite = {});
    uint64_t failures() const { return m_failures; }
    /// After a render with failures: "N of M checkpoint writes failed; '<path>' holds the
    /// checkpoint of pass K" (or "... holds no checkpoint of this render"); "" when none failed.
    std::string summary() const;

private:
    std::string m_path;
    uint64_t m_writes = 0, m_failures = 0, m_lastGoodPasses = 0;
    bool m_anyGood = false;
};

/// Reads the record back; Error "<where>: ..." for a checkpoint of another kind or version.
RenderRecord readRecord(const Checkpoint& checkpoint, const std::string& where);

}  // namespace tyndall::app
