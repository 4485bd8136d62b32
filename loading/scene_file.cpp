#include "loading/scene_file.h"

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/settings.h"
#include "loading/default_scene.h"
#include "loading/default_smoke_scene.h"
#include "loading/gltf_loader.h"
#include "loading/json_reader.h"
#include "loading/scene_edits.h"
#include "loading/scene_environment.h"
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

namespace {
/// A view file (scene_edits.h): the base scene, loaded with the camera it was viewed from, the
/// edits applied, the view file's own render block (the base's is not used).
SceneFile loadViewFile(const nlohmann::json& doc, const std::string& file, const std::string& baseDir,
                       const SceneLoadOptions& options) {
    JsonObject top = JsonValue(doc, file, "").object();
    JsonValue baseKey = top.require("base");
    auto nameKey = top.get("name"), cameraKey = top.get("base_camera");
    auto editsKey = top.get("edits"), renderKey = top.get("render");
    top.finish();
    if (!options.allowExternalFiles) baseKey.fail("references to other files are disabled");
    std::string base = baseKey.string();
    SceneLoadOptions baseOptions = options;
    baseOptions.camera = cameraKey ? cameraKey->string() : std::string();
    if (!options.camera.empty()) {
        if (editsKey && editsKey->raw().contains("camera"))
            throw Error(file + ": --camera " + options.camera + ": a view file fixes its camera (edits/camera)");
        baseOptions.camera = options.camera;
    }
    SceneFile out;
    if (base == kBuiltinDefaultScene || base == kBuiltinSmokeScene) {
        if (!baseOptions.camera.empty() && baseOptions.camera != "0" && baseOptions.camera != "default")
            baseKey.fail("the built-in scenes have one camera, 0 'default'");
        out.scene = base == kBuiltinDefaultScene ? makeDefaultScene() : makeDefaultSmokeScene();
        if (!options.environment.empty()) {
            WarnOnce warn(options.warn);
            out.scene.environment =
                loadEnvironmentImage(options.environment, "--environment", warn, options.budget.get());
        }
        out.cameras = {"default"};
        out.cameraViews = {out.scene.camera};
    } else {
        std::filesystem::path path(base);
        if (path.is_relative() && !baseDir.empty()) path = std::filesystem::path(baseDir) / path;
        out = loadSceneFile(path.string(), baseOptions);
    }
    if (editsKey) applySceneEdits(out.scene, editsKey->raw(), file);
    out.scene.source = file;
    if (nameKey) out.scene.name = nameKey->string();
    out.scene.validate();
    out.render = nlohmann::json::object();
    if (renderKey) {
        out.renderWhere = renderKey->where();
        RenderSettings::fromJson(renderKey->raw(), out.renderWhere);  // reject bad keys now
        out.render = renderKey->raw();
    }
    return out;
}
}  // namespace

SceneFile loadSceneData(const std::string& bytes, SceneFormat format, const std::string& file,
                        const std::string& baseDir, const SceneLoadOptions& givenOptions) {
    SceneLoadOptions options = givenOptions;
    if (!options.budget) options.budget = std::make_shared<LoadBudget>(options.loadMemoryBytes);
    if (format == SceneFormat::Json) {
        nlohmann::json doc = parseJsonText(bytes, file);
        if (isViewFile(doc)) return loadViewFile(doc, file, baseDir, options);
    }
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
