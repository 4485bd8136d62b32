#include "loading/gltf_loader.h"

#include <tiny_gltf.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <tuple>
#include <sstream>

#include "core/error.h"
#include "core/load_budget.h"
#include "loading/gltf_accessor.h"
#include "loading/gltf_json_check.h"
#include "loading/gltf_material_mapping.h"
#include "loading/json_reader.h"
#include "core/photometry.h"
#include "core/transform.h"

namespace tyndall {

namespace {

namespace fs = std::filesystem;

// ---- File access for tinygltf: regular files inside the base directory only. tinygltf joins the
// URI to the base directory as text and also tries the current directory, so "../x.bin", a
// sibling folder that shares the base's name as a prefix, an absolute path or a symbolic link
// leading out would otherwise reach unrelated files.
struct FileAccess {
    std::string baseDir;     // absolute, lexically normal: what tinygltf joins URIs to
    fs::path canonicalBase;  // symbolic links resolved: what a file must lie inside
    bool allowed = true;
    std::string file;              // the glTF file, for messages
    LoadBudget* budget = nullptr;  // asked for each file's size before it is read
    std::string refused;           // the budget's message when it refused a file
};

/// Whether `path` lies strictly inside `base`, comparing whole path components after resolving
/// ".", ".." and symbolic links.
bool insideBase(const std::string& path, const fs::path& base) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
    if (ec || base.empty()) return false;
    auto b = base.begin(), q = p.begin();
    for (; b != base.end(); ++b, ++q) {
        if (b->empty()) continue;  // a trailing separator
        if (q == p.end() || *q != *b) return false;
    }
    return q != p.end();
}

bool fileExists(const std::string& path, void* user) {
    auto* access = static_cast<FileAccess*>(user);
    if (!access->allowed) return true;  // let readFile report that references are disabled
    if (!insideBase(path, access->canonicalBase)) return false;
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

std::string expandPath(const std::string& path, void*) {
    return path;
}  // no shell expansion

bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    auto* access = static_cast<FileAccess*>(user);
    if (!access->allowed) {
        if (err) *err = "references to other files are disabled";
        return false;
    }
    if (!insideBase(path, access->canonicalBase)) {  // tinygltf asks fileExists first; be sure
        if (err) *err = "outside the glTF file's folder";
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (err) *err = "cannot open";
        return false;
    }
    if (access->budget) {
        std::error_code ec;
        const uint64_t size = fs::file_size(path, ec);
        try {
            access->budget->reserve(ec ? 0 : size,
                                    access->file + ": file '" + fs::path(path).filename().string() + "'");
        } catch (const Error& e) {
            access->refused = e.what();
            if (err) *err = e.what();
            return false;
        }
    }
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
}

bool writeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err = "writing is not supported";
    return false;
}

/// Image "decoder": keeps each image's encoded bytes (file, .glb buffer view or data URI alike);
/// TextureStore decodes them with OpenImageIO when a material uses the image. An image tinygltf
/// could not find is an error for us (it is only a warning to it).
using ImageBytes = std::map<int, std::vector<unsigned char>>;
bool keepImage(tinygltf::Image*, const int index, std::string*, std::string*, int, int, const unsigned char* bytes,
               int size, void* user) {
    (*static_cast<ImageBytes*>(user))[index].assign(bytes, bytes + std::max(size, 0));
    return true;
}

std::string oneLine(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    std::string out;
    for (char c : s) {
        if (c == '\n')
            out += "; ";
        else if (c != '\r')
            out += c;
    }
    return out;
}

std::string numberText(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& ext, const char* name) {
    auto it = ext.find(name);
    return it == ext.end() ? nullptr : &it->second;
}

/// A number member of a glTF extension object; `fallback` when absent; Error when not a number.
double extNumber(const tinygltf::Value& obj, const char* key, double fallback, const std::string& where) {
    if (!obj.IsObject() || !obj.Has(key)) return fallback;
    const tinygltf::Value& v = obj.Get(key);
    if (!v.IsNumber()) throw Error(where + ": " + key + " must be a number");
    return v.GetNumberAsDouble();
}

Rgb extColor(const tinygltf::Value& obj, const char* key, Rgb fallback, const std::string& where) {
    if (!obj.IsObject() || !obj.Has(key)) return fallback;
    const tinygltf::Value& v = obj.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 3) throw Error(where + ": " + key + " must be an array of 3 numbers");
    Rgb c;
    for (int i = 0; i < 3; ++i) {
        if (!v.Get(i).IsNumber()) throw Error(where + ": " + key + " must be an array of 3 numbers");
        c[i] = float(v.Get(i).GetNumberAsDouble());
    }
    return c;
}

Rgb rgbOf(const std::vector<double>& v, Rgb fallback, size_t expectedSize, const std::string& where, const char* key) {
    if (v.empty()) return fallback;
    if (v.size() != expectedSize)
        throw Error(where + ": " + key + " must have " + std::to_string(expectedSize) + " numbers, got " +
                    std::to_string(v.size()));
    return Rgb(float(v[0]), float(v[1]), float(v[2]));
}

/// "buffers[i]" for the first buffer whose URI, percent-decoded as tinygltf decodes it, is `uri`
/// (`root` has passed checkGltfJson); "buffer" when none is.
std::string bufferNamed(const nlohmann::json& root, const std::string& uri) {
    if (root.is_discarded() || !root.contains("buffers")) return "buffer";
    auto hex = [](char c) {
        return std::isdigit(static_cast<unsigned char>(c)) ? c - '0' : (std::tolower(c) - 'a' + 10) & 15;
    };
    const nlohmann::json& buffers = root["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i) {
        if (!buffers[i].contains("uri")) continue;
        const std::string u = buffers[i]["uri"].get<std::string>();
        std::string decoded;
        for (size_t k = 0; k < u.size(); ++k) {
            if (u[k] == '+') {
                decoded += ' ';
            } else if (u[k] == '%' && k + 2 < u.size()) {
                decoded += char(hex(u[k + 1]) << 4 | hex(u[k + 2]));
                k += 2;
            } else {
                decoded += u[k];
            }
        }
        if (u == uri || decoded == uri) return "buffers[" + std::to_string(i) + "]";
    }
    return "buffer";
}

// Extensions Tyndall reads (others are reported once as ignored).
const std::set<std::string> kHandledExtensions = {
    "KHR_lights_punctual",  "KHR_materials_transmission",      "KHR_materials_ior",
    "KHR_materials_volume", "KHR_materials_emissive_strength", "KHR_mesh_quantization",
    "KHR_texture_transform"};
// Required extensions without which the geometry cannot be read.
const std::set<std::string> kUnreadableExtensions = {"KHR_draco_mesh_compression", "EXT_meshopt_compression",
                                                     "KHR_meshopt_compression"};

class GltfImporter {
public:
    GltfImporter(const tinygltf::Model& model, const ImageBytes& images, std::string file,
                 const SceneLoadOptions& options, WarnOnce& warn)
        : m_model(model), m_images(images), m_file(std::move(file)), m_options(options), m_warn(warn) {}

    SceneDraft run();

private:
    std::string nodeWhere(size_t i) const {
        const std::string& n = m_model.nodes[i].name;
        return m_file + ": node " + (n.empty() ? "" : "'" + n + "' ") + "(index " + std::to_string(i) + ")";
    }
    std::string nodeName(size_t i) const {
        const tinygltf::Node& node = m_model.nodes[i];
        if (!node.name.empty()) return node.name;
        if (node.mesh >= 0 && size_t(node.mesh) < m_model.meshes.size() &&
            !m_model.meshes[size_t(node.mesh)].name.empty())
            return m_model.meshes[size_t(node.mesh)].name;
        return "node " + std::to_string(i);
    }

    std::vector<int> rootNodes();
    void visit(int node, const Affine& parent);
    Affine localTransform(size_t node) const;
    void addMesh(size_t node, const Affine& world);
    void addPrimitive(size_t node, const tinygltf::Primitive& prim, const std::string& name, const std::string& where,
                      const Affine& world);
    int material(int gltfIndex, const std::string& where);
    /// A material's texture slot (textureInfo index, texCoord, KHR_texture_transform) as a
    /// TextureRef; the image goes into the scene's TextureStore once per (image, encoding, sampler).
    TextureRef textureRef(int texture, int texCoord, const tinygltf::ExtensionMap& ext, TextureEncoding enc,
                          const std::string& where);
    void addLight(size_t node, const Affine& world);
    void addCamera(size_t node, const Affine& world);

    const tinygltf::Model& m_model;
    const ImageBytes& m_images;
    std::string m_file;
    const SceneLoadOptions& m_options;
    WarnOnce& m_warn;
    SceneDraft m_draft;
    std::vector<char> m_visited;
    std::map<int, int> m_materials;     // glTF material (-1 = default) -> Scene material
    std::map<int, MediumId> m_volumes;  // glTF material -> its KHR_materials_volume medium
    std::map<std::tuple<int, int, int, int>, int> m_textures;  // (image, encoding, wrapS, wrapT) -> TextureStore id
    size_t m_triangles = 0;
};

SceneDraft GltfImporter::run() {
    for (const std::string& e : m_model.extensionsRequired)
        if (kUnreadableExtensions.count(e))
            throw Error(m_file + ": requires glTF extension " + e + ", which Tyndall cannot read (export without it)");
    for (const std::string& e : m_model.extensionsUsed)
        if (!kHandledExtensions.count(e)) m_warn("ext " + e, m_file + ": glTF extension " + e + " ignored");
    if (!m_model.animations.empty()) m_warn("animations", m_file + ": animations ignored (the rest pose is rendered)");

    m_visited.assign(m_model.nodes.size(), 0);
    for (int root : rootNodes()) visit(root, Affine());
    m_draft.scene.name = fs::path(m_file).stem().string();
    return std::move(m_draft);
}

std::vector<int> GltfImporter::rootNodes() {
    const size_t n = m_model.nodes.size();
    std::vector<int> parents(n, 0);
    for (size_t i = 0; i < n; ++i) {
        for (int c : m_model.nodes[i].children) {
            checkGltfIndex(nodeWhere(i), "child", c, n, " nodes");
            if (++parents[size_t(c)] > 1)
                throw Error(nodeWhere(size_t(c)) + ": has more than one parent (glTF node hierarchies are trees)");
        }
    }
    if (m_model.scenes.empty()) {
        std::vector<int> roots;
        for (size_t i = 0; i < n; ++i)
            if (parents[i] == 0) roots.push_back(int(i));
        return roots;
    }
    int s = m_model.defaultScene >= 0 ? m_model.defaultScene : 0;
    checkGltfIndex(m_file, "default scene", s, m_model.scenes.size(), " scenes");
    for (int r : m_model.scenes[size_t(s)].nodes)
        checkGltfIndex(m_file + ": scene " + std::to_string(s), "node", r, n, " nodes");
    return m_model.scenes[size_t(s)].nodes;
}

Affine GltfImporter::localTransform(size_t i) const {
    const tinygltf::Node& node = m_model.nodes[i];
    Affine t;
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) throw Error(nodeWhere(i) + ": matrix must have 16 numbers");
        t = Affine::fromColumnMajor(node.matrix.data());
    } else {
        auto check = [&](const std::vector<double>& v, size_t want, const char* what) {
            if (!v.empty() && v.size() != want)
                throw Error(nodeWhere(i) + ": " + what + " must have " + std::to_string(want) + " numbers");
            return !v.empty();
        };
        if (check(node.translation, 3, "translation"))
            t = Affine::translation(node.translation[0], node.translation[1], node.translation[2]);
        if (check(node.rotation, 4, "rotation")) {
            const auto& q = node.rotation;
            if (!(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3] > 0))
                throw Error(nodeWhere(i) + ": rotation quaternion is zero");
            t = t * Affine::rotation(q[0], q[1], q[2], q[3]);
        }
        if (check(node.scale, 3, "scale")) t = t * Affine::scaling(node.scale[0], node.scale[1], node.scale[2]);
    }
    if (!t.isFinite()) throw Error(nodeWhere(i) + ": transform contains a non-finite number");
    return t;
}

void GltfImporter::visit(int index, const Affine& parent) {
    size_t i = size_t(index);
    if (m_visited[i]) throw Error(nodeWhere(i) + ": reached twice (the node hierarchy has a cycle or a shared node)");
    m_visited[i] = 1;
    const tinygltf::Node& node = m_model.nodes[i];
    Affine world = parent * localTransform(i);
    if (!world.isFinite()) throw Error(nodeWhere(i) + ": world transform overflows");
    if (node.skin >= 0) m_warn("skins", nodeWhere(i) + ": skinning ignored (the bind pose is rendered)");
    if (node.mesh >= 0 || node.mesh < -1) addMesh(i, world);
    if (node.camera >= 0 || node.camera < -1) addCamera(i, world);
    if (extension(node.extensions, "KHR_lights_punctual")) addLight(i, world);
    for (int c : node.children) visit(c, world);
}

void GltfImporter::addMesh(size_t node, const Affine& world) {
    int meshIndex = m_model.nodes[node].mesh;
    checkGltfIndex(nodeWhere(node), "mesh", meshIndex, m_model.meshes.size(), " meshes");
    const tinygltf::Mesh& mesh = m_model.meshes[size_t(meshIndex)];
    std::string name = nodeName(node);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        std::string where = nodeWhere(node) + ": mesh " + (mesh.name.empty() ? "" : "'" + mesh.name + "' ") +
                            "(index " + std::to_string(meshIndex) + ") primitive " + std::to_string(p);
        addPrimitive(node, mesh.primitives[p], mesh.primitives.size() > 1 ? name + "#" + std::to_string(p) : name,
                     where, world);
    }
}

void GltfImporter::addPrimitive(size_t node, const tinygltf::Primitive& prim, const std::string& name,
                                const std::string& where, const Affine& world) {
    int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode <= TINYGLTF_MODE_LINE_STRIP) {
        m_warn("points and lines", where + ": points and lines ignored (only triangles are rendered)");
        return;
    }
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN) throw Error(where + ": mode " + std::to_string(prim.mode) + " is not valid");
    if (!prim.targets.empty()) m_warn("morph targets", where + ": morph targets ignored");
    auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) throw Error(where + ": has no POSITION attribute");

    const size_t maxElements = m_options.maxTriangles * 3;
    std::vector<float> p =
        readGltfFloats(m_model, pos->second, 3, where + ": POSITION", maxElements, m_options.budget.get());
    const size_t nv = p.size() / 3;
    std::vector<uint32_t> idx;
    if (prim.indices >= 0 || prim.indices < -1) {
        idx = readGltfIndices(m_model, prim.indices, where + ": indices", maxElements, m_options.budget.get());
        for (uint32_t v : idx)
            if (v >= nv)
                throw Error(where + ": vertex index " + std::to_string(v) + " out of range (" + std::to_string(nv) +
                            " vertices)");
    } else {
        idx.resize(nv);
        for (size_t k = 0; k < nv; ++k) idx[k] = uint32_t(k);
    }

    TriangleMesh m;
    m.name = name;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (idx.size() % 3 != 0)
            throw Error(where + ": " + std::to_string(idx.size()) + " indices is not a multiple of 3");
        m.indices = std::move(idx);
    } else {
        for (size_t k = 2; k < idx.size(); ++k) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                if (k % 2 == 0)
                    m.indices.insert(m.indices.end(), {idx[k - 2], idx[k - 1], idx[k]});
                else
                    m.indices.insert(m.indices.end(), {idx[k - 1], idx[k - 2], idx[k]});
            } else {
                m.indices.insert(m.indices.end(), {idx[0], idx[k - 1], idx[k]});
            }
        }
    }
    m_triangles += m.triangleCount();
    checkTriangleBudget(m_triangles, m_options, where);

    m.positions.resize(nv);
    for (size_t k = 0; k < nv; ++k) m.positions[k] = world.point({p[3 * k], p[3 * k + 1], p[3 * k + 2]});
    auto nrm = prim.attributes.find("NORMAL");
    if (nrm != prim.attributes.end()) {
        std::vector<float> n =
            readGltfFloats(m_model, nrm->second, 3, where + ": NORMAL", maxElements, m_options.budget.get());
        if (n.size() != p.size())
            throw Error(where + ": NORMAL has " + std::to_string(n.size() / 3) + " elements for " + std::to_string(nv) +
                        " positions");
        m.normals.resize(nv);
        bool ok = true;
        for (size_t k = 0; k < nv && ok; ++k) {
            Vec3 t = world.normal({n[3 * k], n[3 * k + 1], n[3 * k + 2]});
            float len = length(t);
            ok = len > 0 && std::isfinite(len);
            m.normals[k] = ok ? t / len : Vec3();
        }
        if (!ok) {
            m_warn("bad normals", where + ": zero-length normals: flat shading used instead");
            m.normals.clear();
        }
    }
    auto tan = prim.attributes.find("TANGENT");
    if (tan != prim.attributes.end() && !m.normals.empty()) {  // glTF: tangents without normals are ignored
        std::string what = where + ": TANGENT";
        std::vector<float> t = readGltfFloats(m_model, tan->second, 4, what, maxElements, m_options.budget.get());
        if (t.size() / 4 != nv)
            throw Error(what + " has " + std::to_string(t.size() / 4) + " elements for " + std::to_string(nv) +
                        " positions");
        // Tangents are surface directions: they map with the matrix itself. A mirroring transform
        // flips cross(N, T) relative to the mapped bitangent, hence the sign flip.
        const float mirror = world.determinant() < 0 ? -1.0f : 1.0f;
        m.tangents.resize(nv);
        m.tangentSigns.resize(nv);
        bool ok = true;
        for (size_t k = 0; k < nv && ok; ++k) {
            Vec3 v = world.vector({t[4 * k], t[4 * k + 1], t[4 * k + 2]});
            Vec3 n = m.normals[k];
            v = v - n * dot(n, v);
            float len = length(v);
            ok = len > 0 && std::isfinite(len) && std::isfinite(t[4 * k + 3]);
            m.tangents[k] = ok ? v / len : Vec3();
            m.tangentSigns[k] = (t[4 * k + 3] < 0 ? -1.0f : 1.0f) * mirror;
        }
        if (!ok) {
            m_warn("bad tangents", what + ": zero-length or non-finite tangents: tangents generated from TEXCOORD instead");
            m.tangents.clear();
            m.tangentSigns.clear();
        }
    }
    for (int set = 0; set < 2; ++set) {
        auto uv = prim.attributes.find("TEXCOORD_" + std::to_string(set));
        if (uv == prim.attributes.end()) continue;
        std::string what = where + ": TEXCOORD_" + std::to_string(set);
        std::vector<float> t = readGltfFloats(m_model, uv->second, 2, what, maxElements, m_options.budget.get());
        if (t.size() / 2 != nv)
            throw Error(what + " has " + std::to_string(t.size() / 2) + " elements for " + std::to_string(nv) +
                        " positions");
        m.texcoords[set].resize(nv);
        for (size_t k = 0; k < nv; ++k) {
            if (!std::isfinite(t[2 * k]) || !std::isfinite(t[2 * k + 1]))
                throw Error(what + ": element " + std::to_string(k) + " is not finite");
            m.texcoords[set][k] = {t[2 * k], t[2 * k + 1]};
        }
    }
    if (world.determinant() < 0)  // mirrored instance: keep the exterior on the normals' side
        for (size_t k = 0; k + 2 < m.indices.size(); k += 3) std::swap(m.indices[k + 1], m.indices[k + 2]);

    m.material = material(prim.material, where);
    if (const Material& mat = m_draft.scene.materials[size_t(m.material)]; mat.isNormalMapped()) {
        if (m.texcoords[mat.normalTexture.texcoord].empty())
            m_warn("normal map without uv", where + ": normalTexture needs TEXCOORD_" +
                                                std::to_string(mat.normalTexture.texcoord) +
                                                ": the map is read at uv (0, 0) everywhere");
        // Missing tangents are generated by Scene::finalize (core/tangent_frame.h).
    }
    auto vol = m_volumes.find(prim.material);
    if (vol != m_volumes.end()) {
        if (m.isClosed()) {
            m.interiorMedium = vol->second;
        } else {
            m_warn("open volume", where + ": KHR_materials_volume ignored on an open mesh (thin-walled)");
        }
    }
    m_draft.scene.meshes.push_back(std::move(m));
}

int GltfImporter::material(int index, const std::string& primWhere) {
    auto known = m_materials.find(index);
    if (known != m_materials.end()) return known->second;
    Scene& scene = m_draft.scene;
    if (index == -1) {
        Material def;
        def.name = "glTF default material";
        def.type = MaterialType::Diffuse;
        def.albedo = Rgb(0.8f);
        scene.materials.push_back(def);
        return m_materials[index] = int(scene.materials.size() - 1);
    }
    checkGltfIndex(primWhere, "material", index, m_model.materials.size(), " materials");
    const tinygltf::Material& gm = m_model.materials[size_t(index)];
    GltfMaterialInput in;
    in.where = m_file + ": material " + (gm.name.empty() ? "" : "'" + gm.name + "' ") + "(index " +
               std::to_string(index) + ")";
    in.name = gm.name.empty() ? "material " + std::to_string(index) : gm.name;
    const auto& pbr = gm.pbrMetallicRoughness;
    in.baseColor = rgbOf(pbr.baseColorFactor, Rgb(1.0f), 4, in.where, "baseColorFactor");
    in.alpha = pbr.baseColorFactor.size() == 4 ? float(pbr.baseColorFactor[3]) : 1.0f;
    in.metallic = float(pbr.metallicFactor);
    in.roughness = float(pbr.roughnessFactor);
    in.metallicRoughnessTexture = pbr.metallicRoughnessTexture.index >= 0;
    in.emissive = rgbOf(gm.emissiveFactor, Rgb(0.0f), 3, in.where, "emissiveFactor");
    in.alphaMode = gm.alphaMode;
    in.alphaCutoff = float(gm.alphaCutoff);
    // occlusionTexture is ignored on purpose: it is a baked estimate of the ambient shadowing that
    // Tyndall's light transport computes (applying it would darken crevices twice).
    if (const auto* e = extension(gm.extensions, "KHR_materials_emissive_strength"))
        in.emissiveStrength =
            float(extNumber(*e, "emissiveStrength", 1.0, in.where + ": KHR_materials_emissive_strength"));
    if (const auto* e = extension(gm.extensions, "KHR_materials_transmission")) {
        in.transmission = float(extNumber(*e, "transmissionFactor", 0.0, in.where + ": KHR_materials_transmission"));
    }
    if (const auto* e = extension(gm.extensions, "KHR_materials_ior"))
        in.ior = float(extNumber(*e, "ior", 1.5, in.where + ": KHR_materials_ior"));
    if (const auto* e = extension(gm.extensions, "KHR_materials_volume")) {
        std::string vw = in.where + ": KHR_materials_volume";
        in.hasVolume = true;
        in.thickness = float(extNumber(*e, "thicknessFactor", 0.0, vw));
        in.attenuationDistance = float(extNumber(*e, "attenuationDistance", INFINITY, vw));
        in.attenuationColor = extColor(*e, "attenuationColor", Rgb(1.0f), vw);
    }
    for (const auto& [name, value] : gm.extensions)
        if (!kHandledExtensions.count(name)) m_warn("ext " + name, in.where + ": glTF extension " + name + " ignored");

    GltfMaterialMapping mapped = mapGltfMaterial(in);
    for (const GltfNote& n : mapped.notes) m_warn(n.kind, n.message);
    Material& mat = mapped.material;
    if (pbr.baseColorTexture.index >= 0)
        mat.baseColorTexture = textureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                          pbr.baseColorTexture.extensions, TextureEncoding::Srgb,
                                          in.where + ": baseColorTexture");
    if (gm.emissiveTexture.index >= 0 && mat.isEmissive())
        mat.emissiveTexture = textureRef(gm.emissiveTexture.index, gm.emissiveTexture.texCoord,
                                         gm.emissiveTexture.extensions, TextureEncoding::Srgb,
                                         in.where + ": emissiveTexture");
    if (pbr.metallicRoughnessTexture.index >= 0)
        mat.metallicRoughnessTexture = textureRef(pbr.metallicRoughnessTexture.index,
                                                  pbr.metallicRoughnessTexture.texCoord,
                                                  pbr.metallicRoughnessTexture.extensions, TextureEncoding::Linear,
                                                  in.where + ": metallicRoughnessTexture");
    if (gm.normalTexture.index >= 0) {
        mat.normalTexture = textureRef(gm.normalTexture.index, gm.normalTexture.texCoord, gm.normalTexture.extensions,
                                       TextureEncoding::Linear, in.where + ": normalTexture");
        mat.normalScale = float(gm.normalTexture.scale);
        if (!std::isfinite(mat.normalScale))
            throw Error(in.where + ": normalTexture scale must be a finite number");
    }
    if (const auto* e = extension(gm.extensions, "KHR_materials_transmission");
        e && e->IsObject() && e->Has("transmissionTexture") && mat.type == MaterialType::Dielectric) {
        std::string tw = in.where + ": KHR_materials_transmission transmissionTexture";
        const tinygltf::Value& info = e->Get("transmissionTexture");
        if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsNumber())
            throw Error(tw + ": expected {\"index\": n, ...}");
        tinygltf::ExtensionMap infoExt;
        if (info.Has("extensions") && info.Get("extensions").IsObject())
            for (const std::string& k : info.Get("extensions").Keys()) infoExt[k] = info.Get("extensions").Get(k);
        mat.transmissionTexture = textureRef(int(info.Get("index").GetNumberAsDouble()),
                                             int(extNumber(info, "texCoord", 0.0, tw)), infoExt,
                                             TextureEncoding::Linear, tw);
    }
    scene.materials.push_back(mapped.material);
    int id = int(scene.materials.size() - 1);
    if (mapped.interior) {
        scene.media.push_back(*mapped.interior);
        m_volumes[index] = MediumId(scene.media.size() - 1);
    }
    return m_materials[index] = id;
}

TextureRef GltfImporter::textureRef(int texture, int texCoord, const tinygltf::ExtensionMap& ext, TextureEncoding enc,
                                    const std::string& where) {
    checkGltfIndex(where, "texture", texture, m_model.textures.size(), " textures");
    const tinygltf::Texture& tex = m_model.textures[size_t(texture)];
    const int image = tex.source;
    if (image < 0 || size_t(image) >= m_model.images.size())
        throw Error(where + ": texture " + std::to_string(texture) +
                    " has no PNG/JPEG image source (KHR_texture_basisu and EXT_texture_webp are not read)");
    TextureWrap wrap[2] = {TextureWrap::Repeat, TextureWrap::Repeat};
    if (tex.sampler >= 0) {
        if (size_t(tex.sampler) >= m_model.samplers.size())
            throw Error(where + ": sampler index " + std::to_string(tex.sampler) + " out of range");
        const tinygltf::Sampler& s = m_model.samplers[size_t(tex.sampler)];
        int modes[2] = {s.wrapS, s.wrapT};
        for (int k = 0; k < 2; ++k) {
            switch (modes[k]) {
                case TINYGLTF_TEXTURE_WRAP_REPEAT: wrap[k] = TextureWrap::Repeat; break;
                case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: wrap[k] = TextureWrap::ClampToEdge; break;
                case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: wrap[k] = TextureWrap::MirroredRepeat; break;
                default:
                    throw Error(where + ": sampler " + std::to_string(tex.sampler) + " wrap mode " +
                                std::to_string(modes[k]) + " is not 10497, 33071 or 33648");
            }
        }
    }
    auto key = std::make_tuple(image, int(enc), int(wrap[0]), int(wrap[1]));
    auto known = m_textures.find(key);
    TextureRef ref;
    if (known != m_textures.end()) {
        ref.texture = known->second;
    } else {
        const tinygltf::Image& im = m_model.images[size_t(image)];
        auto bytes = m_images.find(image);
        if (bytes == m_images.end() || bytes->second.empty())
            throw Error(where + ": image " + std::to_string(image) + " has no data");
        std::string mime = im.mimeType;
        if (mime.empty() && im.uri.rfind("data:", 0) == 0) mime = im.uri.substr(5, im.uri.find_first_of(";,") - 5);
        std::string imageWhere = where + ": image " + (im.name.empty() ? "" : "'" + im.name + "' ") + "(index " +
                                 std::to_string(image) + ")";
        if (!m_draft.scene.textures) m_draft.scene.textures = std::make_shared<TextureStore>();
        ref.texture = m_draft.scene.textures->addEncoded(bytes->second, mime, im.uri, enc, wrap[0], wrap[1], imageWhere,
                                                         m_options.budget.get());
        m_textures[key] = ref.texture;
    }
    ref.texcoord = texCoord;
    if (const tinygltf::Value* t = extension(ext, "KHR_texture_transform")) {
        std::string tw = where + ": KHR_texture_transform";
        auto pair = [&](const char* key, Vec2 fallback) {
            if (!t->IsObject() || !t->Has(key)) return fallback;
            const tinygltf::Value& v = t->Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
                throw Error(tw + ": " + key + " must be an array of 2 numbers");
            return Vec2{float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble())};
        };
        Vec2 offset = pair("offset", {0, 0}), scale = pair("scale", {1, 1});
        float rotation = float(extNumber(*t, "rotation", 0.0, tw));
        ref.transform = TextureTransform::fromOffsetRotationScale(offset, rotation, scale);
        ref.texcoord = int(extNumber(*t, "texCoord", double(texCoord), tw));
    }
    if (ref.texcoord != 0 && ref.texcoord != 1) {
        m_warn("texcoord", where + ": TEXCOORD_" + std::to_string(ref.texcoord) + " not supported: TEXCOORD_0 used");
        ref.texcoord = 0;
    }
    return ref;
}

void GltfImporter::addLight(size_t node, const Affine& world) {
    std::string where = nodeWhere(node) + ": KHR_lights_punctual";
    const tinygltf::Value& ext = *extension(m_model.nodes[node].extensions, "KHR_lights_punctual");
    if (!ext.IsObject() || !ext.Has("light") || !ext.Get("light").IsNumber())
        throw Error(where + ": expected {\"light\": index}");
    double li = ext.Get("light").GetNumberAsDouble();
    if (!(li >= 0 && li < double(m_model.lights.size())) || li != std::floor(li))
        throw Error(where + ": light index " + numberText(li) + " out of range (the file has " +
                    std::to_string(m_model.lights.size()) + " lights)");
    const tinygltf::Light& gl = m_model.lights[size_t(li)];
    where = m_file + ": light " + (gl.name.empty() ? "" : "'" + gl.name + "' ") + "(index " +
            std::to_string(int64_t(li)) + ", node " + std::to_string(node) + ")";
    Rgb color = rgbOf(gl.color, Rgb(1.0f), 3, where, "color");
    for (int c = 0; c < 3; ++c)
        if (!(color[c] >= 0.0f && color[c] <= 1.0f)) throw Error(where + ": color must lie in [0, 1]");
    if (!(gl.intensity >= 0) || !std::isfinite(gl.intensity))
        throw Error(where + ": intensity must be a finite number >= 0");
    if (gl.range > 0) m_warn("light range", where + ": range ignored (inverse-square falloff without cut-off)");

    Light l;
    l.name = gl.name.empty() ? nodeName(node) : gl.name;
    l.position = world.point({0, 0, 0});
    Vec3 dir = world.vector({0, 0, -1});
    if (gl.type == "point") {
        l.type = LightType::Point;
        l.intensity = radiantIntensityFromCandela(color, float(gl.intensity));
    } else if (gl.type == "spot" || gl.type == "directional") {
        if (!(length(dir) > 0)) throw Error(where + ": the node's transform collapses the light direction");
        l.direction = normalize(dir);
        if (gl.type == "directional") {
            l.type = LightType::Directional;
            l.intensity = irradianceFromLux(color, float(gl.intensity));
        } else {
            l.type = LightType::Spot;
            double inner = gl.spot.innerConeAngle, outer = gl.spot.outerConeAngle;
            if (!(inner >= 0 && inner < outer && outer <= kPi / 2 + 1e-6))
                throw Error(where + ": spot cone angles must satisfy 0 <= innerConeAngle < outerConeAngle <= pi/2");
            l.cosInnerAngle = float(std::cos(inner));
            l.cosOuterAngle = float(std::cos(outer));
            l.intensity = radiantIntensityFromCandela(color, float(gl.intensity));
        }
    } else {
        throw Error(where + ": type '" + gl.type + "' is not point, spot or directional");
    }
    m_draft.scene.lights.push_back(l);
}

void GltfImporter::addCamera(size_t node, const Affine& world) {
    int ci = m_model.nodes[node].camera;
    checkGltfIndex(nodeWhere(node), "camera", ci, m_model.cameras.size(), " cameras");
    const tinygltf::Camera& gc = m_model.cameras[size_t(ci)];
    std::string name = !m_model.nodes[node].name.empty() ? m_model.nodes[node].name
                       : !gc.name.empty()                ? gc.name
                                                         : "camera " + std::to_string(ci);
    std::string where = nodeWhere(node) + ": camera " + (gc.name.empty() ? "" : "'" + gc.name + "' ") + "(index " +
                        std::to_string(ci) + ")";
    if (gc.type != "perspective") {
        m_warn("orthographic camera", where + ": " + gc.type + " cameras are not supported: skipped");
        return;
    }
    double yfov = gc.perspective.yfov;
    if (!(yfov > 0 && yfov < kPi)) throw Error(where + ": yfov must lie in (0, pi) radians");
    Vec3 eye = world.point({0, 0, 0});
    Vec3 forward = world.vector({0, 0, -1}), up = world.vector({0, 1, 0});
    if (!(length(cross(forward, up)) > 0)) throw Error(where + ": the node's transform collapses the view direction");
    Camera c = Camera::lookAt(eye, eye + normalize(forward), normalize(up), float(yfov));
    m_draft.cameras.push_back({name, c});
}

}  // namespace

SceneDraft importGltf(const std::string& bytes, bool binary, const std::string& file, const std::string& baseDir,
                      const SceneLoadOptions& options, WarnOnce& warn) {
    // tinygltf ignores properties of the wrong type: check them first (gltf_json_check.h).
    const nlohmann::json root = gltfJsonOf(bytes, binary);
    if (!root.is_discarded()) checkGltfJson(root, file);

    FileAccess access;
    std::error_code ec;
    access.baseDir = fs::absolute(baseDir.empty() ? fs::path(".") : fs::path(baseDir), ec).lexically_normal().string();
    while (access.baseDir.size() > 1 && access.baseDir.back() == '/') access.baseDir.pop_back();
    access.canonicalBase = fs::weakly_canonical(access.baseDir, ec);
    if (ec) access.canonicalBase.clear();  // nothing resolves inside it
    access.allowed = options.allowExternalFiles;
    access.file = file;
    access.budget = options.budget.get();
    ImageBytes images;

    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&fileExists, &expandPath, &readFile, &writeFile, &access});
    loader.SetImageLoader(&keepImage, &images);
    tinygltf::Model model;
    std::string err, warnings;
    bool ok = false;
    try {
        if (binary) {
            ok = loader.LoadBinaryFromMemory(&model, &err, &warnings,
                                             reinterpret_cast<const unsigned char*>(bytes.data()),
                                             unsigned(bytes.size()), access.baseDir);
        } else {
            ok = loader.LoadASCIIFromString(&model, &err, &warnings, bytes.data(), unsigned(bytes.size()),
                                            access.baseDir);
        }
    } catch (const std::exception& e) {
        throw Error(file + ": not valid glTF: " + jsonErrorText(oneLine(e.what()), binary ? std::string() : bytes));
    }
    if (!access.refused.empty()) throw Error(access.refused);
    // tinygltf treats only buffers as required external files: a missing one is an error there.
    for (const std::string prefix : {"File not found : ", "File read error : "}) {
        auto at = err.find(prefix);
        if (ok || at == std::string::npos) continue;
        std::string what = err.substr(at + prefix.size());
        what = what.substr(0, what.find('\n'));
        bool missing = prefix.rfind("File not found", 0) == 0;
        if (missing)
            throw Error(file + ": " + bufferNamed(root, what) + ": file '" + what +
                        "' not found in the glTF file's folder");
        throw Error(file + ": buffer file cannot be read: " + what);
    }
    if (!ok)
        throw Error(file + ": not valid glTF: " +
                    jsonErrorText(oneLine(err.empty() ? warnings : err), binary ? std::string() : bytes));

    for (size_t i = 0; i < model.images.size(); ++i) {
        if (images.count(int(i))) continue;
        const tinygltf::Image& im = model.images[i];
        throw Error(file + ": image " + (im.name.empty() ? "" : "'" + im.name + "' ") + "(index " + std::to_string(i) +
                    "): " + (im.uri.empty() ? "no data" : "file '" + im.uri + "' not found or unreadable"));
    }
    for (size_t i = 0; i < model.buffers.size(); ++i)
        if (model.buffers[i].data.empty())
            throw Error(file + ": buffer " + std::to_string(i) +
                        (model.buffers[i].uri.empty() ? "" : " ('" + model.buffers[i].uri + "')") + ": no data");
    return GltfImporter(model, images, file, options, warn).run();
}

}  // namespace tyndall
