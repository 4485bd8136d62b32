// The surface scattering every tracer shares (core/bsdf.h), checked against closed forms
// and implementations written here, never against itself or another tracer: PPB and the reference
// path tracer both call these functions, so a bug in them moves both images together and the
// consistency tests cannot see it.
//   - smooth dielectric and mirror sampling: Fresnel's reflected share (Hecht's angle form of the
//     Fresnel equations), the law of reflection, Snell's law, the medium switch, and the radiance
//     scaling (eta_i / eta_t)^2 alone, from each side (a round trip through glass cancels it);
//   - the rough conductor with a coloured F0 (glTF metallic = 1): eval against GGX, Smith and
//     Schlick written out here, and the mean sampled weight of each channel against the directional
//     albedo by quadrature of that independent f (the furnace tests use F0 = 1, where any Fresnel
//     formula gives 1).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cpu/surface_scattering.h"

namespace tyndall {
namespace {

// ---- Independent formulas (textbook forms, not the renderer's algebra).

/// Unpolarised Fresnel reflectance from the angles (Hecht, Optics, 4.42-4.43): eta = n_t / n_i.
double fresnelByAngles(double cosI, double eta) {
    double thetaI = std::acos(std::min(1.0, std::abs(cosI)));
    double sinT = std::sin(thetaI) / eta;
    if (sinT >= 1.0) return 1.0;
    double thetaT = std::asin(sinT);
    if (thetaI < 1e-6) return std::pow((eta - 1) / (eta + 1), 2);
    double rs = std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
    double rp = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
    return 0.5 * (rs * rs + rp * rp);
}

/// GGX in the (n.h)^2 (a^2 - 1) + 1 form (Walter et al. 2007, eq. 33 rewritten).
double ggxD(double alpha, double cosH) {
    if (cosH <= 0) return 0;
    double a2 = alpha * alpha, k = cosH * cosH * (a2 - 1) + 1;
    return a2 / (kPi * k * k);
}
/// Smith's Lambda for GGX from the angle (Heitz 2014, eq. 72).
double smithLambda(double alpha, double cosT) {
    double tanT = std::sqrt(std::max(0.0, 1 - cosT * cosT)) / cosT;
    return 0.5 * (-1 + std::sqrt(1 + alpha * alpha * tanT * tanT));
}
/// f of a GGX conductor with Schlick's Fresnel, one channel, in a frame with the normal `n`.
double conductorF(double f0, double alpha, const Vec3& n, const Vec3& wo, const Vec3& wi) {
    double co = dot(wo, n), ci = dot(wi, n);
    if (co <= 0 || ci <= 0) return 0;
    Vec3 h = normalize(wo + wi);
    double fr = f0 + (1 - f0) * std::pow(1 - double(dot(wo, h)), 5);
    double g = 1 / (1 + smithLambda(alpha, co) + smithLambda(alpha, ci));
    return fr * ggxD(alpha, dot(h, n)) * g / (4 * co * ci);
}

/// A hit on the plane through the origin with normal `n` (exterior side), on a one-triangle mesh
/// of `material` that separates medium 0 (exterior) from medium 1 (interior).
struct PlaneHit {
    Scene scene;
    SurfaceHit hit;
    PlaneHit(const Vec3& n, const Material& material) {
        TriangleMesh mesh;
        mesh.interiorMedium = 1;
        mesh.exteriorMedium = 0;
        scene.meshes.push_back(mesh);
        scene.materials.push_back(material);
        hit.mesh = 0;
        hit.ng = hit.ns = normalize(n);
    }
    /// The Bsdf for a path arriving along dIn in `medium`, base colour `tint`.
    template <class Uniforms>
    Bsdf at(const Vec3& dIn, MediumId medium, const Rgb& tint, TransportMode mode, Uniforms& u) const {
        SurfacePoint sp;
        sp.baseColor = tint;
        sp.roughness = scene.materials[0].roughness;
        return Bsdf::at(scene, hit, sp, dIn, medium, mode, u);
    }
};

/// Every number drawn is `u` (a delta lobe draws one).
struct FixedUniform {
    float u;
    float uniform() const { return u; }
};

/// Numbers from a seeded generator.
struct GenUniforms {
    std::mt19937& gen;
    std::uniform_real_distribution<float> u{0.0f, 1.0f};
    float uniform() { return u(gen); }
};

Vec3 tilted(float cosTheta, float phi, const Frame& f) {
    float s = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
    return f.toWorld(Vec3(s * std::cos(phi), s * std::sin(phi), cosTheta));
}

// ---- Smooth dielectric and mirror.

TEST(SurfaceScatteringClosedForm, SmoothDielectricFollowsFresnelSnellAndScalesRadianceByEtaSquared) {
    const Vec3 n = normalize(Vec3(0.3f, 0.8f, -0.5f));  // an arbitrary orientation
    const Frame frame(n);
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.5f;
    PlaneHit p(n, glass);
    const Rgb tint(0.9f, 0.6f, 0.3f);
    const int kU = 4000;  // stratified u: the reflected share is exact to 1 / kU
    for (bool fromOutside : {true, false}) {
        const double etaT = fromOutside ? 1.5 : 1.0 / 1.5;  // n_t / n_i
        for (float cosI : {1.0f, 0.9f, 0.6f, 0.3f, 0.1f}) {
            // dIn travels toward the surface from the side it arrives on.
            Vec3 wo = tilted(cosI, 0.7f, frame);
            if (!fromOutside) wo = -wo;
            const Vec3 dIn = -wo;
            SCOPED_TRACE(std::string(fromOutside ? "outside" : "inside") + " cos " + std::to_string(cosI));
            const double F = fresnelByAngles(cosI, etaT);
            int reflected = 0;
            for (int k = 0; k < kU; ++k) {
                FixedUniform u{(k + 0.5f) / kU};
                for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                    const Bsdf bsdf = p.at(dIn, /*medium=*/7, tint, mode, u);
                    BsdfSample ev;
                    Rgb beta(1.0f);
                    ASSERT_TRUE(bsdf.sample(u, &beta, &ev));
                    const bool transmitted = (ev.lobe & kLobeTransmission) != 0;
                    for (int c = 0; c < 3; ++c) EXPECT_EQ(beta[c], ev.weight[c]) << "beta took the weight";
                    const float side = dot(ev.wi, n) * dot(wo, n);  // > 0: reflected
                    EXPECT_NEAR(length(ev.wi), 1.0f, 1e-5f);
                    if (side > 0) {
                        if (mode == TransportMode::Radiance) ++reflected;
                        // Law of reflection: d = dIn - 2 (dIn.n) n.
                        Vec3 r = dIn - n * (2 * dot(dIn, n));
                        EXPECT_LT(length(ev.wi - r), 1e-5f);
                        EXPECT_FALSE(transmitted);
                        EXPECT_EQ(ev.medium, 7) << "reflection keeps the current medium";
                        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ev.weight[c], 1.0f, 1e-6f) << "untinted reflection";
                    } else {
                        // Snell: n_i sin_i = n_t sin_t, in the plane of incidence.
                        double sinI = std::sqrt(1 - double(cosI) * cosI);
                        double sinT = length(cross(ev.wi, n));
                        EXPECT_NEAR(sinT, sinI / etaT, 2e-5);
                        EXPECT_NEAR(dot(cross(dIn, n), ev.wi), 0.0f, 1e-5f) << "left the plane of incidence";
                        EXPECT_TRUE(transmitted);
                        EXPECT_EQ(ev.medium, fromOutside ? 1 : 0);
                        // Radiance crossing into n_t is scaled by (n_i / n_t)^2; power is not.
                        double scale = mode == TransportMode::Radiance ? 1 / (etaT * etaT) : 1.0;
                        for (int c = 0; c < 3; ++c)
                            EXPECT_NEAR(ev.weight[c], tint[c] * scale, 1e-5 * scale) << "channel " << c;
                    }
                }
            }
            EXPECT_NEAR(double(reflected) / kU, F, 1.0 / kU + 1e-5) << "Fresnel's share of reflections";
        }
    }
    // Beyond the critical angle from inside (sin_i > 1 / 1.5): every u reflects.
    Vec3 dIn = tilted(0.5f, 0.2f, frame);  // from inside: travels along +n side... toward the exterior
    for (int k = 0; k < 64; ++k) {
        FixedUniform u{(k + 0.5f) / 64};
        BsdfSample ev;
        Rgb beta(1.0f);
        ASSERT_TRUE(p.at(dIn, 1, tint, TransportMode::Radiance, u).sample(u, &beta, &ev));
        EXPECT_FALSE(ev.lobe & kLobeTransmission) << "total internal reflection";
        EXPECT_LT(dot(ev.wi, n), 0.0f);
    }
}

TEST(SurfaceScatteringClosedForm, SmoothMirrorReflectsWithItsTint) {
    const Vec3 n = normalize(Vec3(-0.2f, 0.1f, 0.9f));
    Material mirror;
    mirror.type = MaterialType::Mirror;
    PlaneHit p(n, mirror);
    const Rgb tint(0.95f, 0.64f, 0.54f);
    for (float cosI : {1.0f, 0.5f, 0.05f})
        for (float sign : {1.0f, -1.0f}) {  // both faces of a mirror reflect
            Vec3 dIn = -tilted(cosI, 2.0f, Frame(n)) * sign;
            FixedUniform u{0.5f};
            BsdfSample ev;
            Rgb beta(1.0f);
            ASSERT_TRUE(p.at(dIn, 3, tint, TransportMode::Radiance, u).sample(u, &beta, &ev));
            EXPECT_LT(length(ev.wi - (dIn - n * (2 * dot(dIn, n)))), 1e-5f);
            EXPECT_EQ(ev.medium, 3);
            for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(ev.weight[c], tint[c]);
        }
}

// ---- Rough conductor with a coloured F0.

TEST(SurfaceScatteringClosedForm, RoughConductorWithColouredF0MatchesIndependentGgxSmithSchlick) {
    const Vec3 n = normalize(Vec3(0.4f, -0.3f, 0.87f));
    const Frame frame(n);
    Material metal;
    metal.type = MaterialType::Mirror;
    const Rgb f0(0.95f, 0.64f, 0.54f);  // copper
    std::mt19937 gen(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    GenUniforms draws{gen};
    for (float roughness : {0.3f, 0.6f}) {
        metal.roughness = roughness;
        PlaneHit p(n, metal);
        const double alpha = double(roughness) * roughness;
        for (float cosO : {0.95f, 0.5f, 0.12f}) {
            SCOPED_TRACE("roughness " + std::to_string(roughness) + " cos_o " + std::to_string(cosO));
            const Vec3 wo = tilted(cosO, 0.4f, frame);
            const Bsdf bsdf = p.at(-wo, 0, f0, TransportMode::Radiance, draws);
            // Pointwise: eval = the independent f, each channel, where f is not tiny.
            for (int k = 0; k < 200; ++k) {
                Vec3 wi = tilted(0.02f + 0.98f * u(gen), 2 * kPi * u(gen), frame);
                Rgb f = bsdf.f(wi);
                for (int c = 0; c < 3; ++c) {
                    double ref = conductorF(f0[c], alpha, n, wo, wi);
                    EXPECT_NEAR(f[c], ref, 2e-4 * ref + 1e-6) << "channel " << c;
                }
            }
            // The sampled weights' mean per channel = directional albedo by quadrature of the
            // independent f (not of eval, not of the pdf).
            double quad[3] = {0, 0, 0};
            const int nq = 500;
            for (int i = 0; i < nq; ++i)
                for (int j = 0; j < nq; ++j) {
                    float c = (i + 0.5f) / nq;
                    Vec3 wi = tilted(c, 2 * kPi * (j + 0.5f) / nq, frame);
                    for (int ch = 0; ch < 3; ++ch) quad[ch] += conductorF(f0[ch], alpha, n, wo, wi) * c;
                }
            for (double& q : quad) q *= (1.0 / nq) * (2 * kPi / nq);
            const int ns = 60000;
            double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
            for (int k = 0; k < ns; ++k) {
                BsdfSample ev;
                Rgb beta(1.0f);
                if (!bsdf.sample(draws, &beta, &ev)) continue;
                EXPECT_GT(dot(ev.wi, n), 0.0f);
                for (int c = 0; c < 3; ++c) sum[c] += ev.weight[c], sum2[c] += double(ev.weight[c]) * ev.weight[c];
            }
            for (int c = 0; c < 3; ++c) {
                double mean = sum[c] / ns, sigma = std::sqrt(std::max(0.0, sum2[c] / ns - mean * mean) / ns);
                // 5 sigma (measured spread ~0.1-0.3% of the mean) plus the quadrature's 0.3% at grazing.
                EXPECT_NEAR(mean, quad[c], 5 * sigma + 0.003 * quad[c]) << "channel " << c;
            }
            // The colour: Schlick's grazing brightening makes red/blue fall toward 1 at grazing.
            double ratio = (sum[0] / ns) / (sum[2] / ns);
            EXPECT_NEAR(ratio, quad[0] / quad[2], 0.01 * ratio);
        }
    }
}

}  // namespace
}  // namespace tyndall
