// Photon planes (core/photon_plane.h, cpu/plane_bvh.h; docs/algorithm.md "Photon planes").
//
// 1. The estimator against quadrature: the light that a beam in open homogeneous fog scatters
//    twice (anywhere on the beam, then on a camera segment) toward the camera, as a double integral
//    over both scattering points computed in the test; the mean of many planes within 4 standard
//    errors (isotropic, forward and backward HG).
// 2. PPB with planes on, against the in-tree path tracer: the fog box parted by a black panel with
//    the lamp behind it (the light's first beams splatted, planes for the rest, the panel between
//    many planes' scattering points), and the consistency room (fog, a spot
//    and an area light, a mirror and a glass sphere: planes along primary and secondary segments,
//    walls between a plane's two scattering points) with equiangular sampling.
// 3. The variance law: with the path length capped at 3 in a black-walled fog box, equiangular
//    sampling carries the single scattering and planes the double (no beam, no kernel left): a
//    pixel's variance over seeds falls as 1/passes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/photon_plane.h"
#include "core/rng.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

// ---- 1. The estimator against quadrature ----

/// Open fog with coloured extinction (so the length's channel weight is exercised).
Medium planeTestFog(float g) {
    Medium m;
    m.name = "fog";
    m.sigmaS = Rgb(0.5f, 0.4f, 0.3f);
    m.sigmaA = Rgb(0.1f, 0.15f, 0.3f);
    m.g = g;
    return m;
}

/// The beam x0 + a w1, a in [0, A], of power 1, scattered at x1 = x0 + a w1 toward x(s) = xc + s wc
/// and there toward the camera, by Gauss-Legendre quadrature over a and s (the integrand is smooth:
/// the camera segment stays 0.6 from the beam):
///   int ds int da sigma_s^2 Tr(a) p(w1 . w) Tr(|x - x1|) / |x - x1|^2 p(w . -wc) Tr(s)
double doubleScatteringQuadrature(const Medium& m, int channel, Vec3 x0, Vec3 w1, float A, Vec3 xc, Vec3 wc,
                                  float S) {
    // 16-point Gauss-Legendre on each of 32 sub-intervals per axis.
    static const double kNodes[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274, 0.6178762444026438,
                                     0.7554044083550030, 0.8656312023878318, 0.9445750230732326, 0.9894009349916499};
    static const double kWeights[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                       0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                       0.0622535239386479, 0.0271524594117541};
    auto rule = [&](double lo, double hi, auto f) {
        const int pieces = 32;
        double sum = 0;
        for (int p = 0; p < pieces; ++p) {
            const double a = lo + (hi - lo) * p / pieces, b = lo + (hi - lo) * (p + 1) / pieces;
            const double c = 0.5 * (a + b), h = 0.5 * (b - a);
            for (int k = 0; k < 8; ++k) sum += h * kWeights[k] * (f(c - h * kNodes[k]) + f(c + h * kNodes[k]));
        }
        return sum;
    };
    const double ss = m.sigmaS[channel], st = m.sigmaT()[channel];
    return rule(0.0, S, [&](double s) {
        const Vec3 x = xc + wc * float(s);
        return rule(0.0, A, [&](double a) {
            const Vec3 x1 = x0 + w1 * float(a);
            const Vec3 v = x - x1;
            const double d2 = double(dot(v, v)), d = std::sqrt(d2);
            const Vec3 w = v / float(d);
            return ss * ss * std::exp(-st * (a + d + s)) * hgPhase(dot(w1, w), m.g) * hgPhase(dot(w, -wc), m.g) / d2;
        });
    });
}

TEST(PhotonPlane, EstimatorAgainstQuadratureOfDoubleScattering) {
    const Vec3 x0(0, 0, 0), w1(1, 0, 0);
    const float A = 2.0f;
    const Vec3 xc(0.9f, 1.0f, -1.5f), wc = normalize(Vec3(0.1f, -0.25f, 1.0f));
    const float S = 3.0f;
    for (float g : {0.0f, 0.6f, -0.6f}) {
        const Medium m = planeTestFog(g);
        const int n = 400000;
        double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i) {
            Rng rng = Rng::forKey(7, 0, uint64_t(i), StreamPurpose::Test);
            PhotonPlane p;
            p.origin = x0;
            p.dir1 = w1;
            p.len1 = A;
            p.dir2 = sampleHg(w1, g, rng.uniform(), rng.uniform());
            p.len2 = samplePlaneLength(m, 100.0f, rng.uniform());
            p.power = Rgb(1.0f);
            PlaneRayHit hit;
            if (!intersectPlaneRay(xc, wc, S, p, &hit)) continue;
            const Rgb v = planeRadiance(hit, p, m);
            for (int c = 0; c < 3; ++c) sum[c] += v[c], sum2[c] += double(v[c]) * v[c];
        }
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / n, se = std::sqrt(std::max(0.0, sum2[c] / n - mean * mean) / (n - 1));
            const double exact = doubleScatteringQuadrature(m, c, x0, w1, A, xc, wc, S);
            std::printf("g %+.1f channel %d: planes %.6f +- %.6f, quadrature %.6f\n", g, c, mean, se, exact);
            EXPECT_LT(se, 0.015 * exact) << "too noisy to test";
            EXPECT_NEAR(mean, exact, 4 * se) << "g " << g << " channel " << c;
        }
    }
}

// ---- 2. PPB with planes against the path tracer ----

void expectPlanesAgreeWithThePathTracer(const Scene& scene, bool equiangular, uint32_t photons, double noise,
                                        double bias) {
    const int size = 16;
    RenderSettings ps = test::constantRadiusSettings(size, photons, 5, true, 0.06f);
    ps.radius = 0.03f;
    ps.photonAngle = 0;
    ps.photonPlanes = true;
    ps.equiangular = equiangular;
    // The whole image and its four quadrants, within 4 standard errors plus `bias` for the kernel
    // bias of the remaining beams and surface photons.
    test::expectBatchesAgreeWithThePathTracer(scene, ps, noise, bias);
}

TEST(PhotonPlanePpb, FogBoxWithAPartitionAgreesWithThePathTracer) {
    // A black panel across the fog box (z = 0, all but the top 0.8), the lamp behind it: the fog
    // in front is lit through the gap above the panel and by the walls, so a plane whose two
    // scattering points lie on either side of the panel must count nothing (its shadow ray).
    // Equiangular sampling off: the lamp's first beams are splatted, planes carry the rest.
    Scene scene = test::makeFogBoxWithLamp(Rgb(0.5f), Rgb(0.1f), 0.4f, Vec3(0.0f, -0.3f, -0.6f), 1.2f);
    const int black = test::addMaterial(scene, "black", MaterialType::Diffuse, Rgb(0.0f));
    scene.meshes.push_back(makeQuad("panel", {-1, -1, 0}, {2, 0, 0}, {0, 1.2f, 0}, black));
    scene.finalize();
    scene.validate();
    // The lower quadrants see the black panel through little fog (their standard error ~10%); with
    // the planes' shadow ray left out they read 5x the path tracer, the whole image 1.6x.
    expectPlanesAgreeWithThePathTracer(scene, false, 1500, 0.12, 0.02);
}

TEST(PhotonPlanePpb, ConsistencyRoomWithEquiangularAgreesWithThePathTracer) {
    // The quadrant with the glass sphere is heavy-tailed (paths split by Fresnel through it). 1% for
    // the kernels' bias: the planes are a small part of this room's light (the beams after a
    // scattering stored as well as the planes read +8.7% on the whole image).
    expectPlanesAgreeWithThePathTracer(test::makeConsistencyScene(), true, 300, 0.06, 0.01);
}

// ---- 3. The variance law ----

TEST(PhotonPlanePpb, DoubleScatteringVarianceFallsAsOneOverPasses) {
    // Black walls, light paths of at most three segments: single scattering by equiangular
    // sampling (the lamp's first beams are left out), double scattering by planes (the beams after
    // a scattering are the planes'; a wall reflects nothing). No kernel remains, so each pass is an
    // independent unbiased estimate and the variance of a pixel's mean over n passes, measured
    // over seeds, must fall as 1/n. The lamp is out of view.
    Scene scene = test::makeFogBoxWithLamp(Rgb(0.5f), Rgb(0.1f), 0.4f, Vec3(0.5f, 0.5f, 0.8f), 1.2f);
    scene.materials[0].albedo = Rgb(0.0f);
    const int size = 8, seeds = 48;
    RenderSettings ps = test::constantRadiusSettings(size, 8, 0, true, 0.06f);
    ps.maxPathLength = 3;
    ps.equiangular = true;
    ps.photonPlanes = true;
    ps.photonAngle = 0;
    // Each variance from 48 seeds is within ~20% (one standard deviation), so the slope over a
    // factor of 4 within ~0.2.
    EXPECT_NEAR(test::varianceSlopeOverPasses(scene, ps, seeds, 300), -1.0, 0.3);
}

}  // namespace
}  // namespace tyndall
