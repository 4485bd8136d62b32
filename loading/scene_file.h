#pragma once
// Loading scene files into a Scene. Three formats, chosen by extension:
//   .json  Tyndall scene description (docs/scene-format.md): optionally references a glTF file
//          and adds materials, participating media, procedural shapes, lights, cameras and
//          render settings;
//   .gltf  glTF 2.0 with embedded or external buffers;
//   .glb   binary glTF 2.0.
// A .json file with a "base" key is a view file (scene_edits.h): a base scene plus edits.
// The result is finalize()d and validate()d. Every problem with the input throws Error with one
// line naming the file and the place in it (a JSON pointer, or a glTF node/mesh/material name
// and index); features glTF has and Tyndall approximates or ignores are reported once per kind
// through SceneLoadOptions::warn. Loads are independent: safe to run on several threads.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "core/load_budget.h"
#include "core/scene.h"

namespace tyndall {

struct SceneLoadOptions {
    /// Which camera to use, by name or index into SceneFile::cameras (`--camera NAME|INDEX`);
    /// empty = the first one (the file's own "cameras" first, then the glTF's, then an automatic
    /// camera that frames the scene).
    std::string camera;
    /// Receives one line per kind of ignored/approximated feature. Empty = print
    /// "tyndall: warning: <line>" to stderr.
    std::function<void(const std::string&)> warn;
    /// Refuse scenes with more triangles than this (a bound on memory for hostile input).
    size_t maxTriangles = size_t(1) << 27;
    /// Refuse scenes whose procedural density grids hold more voxels than this, all together (a
    /// bound on load time and memory for hostile input; the built-in smoke has 0.7 M).
    uint64_t maxProceduralVoxels = uint64_t(1) << 24;
    /// `--environment FILE`: a latitude-longitude image that lights the scene (replacing the
    /// file's own "environment"; a glTF without lights then gets no headlight). "" = none.
    std::string environment;
    /// false: any reference to another file (glTF from a .json, buffers, images) is an error.
    /// The fuzzer turns it off.
    bool allowExternalFiles = true;
    /// What loading may allocate, in bytes, for grids, buffers, accessors and textures all
    /// together (`--load-memory`, core/load_budget.h).
    uint64_t loadMemoryBytes = LoadBudget::kDefaultMiB << 20;
    /// The running tally of one load against loadMemoryBytes: loadSceneData makes it when empty
    /// (callers leave it empty; a view file hands its own to the base scene's load).
    std::shared_ptr<LoadBudget> budget;
};

struct SceneFile {
    Scene scene;  ///< finalized and validated
    /// The file's "render" block (a JSON object; empty when absent), already checked with
    /// RenderSettings::fromJson. Command-line options given explicitly override it.
    nlohmann::json render = nlohmann::json::object();
    std::string renderWhere;           ///< "<file>: /render", for messages
    std::vector<std::string> cameras;  ///< the selectable cameras' names, in --camera INDEX order
    std::vector<Camera> cameraViews;   ///< those cameras, same order (the viewer's camera list)
};

enum class SceneFormat { Json, Gltf, Glb };

/// Format from the file extension (case-insensitive); throws Error naming the file otherwise.
SceneFormat sceneFormatOf(const std::string& path);

/// Reads and loads a scene file.
SceneFile loadSceneFile(const std::string& path, const SceneLoadOptions& options = {});

/// Loads a scene from memory: `bytes` in `format`, named `file` in messages, with relative
/// references resolved against `baseDir` ("" = the current directory).
SceneFile loadSceneData(const std::string& bytes, SceneFormat format, const std::string& file,
                        const std::string& baseDir, const SceneLoadOptions& options = {});

/// Reports each kind of warning once (the first message of that kind).
class WarnOnce {
public:
    explicit WarnOnce(std::function<void(const std::string&)> sink);
    void operator()(const std::string& kind, const std::string& message);

private:
    std::function<void(const std::string&)> m_sink;
    std::set<std::string> m_seen;
};

}  // namespace tyndall
