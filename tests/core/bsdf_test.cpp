// The surface-scattering interface every tracer calls (core/bsdf.h), against its own contract:
//   - sample() agrees with f() and pdf(): each sample's pdf is pdf(wi) and its weight
//     f(wi) |wi . ns| / pdf(wi) (times Veach's adjoint for importance), with a tilted shading
//     normal; the mean weight is the directional albedo by quadrature of f (so the directions
//     really are distributed by pdf), and pdf integrates to the share of draws that give a sample;
//   - a camera path's continuation (every lobe but the diffuse) draws with pdf(wi, those lobes);
//   - radiance and importance are each other's adjoint on a refractive interface:
//     f_radiance(wo, wi) = f_importance(wi, wo), and they differ by eta^2 through it;
//   - the random numbers each component draws (the tracers' images depend on the order).
// The components themselves are checked against closed forms in microfacet_test,
// rough_dielectric_test, coated_diffuse_test and cpu/scattering_closed_form_test.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/bsdf.h"

namespace tyndall {
namespace {

/// Numbers from a seeded generator, counted.
struct Draws {
    std::mt19937 gen;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    int count = 0;
    explicit Draws(unsigned seed) : gen(seed) {}
    float uniform() {
        ++count;
        return u(gen);
    }
};

/// Scripted numbers (then 0.5), counted.
struct Script {
    std::vector<float> values;
    int count = 0;
    float uniform() { return count < int(values.size()) ? values[size_t(count++)] : (++count, 0.5f); }
};

const Vec3 kNg = normalize(Vec3(0.2f, -0.3f, 0.93f));

/// A one-material scene and a hit on it; `tilt` turns the shading normal away from ng.
struct Surface {
    Scene scene;
    SurfaceHit hit;
    SurfacePoint sp;
    Surface(const Material& m, float tilt) {
        TriangleMesh mesh;
        mesh.exteriorMedium = 0;
        mesh.interiorMedium = 1;
        scene.meshes.push_back(mesh);
        scene.materials.push_back(m);
        hit.mesh = 0;
        hit.ng = kNg;
        const Frame f(kNg);
        hit.ns = tilt == 0 ? kNg : normalize(f.toWorld(Vec3(std::sin(tilt), 0.0f, std::cos(tilt))));
        sp.baseColor = m.albedo;
        sp.roughness = m.roughness;
        sp.metallic = m.metallic;
        sp.transmission = m.transmission;
    }
    template <class U>
    Bsdf at(const Vec3& wo, TransportMode mode, U& u) const {
        return Bsdf::at(scene, hit, sp, -wo, /*medium=*/0, mode, u);
    }
};

Material material(MaterialType type, float roughness, const Rgb& albedo) {
    Material m;
    m.type = type;
    m.roughness = roughness;
    m.albedo = albedo;
    m.ior = 1.5f;
    return m;
}

/// A direction at cosine `c` to kNg, azimuth `phi`.
Vec3 around(float c, float phi) {
    float s = std::sqrt(std::max(0.0f, 1 - c * c));
    return Frame(kNg).toWorld(Vec3(s * std::cos(phi), s * std::sin(phi), c));
}

struct Case {
    std::string name;
    Material m;
    float tilt;
};

std::vector<Case> cases() {
    return {
        {"diffuse", material(MaterialType::Diffuse, 0, Rgb(0.7f, 0.5f, 0.3f)), 0.0f},
        {"diffuse, shading normal", material(MaterialType::Diffuse, 0, Rgb(0.7f, 0.5f, 0.3f)), 0.25f},
        {"smooth coat", material(MaterialType::Plastic, 0, Rgb(0.2f, 0.6f, 0.8f)), 0.0f},
        {"rough coat, shading normal", material(MaterialType::Plastic, 0.4f, Rgb(0.2f, 0.6f, 0.8f)), 0.2f},
        {"rough conductor", material(MaterialType::Mirror, 0.35f, Rgb(0.95f, 0.64f, 0.54f)), 0.0f},
        {"rough conductor, shading normal", material(MaterialType::Mirror, 0.35f, Rgb(0.95f, 0.64f, 0.54f)), 0.2f},
        {"rough dielectric", material(MaterialType::Dielectric, 0.5f, Rgb(0.9f, 0.8f, 0.7f)), 0.0f},
    };
}

TEST(Bsdf, SamplesAgreeWithFAndPdfAndTheMeanWeightIsTheAlbedoByQuadrature) {
    for (const Case& c : cases()) {
        Surface s(c.m, c.tilt);
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
            // From outside, and from inside for the dielectric.
            for (float cosO : {0.8f, 0.35f, -0.6f}) {
                if (cosO < 0 && c.m.type != MaterialType::Dielectric) continue;
                const Vec3 wo = around(cosO, 0.9f);
                SCOPED_TRACE(c.name + (mode == TransportMode::Radiance ? ", radiance" : ", importance") + ", cos_o " +
                             std::to_string(cosO));
                Draws draws(7);
                const Bsdf bsdf = s.at(wo, mode, draws);
                const bool adjoint = mode == TransportMode::Importance && c.tilt != 0;

                // Pointwise, every non-delta sample.
                const int n = 100000;
                double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
                int sampled = 0;  // non-delta samples
                for (int k = 0; k < n; ++k) {
                    Rgb beta(1.0f);
                    BsdfSample smp;
                    if (!bsdf.sample(draws, &beta, &smp)) continue;
                    if (smp.lobe & kLobeSpecular) {
                        for (int ch = 0; ch < 3; ++ch) sum[ch] += smp.weight[ch], sum2[ch] += double(smp.weight[ch]) * smp.weight[ch];
                        continue;
                    }
                    ++sampled;
                    const float pdf = bsdf.pdf(smp.wi);
                    ASSERT_NEAR(smp.pdf, pdf, 1e-3f * pdf) << "sample " << k;
                    const Rgb f = bsdf.f(smp.wi);
                    float expect = std::abs(dot(smp.wi, s.hit.ns)) / pdf;
                    if (adjoint) expect *= shadingNormalAdjoint(s.hit.ng, s.hit.ns, wo, smp.wi);
                    for (int ch = 0; ch < 3; ++ch) {
                        ASSERT_NEAR(smp.weight[ch], f[ch] * expect, 2e-3f * f[ch] * expect + 1e-6f) << "sample " << k;
                        ASSERT_EQ(beta[ch], smp.weight[ch]) << "the throughput took the weight";
                        sum[ch] += smp.weight[ch], sum2[ch] += double(smp.weight[ch]) * smp.weight[ch];
                    }
                }

                // Quadrature over the sphere of f |cos_s| (times the adjoint) and of pdf.
                double albedo[3] = {0, 0, 0}, pdfMass = 0;
                const int nc = 500, np = 500;
                const double dOmega = (2.0 / nc) * (2 * kPi / np);
                for (int i = 0; i < nc; ++i)
                    for (int j = 0; j < np; ++j) {
                        const Vec3 wi = around(-1.0f + 2.0f * (i + 0.5f) / nc, 2 * kPi * (j + 0.5f) / np);
                        // Samples on the wrong geometric side end the path: the diffuse lobe's
                        // below the geometric surface, the others' where the shading frame and
                        // the geometry disagree on reflection or transmission.
                        const bool sameSide = dot(wi, kNg) * dot(wo, kNg) > 0;
                        const bool kept = c.m.type == MaterialType::Diffuse
                                              ? sameSide
                                              : sameSide == (dot(wi, s.hit.ns) * dot(wo, s.hit.ns) > 0);
                        if (!kept) continue;
                        pdfMass += bsdf.pdf(wi) * dOmega;
                        const Rgb f = bsdf.f(wi);
                        if (f.isBlack()) continue;
                        double w = std::abs(dot(wi, s.hit.ns)) * dOmega;
                        if (adjoint) w *= shadingNormalAdjoint(s.hit.ng, s.hit.ns, wo, wi);
                        for (int ch = 0; ch < 3; ++ch) albedo[ch] += f[ch] * w;
                    }
                // The smooth coat's delta reflection: weight F(cos_o) per draw, not in f.
                if (c.m.type == MaterialType::Plastic && !c.m.isRough()) {
                    const float F = fresnelDielectric(std::abs(dot(wo, s.hit.ns)), c.m.ior);
                    for (double& a : albedo) a += F;
                }
                for (int ch = 0; ch < 3; ++ch) {
                    const double mean = sum[ch] / n, sigma = std::sqrt(std::max(0.0, sum2[ch] / n - mean * mean) / n);
                    EXPECT_NEAR(mean, albedo[ch], 5 * sigma + 0.01 * albedo[ch]) << "channel " << ch;
                }
                // pdf's mass where samples are kept: the share of draws that gave a non-delta
                // sample (the rest fell on the wrong side, or were a delta).
                EXPECT_NEAR(pdfMass, double(sampled) / n, 0.01 + 5 * std::sqrt(double(sampled)) / n);
            }
        }
    }
}

TEST(Bsdf, TheContinuationsLobesSampleWithPdfOfThoseLobes) {
    // A camera path's continuation samples every lobe but the diffuse (a coat's specular part
    // alone); the glossy shadow ray's MIS weight needs that density, pdf(wi, lobes), and the two
    // weights sum to 1 only if it is the one the sample was drawn with. The lobes' f with the
    // sample's weight, as above.
    const BsdfLobes continuation = BsdfLobes(kLobesAll & ~kLobeDiffuse);
    for (const Case& c : cases()) {
        if (!c.m.isGlossy() && !(c.m.type == MaterialType::Plastic && c.m.isRough())) continue;
        Surface s(c.m, c.tilt);
        for (float cosO : {0.8f, 0.35f, -0.6f}) {
            if (cosO < 0 && c.m.type != MaterialType::Dielectric) continue;
            const Vec3 wo = around(cosO, 0.9f);
            SCOPED_TRACE(c.name + ", cos_o " + std::to_string(cosO));
            Draws draws(11);
            const Bsdf bsdf = s.at(wo, TransportMode::Radiance, draws);
            int sampled = 0;
            for (int k = 0; k < 20000; ++k) {
                Rgb beta(1.0f);
                BsdfSample smp;
                if (!bsdf.sample(draws, &beta, &smp, continuation)) continue;
                ASSERT_TRUE(smp.lobe & kLobeGlossy);
                ++sampled;
                const float pdf = bsdf.pdf(smp.wi, continuation);
                ASSERT_NEAR(smp.pdf, pdf, 1e-3f * pdf) << "sample " << k;
                const Rgb f = bsdf.f(smp.wi, continuation);
                for (int ch = 0; ch < 3; ++ch)
                    ASSERT_NEAR(smp.weight[ch], f[ch] * std::abs(dot(smp.wi, s.hit.ns)) / pdf,
                                2e-3f * smp.weight[ch] + 1e-6f)
                        << "sample " << k;
            }
            EXPECT_GT(sampled, 10000);
            // With the diffuse lobe: a coat's mixture, as sample() draws it; 0 for a component without one.
            const Vec3 wi = around(0.5f, 2.0f);
            EXPECT_EQ(bsdf.pdf(wi, kLobeDiffuse), c.m.type == MaterialType::Plastic ? bsdf.pdf(wi) : 0.0f);
        }
    }
}

TEST(Bsdf, RadianceAndImportanceAreAdjointOnARefractiveInterface) {
    // Rough glass, eta 1.5: f_radiance(wo, wi) built for a path arriving along -wo equals
    // f_importance(wi, wo) built for one arriving along -wi, for reflection and transmission from
    // both sides; through the interface the two modes differ by eta'^2.
    Surface s(material(MaterialType::Dielectric, 0.4f, Rgb(0.9f, 0.8f, 0.7f)), 0.0f);
    std::mt19937 gen(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Draws none(0);
    int transmissions = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3 wo = around(2 * u(gen) - 1, 2 * kPi * u(gen)), wi = around(2 * u(gen) - 1, 2 * kPi * u(gen));
        const Rgb rad = s.at(wo, TransportMode::Radiance, none).f(wi);
        const Rgb imp = s.at(wi, TransportMode::Importance, none).f(wo);
        for (int ch = 0; ch < 3; ++ch) ASSERT_NEAR(rad[ch], imp[ch], 5e-3f * std::max(rad[ch], imp[ch]) + 1e-6f) << k;  // float half vectors
        const bool transmits = dot(wo, kNg) * dot(wi, kNg) < 0;
        const Rgb impSame = s.at(wo, TransportMode::Importance, none).f(wi);
        if (transmits && rad.g > 1e-4f) {
            ++transmissions;
            const float etap = dot(wi, kNg) < 0 ? 1.5f : 1.0f / 1.5f;  // n on wi's side / n on wo's side
            ASSERT_NEAR(rad.g * etap * etap, impSame.g, 1e-3f * impSame.g) << "radiance carries 1/eta^2";
        } else if (!transmits) {
            ASSERT_NEAR(rad.g, impSame.g, 1e-6f * rad.g) << "reflection is symmetric";
        }
    }
    EXPECT_GT(transmissions, 300);
    EXPECT_EQ(none.count, 0) << "a plain dielectric draws nothing to choose its component";

    // Smooth glass: a refraction's weight is tint x (eta_i / eta_t)^2 for radiance, tint for
    // importance; the round trip cancels the scaling.
    Surface g(material(MaterialType::Dielectric, 0.0f, Rgb(0.9f, 0.8f, 0.7f)), 0.0f);
    const Vec3 out = around(0.8f, 0.3f);
    Script refract{{0.99f}};  // above Fresnel's reflectance: refraction
    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
        Rgb beta(1.0f);
        BsdfSample in, back;
        ASSERT_TRUE(g.at(out, mode, refract).sample(refract, &beta, &in));
        ASSERT_TRUE(in.lobe & kLobeTransmission);
        EXPECT_EQ(in.medium, 1);
        EXPECT_FLOAT_EQ(in.eta, 1.0f / 1.5f);
        const float scale = mode == TransportMode::Radiance ? 1.0f / (1.5f * 1.5f) : 1.0f;
        EXPECT_NEAR(in.weight.g, 0.8f * scale, 1e-6f);
        // Back out along the reversed direction.
        ASSERT_TRUE(g.at(in.wi, mode, refract).sample(refract, &beta, &back));
        EXPECT_NEAR(dot(back.wi, out), 1.0f, 1e-5f);
        EXPECT_NEAR(beta.g, 0.8f * 0.8f, 1e-5f) << "the round trip cancels the radiance scaling";
    }
}

TEST(Bsdf, DrawsTheDocumentedRandomNumbers) {
    const Vec3 wo = around(0.7f, 0.4f);
    auto draws = [&](const Material& m, TransportMode mode, BsdfLobes allowed, bool roulette, int* atDraws) {
        Surface s(m, 0.0f);
        Script u{{0.3f, 0.3f, 0.3f, 0.3f, 0.3f}};
        const Bsdf bsdf = s.at(wo, mode, u);
        *atDraws = u.count;
        Rgb beta(1.0f);
        BsdfSample smp;
        bsdf.sample(u, &beta, &smp, allowed, [&](const Rgb&, const Rgb&) { return roulette ? 1.0f : kNoRoulette; });
        return u.count - *atDraws;
    };
    int at = 0;
    Material partly = material(MaterialType::Dielectric, 0, Rgb(0.5f));
    partly.transmission = 0.5f;  // u = 0.3 < 0.5: the dielectric
    Material metalMix = material(MaterialType::Plastic, 0.4f, Rgb(0.5f));
    metalMix.metallic = 0.5f;  // u = 0.3 < 0.5: the conductor, glossy
    struct Expect {
        const char* name;
        Material m;
        TransportMode mode;
        BsdfLobes allowed;
        int at, plain, withRoulette;
    } expects[] = {
        {"diffuse", material(MaterialType::Diffuse, 0, Rgb(0.5f)), TransportMode::Radiance, kLobesAll, 0, 2, 3},
        {"diffuse (importance)", material(MaterialType::Diffuse, 0, Rgb(0.5f)), TransportMode::Importance, kLobesAll, 0, 2, 3},
        {"coat", material(MaterialType::Plastic, 0.4f, Rgb(0.5f)), TransportMode::Radiance, kLobesAll, 0, 3, 4},
        {"coat, specular part", material(MaterialType::Plastic, 0.4f, Rgb(0.5f)), TransportMode::Radiance,
         BsdfLobes(kLobesAll & ~kLobeDiffuse), 0, 2, 3},
        {"rough conductor", material(MaterialType::Mirror, 0.4f, Rgb(0.5f)), TransportMode::Radiance, kLobesAll, 0, 3, 4},
        {"smooth glass", material(MaterialType::Dielectric, 0, Rgb(0.5f)), TransportMode::Radiance, kLobesAll, 0, 1, 2},
        {"interface", material(MaterialType::Interface, 0, Rgb(0.5f)), TransportMode::Radiance, kLobesAll, 0, 1, 2},
        {"partly transmissive", partly, TransportMode::Radiance, kLobesAll, 1, 1, 2},
        {"plastic with a metal part", metalMix, TransportMode::Importance, kLobesAll, 1, 3, 4},
    };
    for (const Expect& e : expects) {
        SCOPED_TRACE(e.name);
        EXPECT_EQ(draws(e.m, e.mode, e.allowed, false, &at), e.plain);
        EXPECT_EQ(at, e.at);
        EXPECT_EQ(draws(e.m, e.mode, e.allowed, true, &at), e.withRoulette);
    }
    // The importance diffuse lobe plays the roulette before drawing its direction: a path that
    // ends there draws one number; in radiance the direction comes first.
    Surface d(material(MaterialType::Diffuse, 0, Rgb(0.5f)), 0.0f);
    for (TransportMode mode : {TransportMode::Importance, TransportMode::Radiance}) {
        Script u{{0.9f, 0.1f, 0.9f}};
        Rgb beta(1.0f);
        BsdfSample smp;
        const bool goesOn = d.at(wo, mode, u).sample(u, &beta, &smp, kLobesAll,
                                                     [](const Rgb&, const Rgb&) { return 0.5f; });
        EXPECT_FALSE(goesOn);
        EXPECT_EQ(u.count, mode == TransportMode::Importance ? 1 : 3);
    }
}

}  // namespace
}  // namespace tyndall
