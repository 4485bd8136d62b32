#include "loading/scene_file.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "loading/gltf_loader.h"
#include "loading/scene_json.h"

namespace tyndall {

SceneFormat sceneFormatOf(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".json") return SceneFormat::Json;
    if (ext == ".gltf") return SceneFormat::Gltf;
    if (ext == ".glb") return SceneFormat::Glb;
    throw Error("scene '" + path + "': unknown scene file type '" + ext + "' (expected .json, .gltf or .glb)");
}

SceneFile loadSceneFile(const std::string& path, const SceneLoadOptions& options) {
    SceneFormat format = sceneFormatOf(path);
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error("scene '" + path + "': no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error("scene '" + path + "': not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("scene '" + path + "': cannot be read (permissions?)");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return loadSceneData(bytes, format, path, std::filesystem::path(path).parent_path().string(), options);
}

SceneFile loadSceneData(const std::string& bytes, SceneFormat format, const std::string& file,
                        const std::string& baseDir, const SceneLoadOptions& options) {
    WarnOnce warn(options.warn);
    SceneFile out;
    SceneDraft draft;
    if (format == SceneFormat::Json) {
        draft = readSceneJson(bytes, file, baseDir, options, warn, &out);
    } else {
        draft = importGltf(bytes, format == SceneFormat::Glb, file, baseDir, options, warn);
        draft.headlightWhenDark = true;
    }
    SceneFile finished = finishScene(std::move(draft), file, options, warn);
    finished.render = std::move(out.render);
    finished.renderWhere = std::move(out.renderWhere);
    return finished;
}

}  // namespace tyndall
