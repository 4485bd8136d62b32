// libFuzzer target for the view-file reader (loading/scene_edits.h): any bytes that parse as a
// JSON object are loaded as a view file on one of the built-in scenes ("base" is replaced, so the
// fuzzer spends its time on the edits and the render block, not on other files) and must either
// load or throw tyndall::Error. Built and run by ctest through fuzz/run_fuzz.cmake.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "loading/scene_edits.h"
#include "loading/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    nlohmann::json doc = nlohmann::json::parse(data + 1, data + size, nullptr, false);
    if (!doc.is_object()) return 0;
    doc["base"] = (data[0] & 1) ? tyndall::kBuiltinSmokeScene : tyndall::kBuiltinDefaultScene;
    tyndall::SceneLoadOptions options;
    options.warn = [](const std::string&) {};
    options.allowExternalFiles = true;  // the base is a built-in scene: no file is read
    try {
        tyndall::loadSceneData(doc.dump(), tyndall::SceneFormat::Json, "fuzz-view.json", "", options);
    } catch (const tyndall::Error&) {
        // The expected outcome for bad input.
    }
    return 0;
}
