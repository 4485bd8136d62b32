// EmbreeScene's hit record: shading normals come from a packed per-triangle copy of the vertex
// normals (specular meshes only); they must equal, bit for bit, the interpolation straight from
// TriangleMesh's indices and normals, and diffuse meshes with normals keep ns = ng.
#include "cpu/embree_scene.h"

#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "tests/test_scenes.h"

namespace tyndall {
namespace {

/// SurfaceHit::ns as documented, from the mesh itself.
Vec3 expectedShadingNormal(const Scene& scene, const SurfaceHit& hit) {
    const TriangleMesh& mesh = scene.meshes[hit.mesh];
    if (mesh.normals.empty() || !scene.materials[mesh.material].isSpecular()) return hit.ng;
    const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
    Vec3 n =
        mesh.normals[tri[0]] * (1.0f - hit.b1 - hit.b2) + mesh.normals[tri[1]] * hit.b1 + mesh.normals[tri[2]] * hit.b2;
    float len = length(n);
    if (!(len > 0 && std::isfinite(len))) return hit.ng;
    n = n / len;
    return dot(n, hit.ng) < 0 ? -n : n;
}

bool sameBits(const Vec3& a, const Vec3& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

TEST(EmbreeScene, ShadingNormalsMatchTheMeshInterpolation) {
    for (MaterialType sphereType : {MaterialType::Dielectric, MaterialType::Diffuse}) {
        Scene scene = test::causticScene();  // mesh 0: the room (no normals); mesh 1: the sphere
        scene.materials[1].type = sphereType;
        ASSERT_FALSE(scene.meshes[1].normals.empty());
        EmbreeScene rt(scene);
        Rng rng(3, 4);
        int sphereHits = 0;
        for (int i = 0; i < 2000; ++i) {
            // From points around the sphere toward it (outside hits), and from its centre (inside).
            Vec3 d = sampleUniformSphere(rng.uniform(), rng.uniform());
            Vec3 o = i % 2 ? Vec3(0.0f) : d * -1.2f + sampleUniformSphere(rng.uniform(), rng.uniform()) * 0.1f;
            SurfaceHit hit;
            ASSERT_TRUE(rt.intersect(Ray{o, d}, &hit));
            sphereHits += hit.mesh == 1;
            ASSERT_TRUE(sameBits(hit.ns, expectedShadingNormal(scene, hit))) << i;
            if (sphereType == MaterialType::Diffuse || hit.mesh == 0) {
                ASSERT_TRUE(sameBits(hit.ns, hit.ng)) << i;
            } else {
                EXPECT_GT(dot(hit.ns, hit.ng), 0.9f) << i;  // interpolated, not the flat normal
                EXPECT_FALSE(sameBits(hit.ns, hit.ng)) << i;
            }
        }
        EXPECT_GT(sphereHits, 1500);
    }
}

}  // namespace
}  // namespace tyndall
