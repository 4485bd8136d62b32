// The thin-walled dielectric (Material::thin): a sheet's reflectance and transmittance against the
// thin slab's closed form, and that closed form against a slab traced ray by ray.
//   - fresnelThinSlab (R' = R + T^2 R / (1 - R^2)) against a random walk inside a slab of index
//     eta: Fresnel at the first face for the incident angle, at the inner faces for the refracted
//     angle (Snell), counted until the light leaves on either side;
//   - Bsdf::sample on a thin dielectric, from both sides and at several angles: the share of
//     reflections is R' (binomial bound), a transmission goes straight on (wi = -wo, no refraction
//     offset, eta 1) with the tint as its weight, into the medium on the other side; reflection
//     keeps the arriving medium; radiance and importance alike;
//   - the thin rough sheet (RoughDielectric::thin): its reflected plus transmitted energy equals
//     the albedo of a white GGX conductor of the same roughness (the white furnace: the sheet
//     loses only what masking loses), the sampled weights agree with the quadrature of eval and
//     the directions with pdf (chi-square) from both sides, f is symmetric and the same in both
//     modes, nearly smooth it splits R' / 1 - R' as the smooth sheet, and through Bsdf it is a
//     glossy lobe that crosses into the other medium with eta 1.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/bsdf.h"
#include "core/environment_light.h"
#include "core/error.h"
#include "tests/core/bsdf_checks.h"

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
struct SeededDraws {
    std::mt19937 gen;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    explicit SeededDraws(unsigned seed) : gen(seed) {}
    float uniform() { return u(gen); }
};

/// One mesh between medium 0 (outside) and 1 (inside) with a thin-walled glass of IOR 1.5.
Scene thinSheetScene(float roughness, Rgb tint) {
    Scene scene;
    TriangleMesh mesh;
    mesh.exteriorMedium = 0;
    mesh.interiorMedium = 1;
    scene.meshes.push_back(mesh);
    Material m;
    m.type = MaterialType::Dielectric;
    m.thin = true;
    m.roughness = roughness;
    m.ior = 1.5f;
    m.albedo = tint;
    scene.materials.push_back(m);
    return scene;
}

TEST(ThinDielectric, SheetReflectsTheSlabsShareAndTransmitsStraightThrough) {
    const Vec3 ng = normalize(Vec3(0.3f, 0.2f, 0.93f));
    const Rgb tint(0.9f, 0.7f, 0.5f);
    const Scene scene = thinSheetScene(0.0f, tint);
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
            SeededDraws draws(5);
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

/// Quadrature of g(wi) |cos_i| over the hemisphere on the side `sign` (+1: z > 0), fine in theta so
/// that lobes of alpha ~ 0.1 are resolved.
template <class F>
double hemisphereQuadrature(F g, float sign, int nt = 600, int np = 150) {
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double theta = 0.5 * kPi * (i + 0.5) / nt;
        for (int j = 0; j < np; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / np;
            const Vec3 wi(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                          float(sign * std::cos(theta)));
            sum += g(wi) * std::cos(theta) * std::sin(theta);
        }
    }
    return sum * (0.5 * kPi / nt) * (2.0 * kPi / np);
}

TEST(ThinDielectric, RoughSheetLosesOnlyWhatMaskingLosesAndSamplesItsEval) {
    for (float roughness : {0.3f, 0.7f}) {
        const Ggx ggx = Ggx::fromRoughness(roughness);
        const RoughDielectric sheet{ggx, 1.5f, Rgb(1.0f), true};
        const RoughConductor white{ggx, Rgb(1.0f)};
        for (float cosO : roughness < 0.5f ? std::vector<float>{0.9f, -0.4f} : std::vector<float>{0.5f}) {
            SCOPED_TRACE("roughness " + std::to_string(roughness) + ", cos_o " + std::to_string(cosO));
            const Vec3 wo = dirOf(cosO, 0.9f);
            const float side = cosO > 0 ? 1.0f : -1.0f;
            auto f = [&](const Vec3& wi) { return double(sheet.eval(wo, wi, TransportMode::Radiance).g); };
            const double qR = hemisphereQuadrature(f, side), qT = hemisphereQuadrature(f, -side);
            // A white conductor seen from wo's side: the same microfacets with F = 1.
            const Vec3 woUp(wo.x, wo.y, std::abs(wo.z));
            const double furnace =
                hemisphereQuadrature([&](const Vec3& wi) { return double(white.eval(woUp, wi).g); }, 1.0f);
            EXPECT_NEAR(qR + qT, furnace, 2e-3) << "R " << qR << " T " << qT;
            EXPECT_LE(qR + qT, 1.0 + 1e-3);
            EXPECT_GT(qT, 0.5);  // mostly transmitted, as glass at these angles
            // Sampling: the mean weight of each lobe is its quadrature (seeded, 4 standard errors).
            std::mt19937 gen(31);
            std::uniform_real_distribution<float> u(0.0f, 1.0f);
            const int n = 50000;
            double sr = 0, sr2 = 0, st = 0, st2 = 0;
            for (int k = 0; k < n; ++k) {
                const float u0 = u(gen), u1 = u(gen), u2 = u(gen);
                const MicrofacetSample m = sheet.sample(wo, u0, u1, u2, TransportMode::Importance);
                if (!m.valid) continue;
                ASSERT_EQ(m.transmitted, wo.z * m.wi.z < 0);
                const double w = m.weight.g;
                (m.transmitted ? st : sr) += w;
                (m.transmitted ? st2 : sr2) += w * w;
            }
            const double mr = sr / n, mt = st / n;
            const double seR = std::sqrt(std::max(0.0, sr2 / n - mr * mr) / n),
                         seT = std::sqrt(std::max(0.0, st2 / n - mt * mt) / n);
            EXPECT_NEAR(mr, qR, 4 * seR + 1e-3);
            EXPECT_NEAR(mt, qT, 4 * seT + 1e-3);
            const std::string what = "thin rough sheet, roughness " + std::to_string(roughness) + ", cos " + std::to_string(cosO);
            chiSquare(
                [&](std::mt19937& g, std::uniform_real_distribution<float>& v, Vec3* wi) {
                    const float u0 = v(g), u1 = v(g), u2 = v(g);
                    const MicrofacetSample m = sheet.sample(wo, u0, u1, u2, TransportMode::Radiance);
                    *wi = m.wi;
                    return m.valid;
                },
                [&](const Vec3& wi) { return sheet.pdf(wo, wi); }, what.c_str());
        }
    }
}

TEST(ThinDielectric, RoughSheetIsReciprocalAndBecomesTheSmoothSheet) {
    const RoughDielectric sheet{Ggx::fromRoughness(0.4f), 1.5f, Rgb(0.8f), true};
    std::mt19937 gen(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    int nonzero = 0;
    for (int k = 0; k < 2000; ++k) {
        const Vec3 a = dirOf(2 * u(gen) - 1, 2 * kPi * u(gen)), b = dirOf(2 * u(gen) - 1, 2 * kPi * u(gen));
        const float ab = sheet.eval(a, b, TransportMode::Radiance).g;
        EXPECT_NEAR(ab, sheet.eval(b, a, TransportMode::Radiance).g, 1e-4f * (1 + ab));
        EXPECT_EQ(ab, sheet.eval(a, b, TransportMode::Importance).g);  // no eta^2: the index is the same beyond
        nonzero += ab > 0;
    }
    EXPECT_GT(nonzero, 1000);
    // Nearly smooth: the reflected energy is the smooth sheet's R', the rest crosses near -wo (by
    // sampling: the lobes are too narrow for the quadrature).
    const RoughDielectric nearlySmooth{Ggx::fromRoughness(0.1f), 1.5f, Rgb(1.0f), true};
    for (float cosO : {0.95f, 0.5f, -0.3f}) {
        const Vec3 wo = dirOf(cosO, 0.4f);
        const double R = fresnelThinSlab(cosO, 1.5f);
        double reflected = 0, transmitted = 0;
        int crossed = 0, straight = 0;
        const int n = 20000;
        for (int k = 0; k < n; ++k) {
            const float u0 = u(gen), u1 = u(gen), u2 = u(gen);
            const MicrofacetSample m = nearlySmooth.sample(wo, u0, u1, u2, TransportMode::Radiance);
            if (!m.valid) continue;
            (m.transmitted ? transmitted : reflected) += m.weight.g / n;
            crossed += m.transmitted;
            straight += m.transmitted && dot(m.wi, -wo) > 0.99f;
        }
        EXPECT_GT(straight, 0.98 * crossed) << "within 8 degrees of straight on, but for GGX's tail";
        EXPECT_NEAR(reflected, R, 0.01) << "cos_o " << cosO;
        EXPECT_NEAR(transmitted, 1 - R, 0.01) << "cos_o " << cosO;
    }
}

TEST(ThinDielectric, RoughSheetThroughTheBsdfIsGlossyAndCrossesWithoutRefraction) {
    const Scene scene = thinSheetScene(0.5f, Material{}.albedo);
    SurfaceHit hit;
    hit.mesh = 0;
    hit.ng = hit.ns = Vec3(0, 0, 1);
    SurfacePoint sp;
    sp.baseColor = Rgb(1.0f);
    sp.roughness = 0.5f;
    const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.9f));
    SeededDraws draws(9);
    const Bsdf bsdf = Bsdf::at(scene, hit, sp, -wo, 0, TransportMode::Radiance, draws);
    EXPECT_EQ(bsdf.lobes(), kLobeReflection | kLobeTransmission | kLobeGlossy);
    int crossed = 0;
    for (int k = 0; k < 2000; ++k) {
        Rgb beta(1.0f);
        BsdfSample s;
        if (!bsdf.sample(draws, &beta, &s)) continue;
        ASSERT_EQ(s.eta, 1.0f);
        ASSERT_EQ(s.medium, (s.lobe & kLobeTransmission) ? 1 : 0);
        ASSERT_NEAR(bsdf.pdf(s.wi), s.pdf, 1e-4f * s.pdf);
        crossed += (s.lobe & kLobeTransmission) != 0;
    }
    EXPECT_GT(crossed, 1600);
}

TEST(ThinDielectric, SceneValidationRefusesOpaqueThinMaterials) {
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
    s.materials[0].roughness = 0.3f;  // a frosted pane
    EXPECT_NO_THROW(s.validate());
    s.materials[0].roughness = 0.0f;
    s.materials[0].type = MaterialType::Mirror;
    EXPECT_NE(message().find("material 'sheet' (index 0): thin applies to dielectrics only"), std::string::npos)
        << message();
}

}  // namespace
}  // namespace tyndall
