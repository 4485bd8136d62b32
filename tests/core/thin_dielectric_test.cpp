// The thin-walled dielectric (Material::thin): a sheet's reflectance and transmittance against the
// thin slab's closed form, and that closed form against a slab traced ray by ray.
//   - fresnelThinSlab (R' = R + T^2 R / (1 - R^2)) against a random walk inside a slab of index
//     eta: Fresnel at the first face for the incident angle, at the inner faces for the refracted
//     angle (Snell), counted until the light leaves on either side;
//   - Bsdf::sample on a thin dielectric, from both sides and at several angles: the share of
//     reflections is R' (binomial bound), a transmission goes straight on (wi = -wo, no refraction
//     offset, eta 1) with the tint as its weight, into the medium on the other side; reflection
//     keeps the arriving medium; radiance and importance alike.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/bsdf.h"
#include "core/environment_light.h"
#include "core/error.h"

namespace tyndall {
namespace {

/// A slab of relative index `eta` traced photon by photon: returns the share reflected back to the
/// incident side for light arriving at cosine `cosI`.
double slabReflectanceByRandomWalk(float cosI, float eta, int photons, unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const float sinT = std::sqrt(std::max(0.0f, 1 - cosI * cosI)) / eta;
    const float cosT = std::sqrt(std::max(0.0f, 1 - sinT * sinT));
    const double rOuter = fresnelDielectric(cosI, eta);        // from outside onto either face
    const double rInner = fresnelDielectric(-cosT, eta);       // from inside (the normal points out)
    int reflected = 0;
    for (int k = 0; k < photons; ++k) {
        if (u(gen) < rOuter) {
            ++reflected;
            continue;
        }
        // Inside, heading for the far face; each face reflects with rInner, else the light leaves.
        for (bool towardFar = true;; towardFar = !towardFar) {
            if (u(gen) < rInner) continue;
            if (!towardFar) ++reflected;  // left through the near face
            break;
        }
    }
    return double(reflected) / photons;
}

TEST(ThinDielectric, SlabFormulaMatchesASlabTracedRayByRay) {
    for (float eta : {1.5f, 2.4f}) {
        for (float cosI : {1.0f, 0.7f, 0.3f, 0.08f}) {
            const int n = 400000;
            const double walk = slabReflectanceByRandomWalk(cosI, eta, n, 11);
            const double formula = fresnelThinSlab(cosI, eta), sigma = std::sqrt(formula * (1 - formula) / n);
            EXPECT_NEAR(walk, formula, 5 * sigma + 1e-6) << "eta " << eta << ", cos " << cosI;
            EXPECT_NEAR(fresnelThinSlab(-cosI, eta), formula, 1e-7) << "the same from the other side";
            // More than one face reflects, and the slab reflects more than its first face.
            EXPECT_GT(formula, fresnelDielectric(cosI, eta));
        }
    }
    // At normal incidence, R = ((eta-1)/(eta+1))^2 and R' = 2R / (1 + R) (the series summed).
    const double R = std::pow(0.5 / 2.5, 2);
    EXPECT_NEAR(fresnelThinSlab(1.0f, 1.5f), 2 * R / (1 + R), 1e-6);
}

/// Numbers from a seeded generator.
struct Draws {
    std::mt19937 gen;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    explicit Draws(unsigned seed) : gen(seed) {}
    float uniform() { return u(gen); }
};

TEST(ThinDielectric, SheetReflectsTheSlabsShareAndTransmitsStraightThrough) {
    const Vec3 ng = normalize(Vec3(0.3f, 0.2f, 0.93f));
    const Rgb tint(0.9f, 0.7f, 0.5f);
    Scene scene;
    TriangleMesh mesh;
    mesh.exteriorMedium = 0;
    mesh.interiorMedium = 1;
    scene.meshes.push_back(mesh);
    Material m;
    m.type = MaterialType::Dielectric;
    m.thin = true;
    m.ior = 1.5f;
    m.albedo = tint;
    scene.materials.push_back(m);
    SurfaceHit hit;
    hit.mesh = 0;
    hit.ng = hit.ns = ng;
    SurfacePoint sp;
    sp.baseColor = tint;
    const Frame frame(ng);
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        for (float cosO : {0.95f, 0.5f, 0.15f, -0.4f}) {
            SCOPED_TRACE(std::string(mode == TransportMode::Radiance ? "radiance" : "importance") + ", cos_o " +
                         std::to_string(cosO));
            const float sinO = std::sqrt(1 - cosO * cosO);
            const Vec3 wo = frame.toWorld(Vec3(sinO * std::cos(0.7f), sinO * std::sin(0.7f), cosO));
            const MediumId arriving = cosO > 0 ? 0 : 1, beyond = cosO > 0 ? 1 : 0;
            Draws draws(5);
            const Bsdf bsdf = Bsdf::at(scene, hit, sp, -wo, arriving, mode, draws);
            EXPECT_EQ(bsdf.lobes(), kLobeReflection | kLobeTransmission | kLobeSpecular);
            const int n = 200000;
            int reflected = 0;
            for (int k = 0; k < n; ++k) {
                Rgb beta(1.0f);
                BsdfSample s;
                ASSERT_TRUE(bsdf.sample(draws, &beta, &s));
                ASSERT_EQ(s.eta, 1.0f);
                if (s.lobe & kLobeReflection) {
                    ++reflected;
                    ASSERT_NEAR(dot(s.wi, ng), -dot(-wo, ng), 1e-5f);
                    ASSERT_EQ(s.medium, arriving);
                    ASSERT_EQ(beta.g, 1.0f);
                } else {
                    ASSERT_EQ(s.lobe, kLobeTransmission | kLobeSpecular);
                    ASSERT_EQ(s.wi.x, -wo.x);  // straight on, exactly
                    ASSERT_EQ(s.wi.y, -wo.y);
                    ASSERT_EQ(s.wi.z, -wo.z);
                    ASSERT_EQ(s.medium, beyond);
                    for (int c = 0; c < 3; ++c) ASSERT_EQ(beta[c], tint[c]) << "the tint alone: no 1/eta^2";
                }
            }
            // R' by the slab's closed form, written out here: R + T^2 R / (1 - R^2).
            const double R = fresnelDielectric(std::abs(cosO), 1.5f), T = 1 - R;
            const double slab = R + T * T * R / (1 - R * R);
            const double share = double(reflected) / n, sigma = std::sqrt(slab * (1 - slab) / n);
            EXPECT_NEAR(share, slab, 5 * sigma) << "reflectance; transmittance 1 - R' = " << 1 - slab;
        }
    }
}

TEST(ThinDielectric, SceneValidationRefusesRoughOrOpaqueThinMaterials) {
    Scene s;
    s.name = "thin";
    s.source = "<test>";
    Material m;
    m.name = "sheet";
    m.type = MaterialType::Dielectric;
    m.thin = true;
    s.materials.push_back(m);
    s.environment = EnvironmentLight::constant(Rgb(1.0f));
    EXPECT_NO_THROW(s.validate());
    auto message = [&]() -> std::string {
        try {
            s.validate();
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    s.materials[0].roughness = 0.3f;
    EXPECT_NE(message().find("material 'sheet' (index 0): thin applies to smooth dielectrics only"), std::string::npos)
        << message();
    s.materials[0].roughness = 0.0f;
    s.materials[0].type = MaterialType::Mirror;
    EXPECT_NE(message().find("thin applies to smooth dielectrics only"), std::string::npos) << message();
}

}  // namespace
}  // namespace tyndall
