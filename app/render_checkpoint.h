#pragma once
// What `tyndall render --checkpoint` saves besides the accumulators, and the checks `--resume`
// makes before touching anything: the checkpoint's header (JSON) holds the scene file, the camera
// option, a hash of the scene, the resolved render settings (the original target included), the
// output path and exposure, whether AOV layers are kept, the passes done and the seconds spent.
#include <cstdint>
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
/// coefficients and the light count. A VDB file changed behind an unchanged scene file is not
/// seen (its bytes are not re-read).
uint64_t sceneHash(const std::string& scenePath, const Scene& scene);
std::string hashText(uint64_t hash);

/// The checkpoint of `record` and `layers` (LayerAccumulator::named(), or a beauty-only
/// {"beauty", ...}); holds them as given (moved in: one copy of the sums, as the memory plan counts).
Checkpoint makeCheckpoint(const RenderRecord& record, std::vector<std::pair<std::string, Accumulator>> layers);
inline Checkpoint makeCheckpoint(const RenderRecord& record, const LayerAccumulator& acc) {
    return makeCheckpoint(record, acc.named());
}
/// Reads the record back; Error "<where>: ..." for a checkpoint of another kind or version.
RenderRecord readRecord(const Checkpoint& checkpoint, const std::string& where);

}  // namespace tyndall::app
