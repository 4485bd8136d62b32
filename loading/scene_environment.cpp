#include "loading/scene_environment.h"

#include <filesystem>

#include "core/error.h"

namespace tyndall {

EnvironmentLight loadEnvironmentImage(const std::string& path, const std::string& where, WarnOnce& warn,
                                      LoadBudget* budget) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error(where + ": environment image '" + path + "' does not exist or is not a file");
    EnvironmentLight env = [&] {
        try {
            return EnvironmentLight::fromFile(path, budget);
        } catch (const Error& e) {
            throw Error(where + ": " + e.what());
        }
    }();
    if (env.width() != 2 * env.height())
        warn("environment aspect", where + ": environment image '" + path + "' is " + std::to_string(env.width()) +
                                       "x" + std::to_string(env.height()) +
                                       ", not 2:1 as a latitude-longitude map is: it is stretched over the sphere");
    return env;
}

EnvironmentLight readEnvironment(JsonObject& obj, const std::string& baseDir, const SceneLoadOptions& options,
                                 WarnOnce& warn) {
    auto file = obj.get("file"), radiance = obj.get("radiance");
    if (file && radiance) obj.fail("give either \"file\" or \"radiance\", not both");
    if (!file && !radiance) obj.fail("expected \"file\" (a latitude-longitude image) or \"radiance\" ([r, g, b])");
    const float scale = float(obj.number("scale", 1.0, 0.0, 1e30));
    const float rotate = float(obj.number("rotate", 0.0, -1e6, 1e6));
    const bool visible = obj.boolean("visible", true);
    obj.finish();
    EnvironmentLight env = EnvironmentLight::constant(Rgb(0.0f));
    if (file) {
        if (!options.allowExternalFiles) file->fail("references to other files are disabled");
        const std::filesystem::path path = std::filesystem::path(baseDir.empty() ? "." : baseDir) / file->string();
        env = loadEnvironmentImage(path.string(), file->where(), warn, options.budget.get());
    } else {
        env = EnvironmentLight::constant(radiance->rgb());
    }
    env.setScale(scale);
    env.setRotation(rotate);
    env.setVisible(visible);
    return env;
}

}  // namespace tyndall
