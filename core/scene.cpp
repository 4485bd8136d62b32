#include "core/scene.h"

#include "core/tangent_frame.h"
#include "core/medium_nesting.h"

#include <cmath>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/error.h"

namespace tyndall {

bool TriangleMesh::isClosed() const {
    // Vertices split for normals or UVs share a position: weld them by exact position first.
    std::map<std::tuple<float, float, float>, uint32_t> weld;
    std::vector<uint32_t> canonical(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        auto key = std::make_tuple(positions[i].x, positions[i].y, positions[i].z);
        canonical[i] = weld.emplace(key, uint32_t(weld.size())).first->second;
    }
    // Each directed edge must appear once and its reverse once.
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        if (indices[i] >= positions.size() || indices[i + 1] >= positions.size() || indices[i + 2] >= positions.size())
            return false;
        for (int k = 0; k < 3; ++k) {
            uint32_t a = canonical[indices[i + k]], b = canonical[indices[i + (k + 1) % 3]];
            if (a == b) continue;  // degenerate edge
            edges[{a, b}]++;
        }
    }
    for (const auto& [e, n] : edges) {
        if (n != 1) return false;
        auto it = edges.find({e.second, e.first});
        if (it == edges.end() || it->second != 1) return false;
    }
    return !edges.empty();
}

void Scene::finalize() {
    bounds = Bounds3();
    emitters.clear();
    resolveNestedMedia(*this);
    for (size_t m = 0; m < meshes.size(); ++m) {
        TriangleMesh& mesh = meshes[m];
        for (const Vec3& p : mesh.positions) bounds.extend(p);
        if (mesh.material < 0 || mesh.material >= int(materials.size())) continue;  // validate() reports
        const Material& mat = materials[mesh.material];
        if (mat.isNormalMapped() && mesh.tangents.empty()) generateTangents(mesh, mat.normalTexture.texcoord);
        if (!mat.isEmissive()) continue;
        for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
            float area = 0.5f * length(mesh.geometricNormal(t));
            if (area > 0) emitters.push_back({int(m), t, area, mat.emission});
        }
    }
}

size_t Scene::triangleCount() const {
    size_t n = 0;
    for (const auto& m : meshes) n += m.triangleCount();
    return n;
}

namespace {
std::string where(const Scene& s) { return "scene '" + s.name + "' (" + s.source + ")"; }
bool finiteNonNegative(const Rgb& c) { return isFinite(c) && c.r >= 0 && c.g >= 0 && c.b >= 0; }
}  // namespace

void Scene::validate() const {
    auto fail = [&](const std::string& what) { throw Error(where(*this) + ": " + what); };
    auto mediumOk = [&](MediumId id) { return id == kVacuum || (id >= 0 && id < int(media.size())); };
    if (!mediumOk(globalMedium)) fail("global medium index " + std::to_string(globalMedium) + " out of range");
    for (size_t i = 0; i < materials.size(); ++i) {
        const Material& m = materials[i];
        std::string at = "material '" + m.name + "' (index " + std::to_string(i) + "): ";
        if (!finiteNonNegative(m.albedo)) fail(at + "albedo must be finite and >= 0");
        if (!finiteNonNegative(m.emission)) fail(at + "emission must be finite and >= 0");
        if (!(m.ior > 0) || !std::isfinite(m.ior)) fail(at + "ior must be a finite number > 0");
        if (m.thin && m.type != MaterialType::Dielectric) fail(at + "thin applies to dielectrics only");
        for (const TextureRef* t : {&m.baseColorTexture, &m.emissiveTexture, &m.metallicRoughnessTexture}) {
            if (!t->present()) continue;
            if (!textures || size_t(t->texture) >= textures->size())
                fail(at + "texture index " + std::to_string(t->texture) + " out of range");
            if (t->texcoord != 0 && t->texcoord != 1) fail(at + "texCoord must be 0 or 1");
        }
    }
    for (size_t i = 0; i < media.size(); ++i) {
        const Medium& m = media[i];
        std::string at = "medium '" + m.name + "' (index " + std::to_string(i) + "): ";
        if (!finiteNonNegative(m.sigmaS)) fail(at + "scattering coefficient must be finite and >= 0");
        if (!finiteNonNegative(m.sigmaA)) fail(at + "absorption coefficient must be finite and >= 0");
        if (!(m.g > -1.0f && m.g < 1.0f)) fail(at + "phase asymmetry g must lie in (-1, 1)");
        if (!finiteNonNegative(m.emission)) fail(at + "emission must be finite and >= 0");
        if (!(m.emissionScale >= 0) || !std::isfinite(m.emissionScale))
            fail(at + "emission scale must be finite and >= 0");
        if (m.emissionField && !m.density) fail(at + "an emission grid needs a density grid");
        if (m.density) {
            Rgb t = m.sigmaT();
            if (std::abs(t.r - t.g) > 1e-5f * t.r || std::abs(t.r - t.b) > 1e-5f * t.r)
                fail(at + "a density-grid medium needs grey extinction (sigma_s + sigma_a equal in r, g, b); "
                          "put colour in the albedo");
        }
    }
    for (size_t i = 0; i < meshes.size(); ++i) {
        const TriangleMesh& m = meshes[i];
        std::string at = "mesh '" + m.name + "' (index " + std::to_string(i) + "): ";
        if (m.material < 0 || m.material >= int(materials.size()))
            fail(at + "material index " + std::to_string(m.material) + " out of range");
        if (m.indices.size() % 3 != 0) fail(at + "index count is not a multiple of 3");
        for (int set = 0; set < 2; ++set)
            if (!m.texcoords[set].empty() && m.texcoords[set].size() != m.positions.size())
                fail(at + "has " + std::to_string(m.texcoords[set].size()) + " TEXCOORD_" + std::to_string(set) +
                     " values for " + std::to_string(m.positions.size()) + " positions");
        if (!m.normals.empty() && m.normals.size() != m.positions.size())
            fail(at + "has " + std::to_string(m.normals.size()) + " normals for " +
                 std::to_string(m.positions.size()) + " positions");
        for (uint32_t idx : m.indices)
            if (idx >= m.positions.size()) fail(at + "vertex index " + std::to_string(idx) + " out of range");
        for (const Vec3& p : m.positions)
            if (!isFinite(p)) fail(at + "has a non-finite vertex position");
        if (!mediumOk(m.interiorMedium) || !mediumOk(m.exteriorMedium))
            fail(at + "medium index out of range");
        if (m.interiorMedium != m.exteriorMedium && !m.isClosed())
            fail(at + "bounds a medium but is not a closed, consistently oriented mesh");
    }
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        std::string at = "light '" + l.name + "' (index " + std::to_string(i) + "): ";
        if (!finiteNonNegative(l.intensity)) fail(at + "intensity must be finite and >= 0");
        if (!isFinite(l.position)) fail(at + "position must be finite");
        if (l.type != LightType::Point && std::abs(length(l.direction) - 1.0f) > 1e-3f)
            fail(at + "direction must be a unit vector");
        if (l.type == LightType::Spot && !(l.cosOuterAngle < l.cosInnerAngle || l.cosInnerAngle == 1.0f))
            fail(at + "spot outer cone must be wider than the inner cone");
    }
    if (environment) {
        if (!(std::isfinite(environment->scale()) && environment->scale() >= 0))
            fail("environment '" + environment->name() + "': scale must be finite and >= 0");
        if (!std::isfinite(environment->rotation()))
            fail("environment '" + environment->name() + "': rotation must be finite");
    }
    bool emissiveMedium = false;
    for (const Medium& m : media) emissiveMedium |= m.emissive();
    if (lights.empty() && emitters.empty() && !environment && !emissiveMedium)
        fail("has no lights, no emissive surfaces or media and no environment: the image would be black");
    if (!isFinite(camera.position) || !isFinite(camera.forward)) fail("camera has a non-finite position or direction");
}

}  // namespace tyndall
