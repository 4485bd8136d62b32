#pragma once
// The scene representation every stage renders: world-space triangle meshes with a material and
// the media on either side, lights, one camera, and an optional medium filling all space that no
// closed mesh claims. Built by the default-scene builder or the scene-file loader, then
// finalize()d once (derived data) and validate()d (throws Error naming the offending element).
//
// Media and surfaces: every mesh has an interior and exterior medium. The geometric normal
// (counter-clockwise winding) points to the exterior. Crossing a transmissive surface
// (dielectric or interface) against the normal enters the interior medium, along it leaves to
// the exterior. Meshes whose interior medium differs from their exterior must be closed
// (checked by validate()). Slots left kInheritMedium are resolved by finalize() from how the
// meshes lie inside one another (core/medium_nesting.h): exterior = the medium of the innermost
// closed medium-bounding mesh around it, else the scene's global medium; interior = vacuum for
// closed transmissive meshes (a glass ball in fog holds no fog) and = exterior for the others.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/environment_light.h"
#include "core/light.h"
#include "core/material.h"
#include "core/medium.h"
#include "core/texture.h"

namespace tyndall {

/// Marks a mesh medium slot to be resolved by finalize() (see the defaults above).
constexpr MediumId kInheritMedium = -2;

struct TriangleMesh {
    std::string name;
    std::vector<Vec3> positions;     ///< world space
    std::vector<Vec3> normals;       ///< optional per-vertex shading normals (world, unit); empty = flat
    std::vector<Vec2> texcoords[2];  ///< optional per-vertex TEXCOORD_0 / TEXCOORD_1 (glTF uv); empty = none
    /// Optional per-vertex tangents for normal maps (world, unit, perpendicular to the normal) and
    /// the bitangent sign: B = tangentSigns[i] x cross(N, T) (glTF's TANGENT.w). Both empty = none;
    /// core/tangent_frame.h generates them from TEXCOORD when a normal-mapped mesh has none.
    std::vector<Vec3> tangents;
    std::vector<float> tangentSigns;
    std::vector<uint32_t> indices;   ///< 3 per triangle, counter-clockwise seen from the exterior
    int material = 0;                ///< index into Scene::materials
    MediumId interiorMedium = kInheritMedium;
    MediumId exteriorMedium = kInheritMedium;

    size_t triangleCount() const { return indices.size() / 3; }
    Vec3 vertex(size_t tri, int k) const { return positions[indices[3 * tri + k]]; }
    /// Unnormalised geometric normal (length = 2 x area), pointing to the exterior.
    Vec3 geometricNormal(size_t tri) const {
        return cross(vertex(tri, 1) - vertex(tri, 0), vertex(tri, 2) - vertex(tri, 0));
    }
    /// True when every edge is shared by exactly two triangles with opposite orientation.
    bool isClosed() const;
};

/// One emissive triangle: an area light.
struct EmissiveTriangle {
    int mesh = 0;
    uint32_t triangle = 0;
    float area = 0;
    Rgb radiance;  ///< Material::emission
};

struct Scene {
    std::string name;     ///< for messages and image metadata
    std::string source;   ///< file it came from, or "<built-in default scene>"
    std::vector<TriangleMesh> meshes;
    std::vector<Material> materials;
    std::vector<Medium> media;
    std::vector<Light> lights;
    Camera camera;
    MediumId globalMedium = kVacuum;  ///< fills space not inside any medium-bounding mesh (clipped to `bounds`)
    /// Light from infinitely far away (core/environment_light.h); none = black beyond the scene.
    /// Paths that leave the scene's bounds reach it unattenuated: the global medium ends there.
    std::optional<EnvironmentLight> environment;
    /// Images the materials' TextureRefs index; null when no material is textured. Shared, so a
    /// copied Scene reads the same TextureSystem.
    std::shared_ptr<TextureStore> textures;

    // Derived by finalize().
    Bounds3 bounds;
    std::vector<EmissiveTriangle> emitters;

    /// Resolves inherited media (core/medium_nesting.h), computes bounds and the emitter list. Call
    /// once after building. Throws Error when a mesh straddles a medium-bounding mesh.
    void finalize();
    /// Throws Error naming the first invalid element ("scene 'x': mesh 'lamp' (index 3): ...").
    void validate() const;

    const Material& materialOf(int mesh) const { return materials[meshes[mesh].material]; }
    const Medium* medium(MediumId id) const { return id >= 0 ? &media[id] : nullptr; }
    size_t triangleCount() const;
};

}  // namespace tyndall
