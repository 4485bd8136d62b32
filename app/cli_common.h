#pragma once
// Options shared by the commands that render (render, reference, bench, compare), registered on a
// CLI11 subcommand, and the helpers every command uses to load the scene and write results.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "core/image_io.h"
#include "core/load_budget.h"
#include "core/scene.h"
#include "core/settings.h"
#include "loading/homogeneous_twin.h"

namespace tyndall::app {

struct CommonOptions {
    std::string scene;   ///< empty = built-in default scene
    std::string camera;  ///< --camera NAME|INDEX; empty = the scene's first camera
    std::string environment;  ///< --environment FILE: a lat-long image lighting the scene; empty = none
    std::string output;
    std::string size = "512x512";
    float exposure = 1.0f;
    uint64_t loadMemoryMiB = LoadBudget::kDefaultMiB;  ///< --load-memory: what loading the scene may allocate
    RenderSettings settings;
    std::vector<int> region;      ///< --region X Y W H as given (finishOptions checks and sets settings.region)
    CLI::App* command = nullptr;  ///< the subcommand, to tell options given from defaults
};

/// Rejects "-3" for unsigned options (CLI11 would wrap it to 2^64 - 3) with a plain message.
CLI::Validator nonNegativeInteger();
/// Rejects 0 and negative values (and "-3" before CLI11 wraps it) for counts that must be >= 1.
CLI::Validator positiveInteger();
/// Rejects numbers <= 0, NaN and infinity (time budgets, rates' denominators).
CLI::Validator positiveNumber();

/// Adds [SCENE] --camera --environment --size --seed --threads --load-memory, and -o --exposure unless
/// `defaultOutput` is empty
/// (a command that writes no image, such as bench).
void addSceneAndOutputOptions(CLI::App* cmd, CommonOptions& o, const std::string& defaultOutput);
/// Adds the PPB options: --passes --time --photons --alpha --radius --surface-radius.
void addPpbOptions(CLI::App* cmd, CommonOptions& o);

/// Adds --gpu auto|on|off (RenderSettings::gpu) with `help`.
void addGpuOption(CLI::App* cmd, CommonOptions& o, const std::string& help);
/// --max-path-length N (RenderSettings::maxPathLength): render and reference.
void addPathLengthOption(CLI::App* cmd, CommonOptions& o);
/// --region X Y W H (RenderSettings::region): render and view.
void addRegionOption(CLI::App* cmd, CommonOptions& o);
/// Adds --simd on|off (RenderSettings::simd); part of addPpbOptions.
void addSimdOption(CLI::App* cmd, CommonOptions& o);
/// --direct-light, --surface-boundary, --equiangular and --photon-planes, each on|off (part of
/// addPpbOptions; bench and tyndall_quality add them alone).
void addDirectLightOption(CLI::App* cmd, CommonOptions& o);

/// Adds --twin support|domain: where the homogeneous twin's medium sits (loading/homogeneous_twin.h);
/// `tyndall compare` and the viewer's --compare.
void addTwinOption(CLI::App* cmd, TwinRegion& region);

/// Parses --size into the settings and validates them; throws Error naming the bad option (a
/// value out of range from the scene's render block is named by the option that sets it).
void finishOptions(CommonOptions& o);
/// The scene named on the command line (or the built-in default), finalized and validated, with
/// the camera --camera selects. The scene file's "render" block replaces the settings' defaults;
/// options given on the command line win over it (o.settings is updated and re-validated).
/// `cameraNames`/`cameras` (optional) receive the scene's selectable cameras (the viewer's list).
Scene loadScene(CommonOptions& o, std::vector<std::string>* cameraNames = nullptr, std::vector<Camera>* cameras = nullptr);
/// The loading memory budget in bytes: --load-memory when given, else defaultLoadMemoryBytes().
uint64_t loadMemoryBytes(const CommonOptions& o);
/// Throws Error (naming the file) when `path` cannot be written, before anything is rendered.
void checkOutputWritable(const std::string& path);
/// Caps TBB (and Embree through it) at `threads` workers for the life of the returned object.
class ThreadLimit {
public:
    explicit ThreadLimit(int threads);
    ~ThreadLimit();

private:
    void* m_control = nullptr;
};

}  // namespace tyndall::app
