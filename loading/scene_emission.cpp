// A medium's "emission" in scene descriptions (docs/scene-format.md): the radiance Le of the
// source term sigma_a * Le (core/medium.h).
//
//   "emission": [r, g, b]                 Le everywhere the medium is (grid media: Le where the
//                                         density is, sigma_a(p) = density(p) sigma_a)
//   "emission": {"grid": "flames", "color": [r, g, b], "scale": s}
//                                         Le(p) = s * color * flames(p)
//   "emission": {"grid": "temperature", "blackbody": true, "scale": s,
//                "temperature_scale": k, "temperature_offset": t0}
//                                         Le(p) = s * blackbody((temperature(p) - t0) * k kelvin)
//
// Grids come from the density's own file, through the density's transform, or from the grids a
// procedural fire builds beside its density ("temperature", kelvin); they may have another
// resolution or voxel transform than the density (both are sampled at world points). They must
// be float grids; negative voxels read as 0 (loading/vdb_grid.h). A positive background is the
// field's value away from its voxels (an ambient temperature; voxels below it read as it), and
// emission stays where the density is (the source term is sigma_a * density * Le). Defaults: color [1, 1, 1], scale 1, temperature_scale 1,
// temperature_offset 0.
#include "core/error.h"
#include "core/grid_emission.h"
#include "loading/scene_json.h"

namespace tyndall {

void readEmission(const JsonValue& value, const DensityChannels& channels, const SceneLoadOptions& options,
                  Medium& m) {
    auto needsAbsorption = [&]() {
        if (m.sigmaA.isBlack())
            value.fail("medium '" + m.name +
                       "' emits but has sigma_a = 0: the source term is sigma_a * Le, so a medium emits only "
                       "where it absorbs; give it a sigma_a > 0");
    };
    if (!value.isObject()) {
        m.emission = value.rgb();
        if (!m.emission.isBlack()) needsAbsorption();
        return;
    }
    JsonObject obj(value);
    JsonValue grid = obj.require("grid");
    const std::string name = grid.string();
    const bool blackbody = obj.boolean("blackbody", false);
    const float scale = float(obj.number("scale", 1.0, 0.0, 1e12));
    GridEmission::Blackbody bb;
    Rgb color(1.0f);
    if (blackbody) {
        if (obj.has("color")) obj.get("color")->fail("'color' applies to emission grids without \"blackbody\"");
        bb.scale = scale;
        bb.temperatureScale = float(obj.number("temperature_scale", 1.0, 0.0, 1e12));
        bb.temperatureOffset = float(obj.number("temperature_offset", 0.0, -1e12, 1e12));
    } else {
        for (const char* key : {"temperature_scale", "temperature_offset"})
            if (obj.has(key)) obj.get(key)->fail(std::string("'") + key + "' applies to \"blackbody\": true");
        color = obj.rgb("color", Rgb(1.0f));
    }
    obj.finish();
    auto make = [&](std::shared_ptr<const DensityGrid> values, float ambient) {
        if (blackbody)
            m.emissionField = std::make_shared<GridEmission>(std::move(values), bb, ambient);
        else
            m.emissionField = std::make_shared<GridEmission>(std::move(values), color, scale, ambient);
    };
    if (m.density && !channels.procedural.empty()) {
        needsAbsorption();
        std::string names;
        for (const auto& [gridName, values] : channels.grids) {
            if (gridName == name) return make(values, 0.0f);
            names += (names.empty() ? "'" : ", '") + gridName + "'";
        }
        grid.fail("procedural " + channels.procedural + " has no grid named '" + name + "' (its grids: " + names + ")");
    }
    if (!m.density || channels.file.file.empty())
        value.fail("an emission grid is read from the medium's density file or procedural fire: give the medium a "
                   "\"density\" with a \"file\" or \"procedural\": \"fire\"");
    needsAbsorption();
    VdbGridSource source = channels.file;
    source.grid = name;
    source.scale = 1.0f;
    source.ambientBackground = true;
    std::shared_ptr<const VdbDensityGrid> values;
    try {
        values = VdbDensityGrid::load(source, options.warn, options.budget.get());
    } catch (const Error& e) {
        grid.fail(e.what());
    }
    make(values, values->background());
}

}  // namespace tyndall
