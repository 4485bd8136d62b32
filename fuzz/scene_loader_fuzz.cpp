// libFuzzer target for the scene loader: any bytes, as a Tyndall scene description, a .gltf or a
// .glb (chosen by content), must either load or throw tyndall::Error. Any other exception, a
// crash, a leak or an AddressSanitizer report is a bug. Built and run by ctest through
// fuzz/run_fuzz.cmake (clang, -fsanitize=fuzzer,address); see fuzz/CMakeLists.txt.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "loading/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    tyndall::SceneFormat format = tyndall::SceneFormat::Json;
    if (bytes.compare(0, 4, "glTF") == 0)
        format = tyndall::SceneFormat::Glb;
    else if (bytes.find("\"asset\"") != std::string::npos)
        format = tyndall::SceneFormat::Gltf;

    tyndall::SceneLoadOptions options;
    options.warn = [](const std::string&) {};
    // Keep hostile sizes inside the fuzzer's memory limit and its 10 s per-input timeout: under
    // ASan a procedural grid costs about 1 us a voxel (the loader's 2^24 would take ~16 s; 2^20
    // about 1 s, and the built-in smoke, 0.7 M voxels, still fits).
    options.maxTriangles = size_t(1) << 20;
    options.maxProceduralVoxels = uint64_t(1) << 20;
    options.allowExternalFiles = false;
    try {
        tyndall::loadSceneData(bytes, format, "fuzz-input", "", options);
    } catch (const tyndall::Error&) {
        // The expected outcome for bad input.
    }
    return 0;
}
