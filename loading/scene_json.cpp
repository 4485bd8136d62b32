#include "loading/scene_json.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/error.h"
#include "loading/gltf_loader.h"
#include "loading/scene_environment.h"
#include "core/settings.h"

namespace tyndall {

namespace {

std::string nameList(const std::vector<std::string>& names) {
    std::string out;
    for (size_t i = 0; i < names.size() && i < 12; ++i) out += (i ? ", '" : "'") + names[i] + "'";
    if (names.size() > 12) out += ", ...";
    return out.empty() ? "none" : out;
}

/// A reference by name or index into a list of named things.
template <typename T>
int resolve(const JsonValue& v, const std::vector<T>& items, const char* what) {
    if (v.isInteger()) return int(v.integer(0, int64_t(items.size()) - 1));
    if (!v.isString()) v.fail(std::string("expected a ") + what + " name or index, got " + v.describe());
    std::string name = v.string();
    std::vector<std::string> names;
    for (size_t i = 0; i < items.size(); ++i) {
        if (items[i].name == name) return int(i);
        names.push_back(items[i].name);
    }
    v.fail(std::string("no ") + what + " named '" + name + "' (there are: " + nameList(names) + ")");
}

std::string readFileText(const std::string& path, const std::string& where) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw Error(where + ": '" + path + "' does not exist or is not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(where + ": '" + path + "' cannot be read");
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

/// A material's image texture: `key` names a file relative to the scene file.
TextureRef readTexture(JsonObject& obj, const char* key, TextureEncoding enc, float scale, const std::string& baseDir,
                       const SceneLoadOptions& options, Scene& scene) {
    TextureRef ref;
    auto v = obj.get(key);
    if (!v) return ref;
    std::string rel = v->string();
    if (!options.allowExternalFiles) v->fail("references to other files are disabled");
    std::filesystem::path path = std::filesystem::path(baseDir.empty() ? "." : baseDir) / rel;
    if (!scene.textures) scene.textures = std::make_shared<TextureStore>();
    try {
        ref.texture = scene.textures->addFile(path.string(), enc, TextureWrap::Repeat, TextureWrap::Repeat, v->where(),
                                              options.budget.get());
    } catch (const Error& e) {
        v->fail(std::string("cannot read the texture: ") + e.what());
    }
    ref.transform = TextureTransform::fromOffsetRotationScale({0, 0}, 0.0f, {scale, scale});
    return ref;
}

Material readMaterial(JsonObject& obj, const std::string& baseDir, const SceneLoadOptions& options, Scene& scene) {
    Material m;
    m.name = obj.require("name").string();
    std::string type = obj.string("type", "diffuse");
    auto typeValue = obj.get("type");
    if (type == "diffuse")
        m.type = MaterialType::Diffuse;
    else if (type == "mirror")
        m.type = MaterialType::Mirror;
    else if (type == "dielectric")
        m.type = MaterialType::Dielectric;
    else if (type == "interface")
        m.type = MaterialType::Interface;
    else if (type == "plastic")
        m.type = MaterialType::Plastic;
    else
        typeValue->fail("expected one of diffuse, plastic, mirror, dielectric, interface, got " + typeValue->describe());
    const bool plastic = m.type == MaterialType::Plastic;
    m.albedo = obj.rgb("albedo", Rgb(m.type == MaterialType::Diffuse || plastic ? 0.8f : 1.0f));
    if (m.type == MaterialType::Diffuse || m.type == MaterialType::Mirror || plastic) {
        auto a = obj.get("albedo");
        if (a && m.albedo.maxComponent() > 1.0f) a->fail("a reflectance above 1 creates energy");
    }
    if (auto ior = obj.get("ior")) {
        if (m.type != MaterialType::Dielectric && !plastic)
            ior->fail("ior applies to dielectric and plastic materials only");
        m.ior = float(ior->number(plastic ? 1.0 : 1e-3, 100.0));
    }
    m.emission = obj.rgb("emission", Rgb(0.0f));
    if (auto r = obj.get("roughness")) {
        if (m.type != MaterialType::Mirror && m.type != MaterialType::Dielectric && !plastic)
            r->fail("roughness applies to mirror, dielectric and plastic materials only (diffuse is Lambertian)");
        m.roughness = float(r->number(0.0, 1.0));
        if (!plastic) m.metallic = m.type == MaterialType::Mirror ? 1.0f : 0.0f;
    }
    if (auto mt = obj.get("metallic")) {
        if (!plastic) mt->fail("metallic applies to plastic materials only (a mirror is all metal)");
        m.metallic = float(mt->number(0.0, 1.0));
    }
    float scale = float(obj.number("texture_scale", 1.0, 1e-6, 1e6));
    m.baseColorTexture = readTexture(obj, "albedo_texture", TextureEncoding::Srgb, scale, baseDir, options, scene);
    m.emissiveTexture = readTexture(obj, "emission_texture", TextureEncoding::Srgb, scale, baseDir, options, scene);
    m.metallicRoughnessTexture =
        readTexture(obj, "roughness_texture", TextureEncoding::Linear, scale, baseDir, options, scene);
    if (m.metallicRoughnessTexture.present() && !m.isSpecular() && !plastic)
        obj.get("roughness_texture")
            ->fail("roughness_texture applies to mirror, dielectric and plastic materials only");
    m.normalTexture = readTexture(obj, "normal_texture", TextureEncoding::Linear, scale, baseDir, options, scene);
    if (auto ns = obj.get("normal_scale")) {
        if (!m.normalTexture.present()) ns->fail("normal_scale needs a normal_texture");
        m.normalScale = float(ns->number(0.0, 100.0));
    }
    if (auto t = obj.get("transmission")) {
        if (m.type != MaterialType::Dielectric) t->fail("transmission applies to dielectric materials only");
        m.transmission = float(t->number(0.0, 1.0));
    }
    if (auto t = obj.get("thin")) {
        if (m.type != MaterialType::Dielectric) t->fail("thin applies to dielectric materials only");
        m.thin = t->boolean();
    }
    m.transmissionTexture =
        readTexture(obj, "transmission_texture", TextureEncoding::Linear, scale, baseDir, options, scene);
    if (m.transmissionTexture.present() && m.type != MaterialType::Dielectric)
        obj.get("transmission_texture")->fail("transmission_texture applies to dielectric materials only");
    obj.finish();
    return m;
}

Medium readMedium(JsonObject& obj, const std::string& baseDir, const SceneLoadOptions& options,
                  uint64_t* proceduralVoxels) {
    Medium m;
    m.name = obj.require("name").string();
    m.sigmaS = obj.rgb("sigma_s", Rgb(0.0f));
    m.sigmaA = obj.rgb("sigma_a", Rgb(0.0f));
    m.g = float(obj.number("g", 0.0, -0.999, 0.999));
    auto density = obj.get("density");
    auto emission = obj.get("emission");
    obj.finish();
    if (m.sigmaT().maxComponent() <= 0.0f)
        obj.fail("medium '" + m.name + "' has sigma_s + sigma_a = 0: it would be vacuum");
    DensityChannels channels;
    if (density) {
        Rgb t = m.sigmaT();
        if (std::abs(t.r - t.g) > 1e-5f * t.r || std::abs(t.r - t.b) > 1e-5f * t.r)
            obj.fail("medium '" + m.name +
                     "' has a density grid, which needs grey extinction (sigma_s + sigma_a equal in r, g, b); "
                     "put the colour in the albedo");
        JsonObject d = density->object();
        m.density = readDensity(d, baseDir, options, proceduralVoxels, &channels);
    }
    if (emission) readEmission(*emission, channels, options, m);
    return m;
}

Light readLight(JsonObject& obj, const std::string& defaultName) {
    Light l;
    l.name = obj.string("name", defaultName);
    JsonValue typeValue = obj.require("type");
    std::string type = typeValue.string();
    if (type == "point") {
        l.type = LightType::Point;
        l.position = obj.require("position").vec3();
        l.intensity = obj.require("intensity").rgb();
    } else if (type == "spot") {
        l.type = LightType::Spot;
        l.position = obj.require("position").vec3();
        auto target = obj.get("target");
        auto direction = obj.get("direction");
        if (bool(target) == bool(direction)) obj.fail("a spot light needs exactly one of 'target' and 'direction'");
        Vec3 d = target ? target->vec3() - l.position : direction->direction();
        if (!(length(d) > 0)) target->fail("target coincides with the light position");
        l.direction = normalize(d);
        l.intensity = obj.require("intensity").rgb();
        double outer = obj.number("outer_angle", 30.0, 1e-3, 90.0);
        auto innerValue = obj.get("inner_angle");
        double inner = innerValue ? innerValue->number(0.0, 90.0) : 0.0;
        if (inner >= outer) innerValue->fail("inner_angle must be smaller than outer_angle");
        l.cosOuterAngle = float(std::cos(outer * kRadiansPerDegree));
        l.cosInnerAngle = float(std::cos(inner * kRadiansPerDegree));
    } else if (type == "directional") {
        l.type = LightType::Directional;
        l.direction = normalize(obj.require("direction").direction());
        l.intensity = obj.require("irradiance").rgb();
    } else {
        typeValue.fail("expected one of point, spot, directional, got " + typeValue.describe());
    }
    obj.finish();
    return l;
}

NamedCamera readCamera(JsonObject& obj, const std::string& defaultName) {
    NamedCamera c;
    c.name = obj.string("name", defaultName);
    Vec3 eye = obj.require("position").vec3();
    auto target = obj.get("target");
    auto direction = obj.get("direction");
    if (bool(target) == bool(direction)) obj.fail("a camera needs exactly one of 'target' and 'direction'");
    Vec3 d = target ? target->vec3() - eye : direction->direction();
    if (!(length(d) > 0)) target->fail("target coincides with the camera position");
    Vec3 up = obj.get("up") ? obj.get("up")->direction() : Vec3(0, 1, 0);
    if (!(length(cross(normalize(d), normalize(up))) > 1e-4f)) obj.fail("'up' is parallel to the view direction");
    double fov = obj.number("fov", 40.0, 1e-3, 179.0);
    c.camera = Camera::lookAt(eye, target ? target->vec3() : eye + normalize(d), up, float(fov * kRadiansPerDegree));
    c.camera.focusDistance = float(obj.number("focus_distance", target ? length(d) : 1.0, 1e-6));
    c.camera.lensRadius = float(obj.number("lens_radius", 0.0, 0.0));
    obj.finish();
    return c;
}

SceneDraft readSceneJson(const std::string& text, const std::string& file, const std::string& baseDir,
                         const SceneLoadOptions& options, WarnOnce& warn, SceneFile* out) {
    nlohmann::json doc = parseJsonText(text, file);
    JsonObject top = JsonValue(doc, file, "").object();
    // Every top-level key first, so that a misspelt key is reported before its consequences.
    auto gltfKey = top.get("gltf"), nameKey = top.get("name"), renderKey = top.get("render");
    auto materialsKey = top.get("materials"), mediaKey = top.get("media"), globalKey = top.get("global_medium");
    auto shapesKey = top.get("shapes"), lightsKey = top.get("lights"), camerasKey = top.get("cameras");
    auto environmentKey = top.get("environment");
    top.finish();

    // Order: glTF contents first (meshes, materials, lights, cameras), then this file's additions.
    SceneDraft draft;
    if (const auto& gltf = gltfKey) {
        std::string rel = gltf->string();
        if (!options.allowExternalFiles) gltf->fail("references to other files are disabled");
        std::filesystem::path path = std::filesystem::path(baseDir.empty() ? "." : baseDir) / rel;
        std::string ext = path.extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".gltf" && ext != ".glb") gltf->fail("expected a .gltf or .glb file, got '" + rel + "'");
        std::string bytes = readFileText(path.string(), gltf->where());
        draft = importGltf(bytes, ext == ".glb", path.string(), path.parent_path().string(), options, warn);
    }
    Scene& scene = draft.scene;
    scene.name = nameKey ? nameKey->string() : std::filesystem::path(file).stem().string();

    if (const auto& render = renderKey) {
        out->renderWhere = render->where();
        RenderSettings::fromJson(render->raw(), out->renderWhere);  // reject bad keys now
        out->render = render->raw();
    }

    const size_t gltfMaterials = scene.materials.size();
    if (const auto& list = materialsKey) {
        std::map<std::string, std::string> seen;  // name -> where first defined in this file
        for (const JsonValue& v : list->elements()) {
            JsonObject obj = v.object();
            Material m = readMaterial(obj, baseDir, options, scene);
            if (seen.count(m.name)) v.fail("material '" + m.name + "' is already defined at " + seen[m.name]);
            seen[m.name] = v.pointer();
            // A material named like a glTF material replaces it (its meshes take the new one).
            bool replaced = false;
            for (size_t i = 0; i < gltfMaterials && !replaced; ++i)
                if (scene.materials[i].name == m.name) scene.materials[i] = m, replaced = true;
            if (!replaced) scene.materials.push_back(m);
        }
    }

    struct Placement {
        MediumId medium;
        JsonValue inside;
    };
    std::vector<Placement> placements;
    std::vector<bool> placed;
    const size_t gltfMedia = scene.media.size();
    placed.assign(gltfMedia, true);
    if (const auto& list = mediaKey) {
        uint64_t proceduralVoxels = 0;
        for (const JsonValue& v : list->elements()) {
            JsonObject obj = v.object();
            auto inside = obj.get("inside");
            Medium m = readMedium(obj, baseDir, options, &proceduralVoxels);
            for (const Medium& other : scene.media)
                if (other.name == m.name) v.fail("medium '" + m.name + "' is defined twice");
            scene.media.push_back(m);
            placed.push_back(bool(inside));
            if (inside) placements.push_back({MediumId(scene.media.size() - 1), *inside});
        }
    }
    if (const auto& global = globalKey) {
        scene.globalMedium = resolve(*global, scene.media, "medium");
        placed[size_t(scene.globalMedium)] = true;
    }
    if (const auto& list = shapesKey) {
        std::vector<JsonValue> shapes = list->elements();
        for (size_t i = 0; i < shapes.size(); ++i) {
            JsonObject obj = shapes[i].object();
            int material = resolve(obj.require("material"), scene.materials, "material");
            std::string type = obj.has("type") && obj.value().raw()["type"].is_string()
                                   ? obj.value().raw()["type"].get<std::string>()
                                   : "shape";
            // "exterior": the medium on the side the normals face, instead of the one found by
            // containment (core/medium_nesting.h); "vacuum" for none.
            MediumId exterior = kInheritMedium;
            if (auto e = obj.get("exterior")) {
                if (e->isString() && e->string() == "vacuum") {
                    exterior = kVacuum;
                } else {
                    exterior = resolve(*e, scene.media, "medium");
                    placed[size_t(exterior)] = true;
                }
            }
            TriangleMesh mesh =
                readShape(obj, type + " " + std::to_string(i), material, scene.triangleCount(), options);
            mesh.exteriorMedium = exterior;
            scene.meshes.push_back(std::move(mesh));
        }
    }
    for (size_t i = gltfMedia; i < scene.media.size(); ++i)
        if (!placed[i])
            throw Error(file + ": medium '" + scene.media[i].name +
                        "' is not used: give it \"inside\", name it in \"global_medium\" or in a shape's \"exterior\"");

    if (const auto& list = lightsKey) {
        std::vector<JsonValue> lights = list->elements();
        for (size_t i = 0; i < lights.size(); ++i) {
            JsonObject obj = lights[i].object();
            scene.lights.push_back(readLight(obj, "light " + std::to_string(i)));
        }
    }

    if (const auto& env = environmentKey) {
        JsonObject obj = env->object();
        scene.environment = readEnvironment(obj, baseDir, options, warn);
    }

    if (const auto& list = camerasKey) {
        std::vector<NamedCamera> own;
        std::vector<JsonValue> cams = list->elements();
        for (size_t i = 0; i < cams.size(); ++i) {
            JsonObject obj = cams[i].object();
            own.push_back(readCamera(obj, "camera " + std::to_string(i)));
        }
        draft.cameras.insert(draft.cameras.begin(), own.begin(), own.end());  // the file's cameras come first
    }

    // Media inside meshes, after all meshes exist.
    std::vector<int> owner(scene.meshes.size(), -1);
    for (const Placement& p : placements) {
        std::vector<JsonValue> refs = p.inside.isArray() ? p.inside.elements() : std::vector<JsonValue>{p.inside};
        if (refs.empty()) p.inside.fail("expected a mesh name or index, or a non-empty array of them");
        for (const JsonValue& r : refs) {
            std::vector<int> meshes;
            if (r.isInteger()) {
                if (scene.meshes.empty()) r.fail("the scene has no meshes");
                meshes.push_back(int(r.integer(0, int64_t(scene.meshes.size()) - 1)));
            } else if (r.isString()) {
                meshes = meshesNamed(scene, r.string());
                std::vector<std::string> names;
                for (const TriangleMesh& m : scene.meshes) names.push_back(m.name);
                if (meshes.empty()) r.fail("no mesh named '" + r.string() + "' (there are: " + nameList(names) + ")");
            } else {
                r.fail("expected a mesh name or index, got " + r.describe());
            }
            for (int mi : meshes) {
                TriangleMesh& mesh = scene.meshes[size_t(mi)];
                std::string which = "mesh '" + mesh.name + "' (index " + std::to_string(mi) + ")";
                if (owner[size_t(mi)] >= 0 && owner[size_t(mi)] != p.medium)
                    r.fail(which + " already holds medium '" + scene.media[size_t(owner[size_t(mi)])].name + "'");
                if (!mesh.isClosed())
                    r.fail(which + " is not closed: a medium needs a closed, consistently oriented mesh");
                mesh.interiorMedium = p.medium;
                owner[size_t(mi)] = p.medium;
            }
        }
    }

    return draft;
}

}  // namespace tyndall
