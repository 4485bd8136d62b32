// EmbreeScene's hit record: shading normals come from a packed per-triangle copy of the vertex
// normals (specular meshes only); they must equal, bit for bit, the interpolation straight from
// TriangleMesh's indices and normals, and diffuse meshes with normals keep ns = ng. The packet
// query (intersectCoherent) gives the single-ray query's hits bit for bit.
#include "cpu/embree_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

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

bool sameHit(const SurfaceHit& a, const SurfaceHit& b) {
    return a.t == b.t && a.mesh == b.mesh && a.triangle == b.triangle && a.b1 == b.b1 && a.b2 == b.b2 &&
           sameBits(a.p, b.p) && sameBits(a.ng, b.ng) && sameBits(a.ns, b.ns);
}

TEST(EmbreeScene, PacketHitsEqualSingleRayHits) {
    // Camera rays in packets of 4 x 2 pixels (as the primary stage traces them), some packets cut
    // short (n < 8), some rays limited in t so that they miss; then packets of scattered rays,
    // which Embree traverses ray by ray inside the packet.
    Scene scene = test::causticScene();
    scene.materials[1].type = MaterialType::Dielectric;  // shading normals on the sphere
    EmbreeScene rt(scene);
    const int w = 64, h = 64;
    Rng rng(5, 6);
    int compared = 0, misses = 0, sphere = 0;
    for (int trial = 0; trial < 2; ++trial) {
        for (int y = 0; y < h; y += 2) {
            for (int x = 0; x < w; x += 4) {
                Ray rays[EmbreeScene::kPacket];
                const int n = 1 + int(rng.uniform() * EmbreeScene::kPacket);
                for (int k = 0; k < n; ++k) {
                    if (trial == 0) {
                        rays[k] = scene.camera.generateRay(float(x + k % 4) + rng.uniform(), float(y + k / 4) + rng.uniform(),
                                                           w, h, Vec2{0.5f, 0.5f});
                    } else {
                        rays[k] = Ray{Vec3(0.0f) + sampleUniformSphere(rng.uniform(), rng.uniform()) * 0.5f,
                                      sampleUniformSphere(rng.uniform(), rng.uniform())};
                    }
                    if (rng.uniform() < 0.2f) rays[k].tMax = 2.0f * rng.uniform();
                }
                SurfaceHit packet[EmbreeScene::kPacket], single;
                bool found[EmbreeScene::kPacket];
                rt.intersectCoherent(rays, n, packet, found);
                for (int k = 0; k < n; ++k) {
                    const bool hit = rt.intersect(rays[k], &single);
                    ASSERT_EQ(found[k], hit) << trial << " " << x << " " << y << " " << k;
                    if (hit) {
                        ASSERT_TRUE(sameHit(packet[k], single)) << trial << " " << x << " " << y << " " << k;
                        sphere += single.mesh == 1;
                    }
                    misses += !hit;
                    compared++;
                }
            }
        }
    }
    EXPECT_GT(compared, 1500);
    EXPECT_GT(misses, 50);
    EXPECT_GT(sphere, 100);
}

// The ray origin's rounding (offsetOrigin) steps a coordinate one float with nextFloatUp/Down
// instead of std::nextafter: the same bits for every input, the edges (zeros, subnormals, the
// largest finite floats, infinities, NaN) and random bit patterns over the whole range.
TEST(EmbreeScene, NextFloatEqualsNextafterBitForBit) {
    auto bits = [](float f) {
        uint32_t u;
        std::memcpy(&u, &f, sizeof u);
        return u;
    };
    auto same = [&](float a, float b) { return (std::isnan(a) && std::isnan(b)) || bits(a) == bits(b); };
    const float lim = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min(),
                normal = std::numeric_limits<float>::min();
    std::vector<float> values = {0.0f, -0.0f, tiny, -tiny, normal, -normal, lim, -lim, kInfinity, -kInfinity,
                                 std::nanf(""), 1.0f, -1.0f, 0x1p-24f, -3.5f, 1e30f};
    Rng rng(17, 3);
    for (int i = 0; i < 200000; ++i) {
        const uint32_t u = rng.nextUInt();
        float f;
        std::memcpy(&f, &u, sizeof f);
        values.push_back(f);
    }
    for (float v : values) {
        ASSERT_TRUE(same(EmbreeScene::nextFloatUp(v), std::nextafter(v, kInfinity))) << v << " " << bits(v);
        ASSERT_TRUE(same(EmbreeScene::nextFloatDown(v), std::nextafter(v, -kInfinity))) << v << " " << bits(v);
    }
}

}  // namespace
}  // namespace tyndall
