// A scene with an analytic answer, run through BOTH estimators: a light at the centre of a sphere
// (radius R = 1) filled with a homogeneous medium, vacuum outside.
//
// Single scattering (both estimators cut to it: PPB stores only each photon path's first beam,
// the reference stops after one scattering vertex). For a light of intensity I(w) (a spot's
// smoothstep falloff included) the radiance along a camera ray o + s d through the medium,
// s in [s_in, s_out], is the line integral
//     L1 = int sigma_s I(x/|x|) exp(-sigma_t |x|) / |x|^2  p(theta)  exp(-sigma_t (s - s_in)) ds,
// x = o + s d, cos(theta) = dot(x/|x|, -d) (light leaves the centre along x/|x| and travels
// toward the camera along -d). With s = s_c + h tan(phi) (h the ray's distance to the light)
// ds/|x|^2 = dphi/h and the integrand is smooth: Simpson's rule in double with 2000 intervals.
// Each pixel's expected value is that integral averaged over the pixel (a 6x6 grid of rays).
// This is exactly what the beam x ray estimator's normalisation (kernel, 1/sin, phase sign,
// power per path, both transmittances) has to reproduce:
//   - camera inside the medium, beside a spot light's cone: primary segments, gathered by the CPU
//     beam rasterizer (a spot, so that no beam passes by the camera: beams within r of the camera
//     reach every pixel at once, which makes a point light's image flicker by a few percent per
//     pass and the test slow, not wrong);
//   - camera outside, looking at a point light through the Interface hull: secondary segments,
//     gathered through the beam BVH after the camera path crossed the interface.
// Coloured coefficients and g = +0.5 make each channel and the phase convention count.
//
// Direct irradiance on a diffuse inner wall with a purely absorbing medium: E = I exp(-sigma_t R)
// / R^2 everywhere on the wall, so a pixel seeing the wall at distance D_cam has
//     L = rho/pi E exp(-sigma_t D_cam)
// (surface photons and their 2D kernel; the reference's NEE through the medium).
//
// Comparison: pixels are grouped in bins of the ray's distance h to the light (pixels whose rays
// pass within 0.1 R of the light are left out: there the 1/h field changes on the kernel's scale).
// For each bin the ratio sum(estimate)/sum(exact) must be within 4 standard errors plus a stated
// bias allowance (reference 0.2%: integration and pixel-averaging error; PPB 1%: the kernel
// blur, about (r/h)^2/7 = 0.9% at the bin edge h = 0.1 with r = 0.025, much less in the bulk);
// the standard errors come from the reference's per-pixel sample variance and, for PPB, from 8
// independent batches of passes. The standard errors must themselves be small (about 1%), so the
// test can fail: a missing factor 2, pi or 4 pi, or a flipped phase sign is far outside.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "cpu/reference_tracer.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

constexpr float kR = 1.0f;

Light centreLight(LightType type) {
    Light l;
    l.name = type == LightType::Spot ? "spot" : "point";
    l.type = type;
    l.position = Vec3(0.0f);
    l.intensity = Rgb(2.0f, 1.5f, 1.0f);
    l.direction = Vec3(0.0f, 0.0f, -1.0f);
    l.cosOuterAngle = std::cos(40.0f * kPi / 180.0f);
    l.cosInnerAngle = std::cos(28.0f * kPi / 180.0f);
    return l;
}

double hgDouble(double cosTheta, double g) {
    double denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * M_PI * denom * std::sqrt(denom));
}

/// Single-scattered radiance along o + s d, s in [sIn, sOut], from `light` at the origin.
Rgb singleScatter(const Vec3& o, const Vec3& d, double sIn, double sOut, const Medium& m, const Light& light) {
    double sc = -double(dot(o, d));
    Vec3 p = o + d * float(sc);
    double h = length(p);
    double phiA = std::atan2(sIn - sc, h), phiB = std::atan2(sOut - sc, h);
    const int n = 1000;  // even; the spot's smoothstep edge is only C1
    double step = (phiB - phiA) / n, sum[3] = {0, 0, 0};
    for (int k = 0; k <= n; ++k) {
        double phi = phiA + k * step;
        double s = sc + h * std::tan(phi), dist = h / std::cos(phi);
        double x[3] = {o.x + s * d.x, o.y + s * d.y, o.z + s * d.z};
        double cosTheta = -(x[0] * d.x + x[1] * d.y + x[2] * d.z) / dist;
        double falloff = 1.0;
        if (light.type == LightType::Spot) {
            Vec3 w(float(x[0] / dist), float(x[1] / dist), float(x[2] / dist));
            falloff = light.spotFalloff(dot(w, light.direction));
        }
        double weight = (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * falloff / h * hgDouble(cosTheta, m.g);
        for (int c = 0; c < 3; ++c)
            sum[c] += weight * m.sigmaS[c] * light.intensity[c] * std::exp(-m.sigmaT()[c] * (dist + (s - sIn)));
    }
    return Rgb(float(sum[0] * step / 3.0), float(sum[1] * step / 3.0), float(sum[2] * step / 3.0));
}

/// Where a ray o + s d runs inside the sphere mesh (exact facets, via Embree): false if it misses.
bool mediumInterval(const EmbreeScene& rt, const Ray& ray, bool cameraInside, float* sIn, float* sOut) {
    SurfaceHit a;
    if (!rt.intersect(ray, &a)) return false;
    if (cameraInside) {
        *sIn = 0;
        *sOut = a.t;
        return true;
    }
    SurfaceHit b;
    Ray inside{rt.offsetOrigin(a.p, a.ng, ray.d), ray.d};
    if (!rt.intersect(inside, &b)) return false;
    *sIn = a.t;
    *sOut = a.t + length(b.p - a.p);
    return true;
}

struct Expected {
    Image radiance;            ///< pixel-averaged closed form
    std::vector<float> h;      ///< distance of the pixel-centre ray to the light (-1: no medium)
};

/// The closed form for every pixel: `perRay(ray)` averaged over a 6x6 grid inside the pixel.
template <typename PerRay>
Expected expectedImage(const Scene& scene, const EmbreeScene& rt, int size, PerRay perRay) {
    Expected e{Image(size, size), std::vector<float>(size_t(size) * size, -1.0f)};
    const int k = 6;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            Rgb sum;
            for (int j = 0; j < k; ++j)
                for (int i = 0; i < k; ++i) {
                    Ray ray = scene.camera.generateRay(x + (i + 0.5f) / k, y + (j + 0.5f) / k, size, size, {0.5f, 0.5f});
                    sum += perRay(ray);
                }
            e.radiance.at(x, y) = sum / float(k * k);
            Ray centre = scene.camera.generateRay(x + 0.5f, y + 0.5f, size, size, {0.5f, 0.5f});
            float s0, s1;
            if (mediumInterval(rt, centre, rt.mediumAt(scene.camera.position) != kVacuum, &s0, &s1))
                e.h[size_t(y) * size + x] = length(centre.o + centre.d * -dot(centre.o, centre.d));
        }
    return e;
}

struct Bin {
    float hLo, hHi;
};

/// Ratio (sum of estimate)/(sum of exact) over the bin's pixels and channels, for each of
/// `estimates` (independent batches); returns mean ratio and its standard error.
test::MeanVar binRatio(const std::vector<Image>& batches, const Expected& e, const Bin& bin) {
    std::vector<double> ratios;
    for (const Image& img : batches) {
        double num = 0, den = 0;
        for (size_t p = 0; p < img.pixels.size(); ++p) {
            if (e.h[p] < bin.hLo || e.h[p] >= bin.hHi) continue;
            for (int c = 0; c < 3; ++c) num += img.pixels[p][c], den += e.radiance.pixels[p][c];
        }
        ratios.push_back(num / den);
    }
    return test::meanVar(ratios);
}

/// Reference: one image with per-pixel variance; the bin ratio's standard error from it (pixels
/// are independent).
void checkReference(const char* what, const ReferenceImage& ref, const Expected& e, const std::vector<Bin>& bins,
                    double maxStdErr, double biasAllowance) {
    for (const Bin& bin : bins) {
        double num = 0, den = 0, var = 0;
        for (size_t p = 0; p < ref.mean.pixels.size(); ++p) {
            if (e.h[p] < bin.hLo || e.h[p] >= bin.hHi) continue;
            // The channels of one pixel come from the same paths: bound the variance of their sum
            // by (sum of standard deviations)^2 (Cauchy-Schwarz) instead of assuming independence.
            double sd = 0;
            for (int c = 0; c < 3; ++c) {
                num += ref.mean.pixels[p][c];
                den += e.radiance.pixels[p][c];
                sd += std::sqrt(double(ref.varianceOfMean.pixels[p][c]));
            }
            var += sd * sd;
        }
        double ratio = num / den, stdErr = std::sqrt(var) / den;
        std::printf("%s reference, h in [%.2f, %.2f): ratio %.4f +- %.4f\n", what, bin.hLo, bin.hHi, ratio, stdErr);
        EXPECT_LT(stdErr, maxStdErr) << what << ": too noisy to test";
        EXPECT_NEAR(ratio, 1.0, 4.0 * stdErr + biasAllowance) << what << " reference, h in [" << bin.hLo << ", " << bin.hHi << ")";
    }
}

void checkPpb(const char* what, const std::vector<Image>& batches, const Expected& e, const std::vector<Bin>& bins,
              double maxStdErr, double biasAllowance) {
    for (const Bin& bin : bins) {
        test::MeanVar r = binRatio(batches, e, bin);
        double stdErr = std::sqrt(r.var / double(r.n));
        std::printf("%s PPB, h in [%.2f, %.2f): ratio %.4f +- %.4f\n", what, bin.hLo, bin.hHi, r.mean, stdErr);
        EXPECT_LT(stdErr, maxStdErr) << what << ": too noisy to test";
        EXPECT_NEAR(r.mean, 1.0, 4.0 * stdErr + biasAllowance) << what << " PPB, h in [" << bin.hLo << ", " << bin.hHi << ")";
    }
}

/// `batches` independent PPB estimates, each the mean of `passesPerBatch` passes.
std::vector<Image> ppbBatches(const Scene& scene, const RenderSettings& settings, int batches, int passesPerBatch) {
    PassRenderer renderer(scene, settings);
    std::vector<Image> out;
    for (int b = 0; b < batches; ++b) out.push_back(test::renderPpbPasses(renderer, uint64_t(b) * passesPerBatch, passesPerBatch));
    return out;
}

Medium scatteringMedium() {
    Medium m;
    m.name = "amber";
    m.sigmaS = Rgb(0.6f, 0.45f, 0.3f);
    m.sigmaA = Rgb(0.4f, 0.35f, 0.6f);
    m.g = 0.5f;
    return m;
}

/// PPB cut to single scattering, with a beam radius that stays ~constant (a huge schedule
/// offset), small against the excluded 0.15 R around the light.
RenderSettings singleScatterPpbSettings(int size) {
    RenderSettings s;
    s.width = s.height = size;
    s.photonsPerPass = 20000;
    s.maxPhotonBounces = 1;
    s.radius = 0.025f;
    s.surfaceRadius = 0.05f;
    s.radiusOffset = 1000000000000ull;
    s.seed = 7;
    return s;
}

ReferenceSettings singleScatterReferenceSettings(int size, uint32_t spp) {
    ReferenceSettings s;
    s.width = s.height = size;
    s.samplesPerPixel = spp;
    s.maxDepth = 1;
    s.seed = 11;
    return s;
}

void runSingleScatter(const char* what, const Light& light, const Camera& camera, bool cameraInside,
                      const std::vector<Bin>& bins) {
    const int size = 32;
    Medium medium = scatteringMedium();
    Scene scene = test::makeMediumSphereScene(medium, kR, light, camera);
    EmbreeScene rt(scene);
    ASSERT_EQ(rt.mediumAt(camera.position) != kVacuum, cameraInside);
    Expected e = expectedImage(scene, rt, size, [&](const Ray& ray) {
        float s0, s1;
        if (!mediumInterval(rt, ray, cameraInside, &s0, &s1)) return Rgb(0.0f);
        return singleScatter(ray.o, ray.d, s0, s1, medium, light);
    });

    ReferenceImage ref = ReferenceTracer(rt, singleScatterReferenceSettings(size, 256)).render();
    checkReference(what, ref, e, bins, 0.012, 0.002);

    std::vector<Image> batches = ppbBatches(scene, singleScatterPpbSettings(size), 8, 2);
    checkPpb(what, batches, e, bins, 0.01, 0.01);

    if (::testing::Test::HasFailure()) {
        Accumulator acc(size, size);
        for (const Image& b : batches) acc.addPass(b);
        std::string base = std::string("analytic_") + (cameraInside ? "inside" : "outside");
        test::writeEvidence(base + "_exact", e.radiance);
        test::writeEvidence(base + "_reference", ref.mean);
        test::writeEvidence(base + "_ppb", acc.mean());
        test::writeEvidence(base + "_ppb_error", test::absDifference(acc.mean(), e.radiance));
    }
}

TEST(AnalyticSphere, SingleScatteringPrimarySegments) {
    // Camera inside the medium, behind and beside a spot aimed along -z, looking across its cone.
    Camera camera = Camera::lookAt({0.55f, 0.1f, 0.25f}, {-0.1f, 0.0f, -0.55f}, {0, 1, 0}, 80.0f * kPi / 180.0f);
    runSingleScatter("primary", centreLight(LightType::Spot), camera, true, {{0.1f, 0.3f}, {0.3f, 2.0f}});
}

TEST(AnalyticSphere, SingleScatteringSecondarySegmentsThroughInterface) {
    // Camera outside: its paths cross the Interface hull, the medium stretch is secondary.
    Camera camera = Camera::lookAt({0.2f, 0.1f, 2.5f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 2.0f * std::atan(1.0f / 2.5f));
    runSingleScatter("secondary", centreLight(LightType::Point), camera, false, {{0.1f, 0.45f}, {0.45f, 0.92f}});
}

TEST(AnalyticSphere, DirectIrradianceThroughAbsorbingMedium) {
    const int size = 24;
    Medium medium;
    medium.name = "ink";
    medium.sigmaS = Rgb(0.0f);
    medium.sigmaA = Rgb(0.5f, 0.3f, 0.1f);
    const Rgb albedo(0.6f, 0.5f, 0.4f);
    Camera camera = Camera::lookAt({0.0f, 0.1f, 0.4f}, {0.3f, 0.0f, -1.0f}, {0, 1, 0}, 80.0f * kPi / 180.0f);
    const Light light = centreLight(LightType::Point);
    Scene scene = test::makeMediumSphereScene(medium, kR, light, camera, true, albedo);
    EmbreeScene rt(scene);
    Expected e = expectedImage(scene, rt, size, [&](const Ray& ray) {
        SurfaceHit hit;
        if (!rt.intersect(ray, &hit)) return Rgb(0.0f);
        // E = I cos / d^2 exp(-sigma_t d) on the facet actually hit (cos ~ 1, d ~ R).
        float d = length(hit.p);
        float cosine = std::abs(dot(hit.ng, hit.p / d));
        Rgb e = light.intensity * medium.transmittance(d) * (cosine / (d * d));
        return albedo * kInvPi * e * medium.transmittance(hit.t);
    });
    std::vector<Bin> all = {{0.0f, 10.0f}};

    ReferenceImage ref = ReferenceTracer(rt, singleScatterReferenceSettings(size, 128)).render();
    checkReference("wall", ref, e, all, 0.004, 0.002);

    std::vector<Image> batches = ppbBatches(scene, singleScatterPpbSettings(size), 8, 2);
    checkPpb("wall", batches, e, all, 0.01, 0.01);
    if (HasFailure()) {
        test::writeEvidence("analytic_wall_exact", e.radiance);
        test::writeEvidence("analytic_wall_reference", ref.mean);
        test::writeEvidence("analytic_wall_ppb", batches[0]);
    }
}

}  // namespace
}  // namespace tyndall
