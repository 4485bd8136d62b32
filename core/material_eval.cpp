#include "core/material_eval.h"

namespace tyndall {

Vec2 meshTexcoord(const TriangleMesh& mesh, int set, uint32_t tri, float b1, float b2) {
    const std::vector<Vec2>& uv = mesh.texcoords[set];
    if (uv.empty()) return {0, 0};
    const Vec2& a = uv[mesh.indices[3 * size_t(tri)]];
    const Vec2& b = uv[mesh.indices[3 * size_t(tri) + 1]];
    const Vec2& c = uv[mesh.indices[3 * size_t(tri) + 2]];
    float b0 = 1.0f - b1 - b2;
    return {b0 * a.x + b1 * b.x + b2 * c.x, b0 * a.y + b1 * b.y + b2 * c.y};
}

float texcoordScale(const TriangleMesh& mesh, int set, uint32_t tri) {
    const std::vector<Vec2>& uv = mesh.texcoords[set];
    if (uv.empty()) return 0.0f;
    const Vec2& a = uv[mesh.indices[3 * size_t(tri)]];
    const Vec2& b = uv[mesh.indices[3 * size_t(tri) + 1]];
    const Vec2& c = uv[mesh.indices[3 * size_t(tri) + 2]];
    float uvArea = std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    float worldArea = length(mesh.geometricNormal(tri));
    return worldArea > 0 ? std::sqrt(uvArea / worldArea) : 0.0f;
}

std::array<float, 4> sampleSlot(const Scene& scene, const TextureRef& ref, const TriangleMesh& mesh, uint32_t tri,
                                float b1, float b2, float footprint) {
    if (!ref.present() || !scene.textures) return {1, 1, 1, 1};
    int set = ref.texcoord;
    Vec2 uv = ref.transform.apply(meshTexcoord(mesh, set, tri, b1, b2));
    float width = footprint * texcoordScale(mesh, set, tri) * ref.transform.scale();
    return scene.textures->lookup(ref.texture, uv, std::isfinite(width) ? width : 0.0f);
}

SurfacePoint evalSurface(const Scene& scene, const TriangleMesh& mesh, uint32_t tri, float b1, float b2,
                         float footprint) {
    const Material& mat = scene.materials[size_t(mesh.material)];
    SurfacePoint sp = surfaceFactors(mat);
    if (!mat.isTextured()) return sp;
    if (mat.baseColorTexture.present()) {
        auto t = sampleSlot(scene, mat.baseColorTexture, mesh, tri, b1, b2, footprint);
        sp.baseColor *= Rgb(t[0], t[1], t[2]);
        sp.alpha *= t[3];
    }
    if (mat.emissiveTexture.present() && mat.isEmissive()) {
        auto t = sampleSlot(scene, mat.emissiveTexture, mesh, tri, b1, b2, footprint);
        sp.emission *= Rgb(t[0], t[1], t[2]);
    }
    if (mat.metallicRoughnessTexture.present()) {
        auto t = sampleSlot(scene, mat.metallicRoughnessTexture, mesh, tri, b1, b2, footprint);
        sp.roughness *= t[1];
        sp.metallic *= t[2];
    }
    if (mat.transmissionTexture.present()) {
        auto t = sampleSlot(scene, mat.transmissionTexture, mesh, tri, b1, b2, footprint);
        sp.transmission *= t[0];
    }
    return sp;
}

Vec3 normalMappedNormal(const Scene& scene, const TriangleMesh& mesh, uint32_t tri, float b1, float b2,
                        const Vec3& ng, float footprint) {
    const Material& mat = scene.materials[size_t(mesh.material)];
    const TangentFrame frame = normalMapFrame(mesh, mat.normalTexture.texcoord, tri, b1, b2, ng);
    auto t = sampleSlot(scene, mat.normalTexture, mesh, tri, b1, b2, footprint);
    Vec3 m{(2.0f * t[0] - 1.0f) * mat.normalScale, (2.0f * t[1] - 1.0f) * mat.normalScale, 2.0f * t[2] - 1.0f};
    return perturbedNormal(frame, m, ng);
}

}  // namespace tyndall
