// A medium's "density" in scene descriptions: heterogeneous media (docs/scene-format.md).
//
//   "density": {"file": "smoke.vdb", "grid": "density", "scale": 1.5,
//               "transform": {"scale": 0.3, "rotate": {...}, "translate": [0, 0.05, 0]}}
//   "density": {"procedural": "smoke", "base": [0.45, 0, -1.3], "height": 2.7, ...}
//   "density": {"procedural": "rolling_fog", "min": [-10, 0, -4], "max": [10, 3, 10], ...}
//   "density": {"procedural": "fire", "base": [0, 0, 0], "radius": 0.3, ...}   (+ "temperature")
//
// Exactly one of "file" and "procedural". File grids: "grid" (default: "density", else the first
// float grid), "scale" (>= 0, default 1), "transform" (applied after the file's own index-to-world
// map), the path relative to the scene file. Procedural grids take their parameters in world
// units, plus "scale"; see loading/procedural_media.h for what each builds.
#include <filesystem>
#include <initializer_list>
#include <utility>

#include "core/error.h"
#include "loading/procedural_media.h"
#include "loading/scene_json.h"
#include "loading/vdb_grid.h"

namespace tyndall {

namespace {

Affine3 toAffine3(const Affine& a) {
    Affine3 r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = float(a.m[i][j]);
    return r;
}

uint32_t readSeed(JsonObject& obj, uint32_t fallback) {
    return uint32_t(obj.integer("seed", fallback, 0, 0xFFFFFFFFll));
}

std::shared_ptr<const DensityGrid> readProcedural(JsonObject& obj, const JsonValue& kind, float scale,
                                                  const SceneLoadOptions& options, uint64_t* proceduralVoxels,
                                                  DensityChannels* channels) {
    const std::string type = kind.string();
    auto checkSize = [&](uint64_t voxels) {
        const uint64_t limit = options.maxProceduralVoxels, before = *proceduralVoxels;
        if (voxels > limit || before > limit - voxels)
            obj.fail("procedural grid of " + std::to_string(voxels) + " voxels" +
                     (before > 0 ? " (after " + std::to_string(before) + " in this scene's other grids)" : "") +
                     ": at most " + std::to_string(limit) + " in all; raise voxel_size");
        *proceduralVoxels = before + voxels;
        // The values as built (4 bytes a voxel, freed after), the OpenVDB tree and the dense copy
        // kept for lookups (about 8 bytes a voxel together).
        if (options.budget) {
            const std::string what = obj.where() + ": procedural grid of " + std::to_string(voxels) + " voxels";
            options.budget->check(voxels * 12, what);
            options.budget->reserve(voxels * 8, what);
        }
    };
    // A length or a frequency in world units.
    auto positive = [&](const char* key, float value, double min = 1e-3) {
        return float(obj.number(key, value, min, 1e4));
    };
    // The "base" point a smoke column or a fire stands on, then its lengths, read in this order.
    auto baseAndLengths = [&](Vec3* base, std::initializer_list<std::pair<const char*, float*>> lengths) {
        *base = obj.vec3("base", *base);
        for (const auto& [name, value] : lengths) *value = positive(name, *value);
    };
    // The keys every procedural grid ends with (`noise`: its noise frequency, where it has one),
    // then its voxels against the budget.
    auto finish = [&](auto& p, float* noise) {
        p.voxelSize = positive("voxel_size", p.voxelSize, 1e-4);
        if (noise) *noise = positive("noise_frequency", *noise, 1e-4);
        p.seed = readSeed(obj, p.seed);
        p.densityScale = scale;
        obj.finish();
        checkSize(voxelCount(p));
    };
    if (type == "smoke") {
        ProceduralSmoke p;
        baseAndLengths(&p.base, {{"height", &p.height}, {"base_radius", &p.baseRadius}, {"top_radius", &p.topRadius}});
        finish(p, &p.noiseFrequency);
        return makeProceduralSmoke(p);
    }
    if (type == "rolling_fog") {
        RollingFog f;
        f.lo = obj.vec3("min", f.lo);
        f.hi = obj.vec3("max", f.hi);
        if (!(f.lo.x < f.hi.x && f.lo.y < f.hi.y && f.lo.z < f.hi.z))
            obj.fail("'min' must lie below 'max' on every axis");
        f.layerHeight = positive("layer_height", f.layerHeight);
        f.bankSize = positive("bank_size", f.bankSize);
        finish(f, nullptr);
        return makeRollingFog(f);
    }
    if (type == "fire") {
        ProceduralFire f;
        baseAndLengths(&f.base, {{"radius", &f.radius}, {"flame_height", &f.flameHeight}, {"height", &f.height}});
        if (f.flameHeight > f.height) obj.get("flame_height")->fail("'flame_height' must not exceed 'height'");
        f.temperature = float(obj.number("temperature", f.temperature, 1.0, 1e6));
        finish(f, &f.noiseFrequency);
        FireGrids g = makeProceduralFire(f);
        if (channels) {
            channels->procedural = "fire";
            channels->grids = {{"density", g.density}, {"temperature", g.temperature}};
        }
        return g.density;
    }
    kind.fail("expected \"smoke\", \"rolling_fog\" or \"fire\", got " + kind.describe());
}

}  // namespace

std::shared_ptr<const DensityGrid> readDensity(JsonObject& obj, const std::string& baseDir,
                                               const SceneLoadOptions& options, uint64_t* proceduralVoxels,
                                               DensityChannels* channels) {
    auto file = obj.get("file");
    auto procedural = obj.get("procedural");
    const float scale = float(obj.number("scale", 1.0, 0.0, 1e6));
    if (bool(file) == bool(procedural))
        obj.fail("a density needs exactly one of 'file' (an OpenVDB grid) and 'procedural'");
    if (procedural) {
        if (obj.has("grid") || obj.has("transform"))
            obj.fail("'grid' and 'transform' apply to file grids; procedural grids take world-space parameters");
        return readProcedural(obj, *procedural, scale, options, proceduralVoxels, channels);
    }
    if (!options.allowExternalFiles) file->fail("references to other files are disabled");
    VdbGridSource source;
    source.file = (std::filesystem::path(baseDir.empty() ? "." : baseDir) / file->string()).string();
    source.grid = obj.string("grid", "");
    source.scale = scale;
    if (auto t = obj.get("transform")) {
        JsonObject tobj = t->object();
        source.transform = toAffine3(readTransform(tobj));
    }
    obj.finish();
    if (channels) channels->file = source;
    try {
        return VdbDensityGrid::load(source, options.warn, options.budget.get());
    } catch (const Error& e) {
        file->fail(e.what());
    }
}

}  // namespace tyndall
