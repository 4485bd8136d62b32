// Camera rays drawn towards a light's image (--film-light-sampling, core/film_light_sampler.h;
// docs/algorithm.md "Camera rays near a light's image") in the renderer:
// 1. Unbiased: in a fog box with black walls (light paths of at most two segments: single
//    scattering alone, by equiangular sampling), the pixel that holds the lamp's image and its
//    neighbours (the image outside them) against a quadrature of the pixel integral of the
//    closed-form single scattering along each ray.
// 2. Finite variance: that pixel's variance over seeds falls as 1/passes with it (no kernel is
//    left, so passes are independent), and is well below the uniform film position's, whose
//    variance is infinite (the square of the 1/distance glow has a divergent pixel integral).
// 3. PPB with it against the path tracer where the lamp's image holds a large share of the pixels
//    (the fog box with grey walls, the whole light transport, at 8 x 8).
// 4. A thin lens (the image through each pass's lens point, blurred over about 3 pixels): the
//    pixels round the lamp's image with it on against the uniform film position's, and the lamp's
//    pixel's variance below it.
// 5. A pixel at the lamp's image that sees something brighter than the glow, with structure
//    inside the pixel (the flashlight's reflector and cap): a wall behind the lamp, a mirror on
//    part of the pixel (which sends the glow back past the lamp: the light-directed ray's second
//    segment) and an emitter on the rest. Its mean against uniform film positions, and its
//    variance over seeds no more than uniform's: the camera path keeps its uniform position for
//    all but the lamp's single scattering.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/phase.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

constexpr int kSize = 9;
constexpr float kFov = 1.2f, kSigmaS = 0.5f, kSigmaA = 0.1f, kG = 0.4f, kIntensity = 1.0f;
// The lamp's image on the film, in pixels: inside pixel (4, 4), off its centre.
constexpr double kImageX = 4.3, kImageY = 4.6;

/// The fog box of test::makeFogBoxWithLamp (x, y, z in [-1, 1], the camera at (0, 0, 0.95) looking
/// down -z) with walls of albedo `wall` and the lamp on the ray through the film point
/// (kImageX, kImageY), 1.1 from the camera.
Scene fogBoxWithLampAtImage(float wall) {
    const Camera camera = Camera::lookAt({0, 0, 0.95f}, {0, 0, -1}, {0, 1, 0}, kFov);
    const Ray r = camera.generateRay(float(kImageX), float(kImageY), kSize, kSize, {0.5f, 0.5f});
    Scene s = test::makeFogBoxWithLamp(Rgb(kSigmaS), Rgb(kSigmaA), kG, r.o + r.d * 1.1f, kFov);
    s.materials[0].albedo = Rgb(wall);
    s.lights[0].intensity = Rgb(kIntensity);
    return s;
}

/// Single scattering (light paths of two segments: camera, scattering point, lamp) with no
/// kernel: constant radii (no beam is gathered within the cap anyway), 4 equiangular distances per
/// segment (with one, the phase function's spread along a ray made a pass's estimate 4x noisier).
RenderSettings singleScattering(bool film) {
    RenderSettings ps = test::constantRadiusSettings(kSize, 16, 1, true, 0.06f);
    ps.photonAngle = 0;
    ps.equiangular = true;
    ps.equiangularSamples = 4;
    ps.maxPathLength = 2;
    ps.filmLightSampling = film;
    return ps;
}

/// The single-scattered radiance along the camera ray through film point (fx, fy) up to the box's
/// wall, in the angle about the lamp (t = t0 + h tan(theta): dt / dist^2 = dtheta / h), by Simpson's
/// rule.
double rayRadiance(const Scene& s, double fx, double fy) {
    const Ray ray = s.camera.generateRay(float(fx), float(fy), kSize, kSize, {0.5f, 0.5f});
    const Vec3 l = s.lights[0].position;
    // The wall: the box's exit along the ray.
    double tWall = 1e30;
    for (int a = 0; a < 3; ++a) {
        const double o = ray.o[a], d = ray.d[a];
        if (d > 0) tWall = std::min(tWall, (1.0 - o) / d);
        if (d < 0) tWall = std::min(tWall, (-1.0 - o) / d);
    }
    const double t0 = dot(l - ray.o, ray.d), h = length(ray.o + ray.d * float(t0) - l);
    const double a = std::atan2(-t0, h), b = std::atan2(tWall - t0, h);
    const double sigmaT = kSigmaS + kSigmaA;
    auto f = [&](double theta) {
        const double t = t0 + h * std::tan(theta), dist = h / std::cos(theta);
        const Vec3 x = ray.o + ray.d * float(t);
        const Vec3 wl = normalize(x - l);
        return kSigmaS * kIntensity * hgPhase(dot(wl, -ray.d), kG) * std::exp(-sigmaT * (t + dist)) / h;
    };
    const int n = 2000;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + (b - a) * i / n) * (i % 2 ? 4 : 2);
    return sum * (b - a) / n / 3;
}

/// Gauss-Legendre nodes and weights on [0, 1].
void gaussLegendre(int n, std::vector<double>* x, std::vector<double>* w) {
    x->resize(n);
    w->resize(n);
    for (int i = 0; i < n; ++i) {
        double z = std::cos(3.141592653589793 * (i + 0.75) / (n + 0.5)), dp = 0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = 0;
            for (int k = 1; k <= n; ++k) {
                const double p2 = p1;
                p1 = p0;
                p0 = ((2 * k - 1) * z * p1 - (k - 1) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1);
            const double dz = p0 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-15) break;
        }
        (*x)[i] = 0.5 * (1 - z);
        (*w)[i] = 1.0 / ((1 - z * z) * dp * dp) * 2 * 0.5;
    }
}

/// The mean over pixel (px, py) of rayRadiance: where the lamp's image lies inside it, in polar
/// coordinates about the image over the four triangles (image, edge), where r times the 1/r glow
/// is smooth; elsewhere over 4 x 4 squares; Gauss-Legendre in both.
double pixelIntegral(const Scene& s, int px, int py) {
    std::vector<double> x, w;
    gaussLegendre(24, &x, &w);
    const double ix = kImageX - px, iy = kImageY - py;
    double sum = 0;
    if (ix > 0 && ix < 1 && iy > 0 && iy < 1) {
        // Each edge from corner a to corner b; points a + u (b - a), then toward the image.
        const double corners[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
        for (int e = 0; e < 4; ++e) {
            const double ax = corners[e][0], ay = corners[e][1], bx = corners[e + 1][0], by = corners[e + 1][1];
            const double phiA = std::atan2(ay - iy, ax - ix);
            double phiB = std::atan2(by - iy, bx - ix);
            if (phiB < phiA) phiB += 2 * 3.141592653589793;
            // The edge's line: distance d from the image, its unit normal n.
            const double nx = by - ay, ny = ax - bx;  // unit for the unit square's edges
            const double d = std::abs((ax - ix) * nx + (ay - iy) * ny);
            for (size_t i = 0; i < x.size(); ++i) {
                const double phi = phiA + (phiB - phiA) * x[i];
                const double cx = std::cos(phi), cy = std::sin(phi);
                const double R = d / std::abs(cx * nx + cy * ny);
                for (size_t j = 0; j < x.size(); ++j) {
                    const double r = R * x[j];
                    sum += w[i] * w[j] * (phiB - phiA) * R * r *
                           rayRadiance(s, px + ix + r * cx, py + iy + r * cy);
                }
            }
        }
        return sum;
    }
    const int k = 4;
    for (int sy = 0; sy < k; ++sy)
        for (int sx = 0; sx < k; ++sx)
            for (size_t i = 0; i < x.size(); ++i)
                for (size_t j = 0; j < x.size(); ++j)
                    sum += w[i] * w[j] * rayRadiance(s, px + (sx + x[i]) / k, py + (sy + x[j]) / k) / (k * k);
    return sum;
}

struct PixelRuns {
    std::vector<std::vector<double>> means;  // per pixel asked for, one per seed
};

/// The green channel of `pixels` after `passes` passes, for `seeds` seeds from `firstSeed`.
PixelRuns renderSeeds(const Scene& scene, RenderSettings ps, const std::vector<std::pair<int, int>>& pixels,
                      int seeds, uint64_t firstSeed, uint64_t passes) {
    PixelRuns out;
    out.means.resize(pixels.size());
    for (int k = 0; k < seeds; ++k) {
        ps.seed = firstSeed + uint64_t(k);
        PassRenderer renderer(scene, ps);
        const Image img = test::renderPpbPasses(renderer, 0, passes);
        for (size_t i = 0; i < pixels.size(); ++i) out.means[i].push_back(img.at(pixels[i].first, pixels[i].second).g);
    }
    return out;
}

TEST(FilmLight, LampPixelAndItsNeighboursAgainstQuadrature) {
    const Scene scene = fogBoxWithLampAtImage(0.0f);
    const std::vector<std::pair<int, int>> pixels = {{4, 4}, {5, 4}, {4, 5}, {3, 3}};
    const PixelRuns runs = renderSeeds(scene, singleScattering(true), pixels, 16, 1, 256);
    for (size_t i = 0; i < pixels.size(); ++i) {
        const double expected = pixelIntegral(scene, pixels[i].first, pixels[i].second);
        const test::MeanVar mv = test::meanVar(runs.means[i]);
        const double se = std::sqrt(mv.var / double(runs.means[i].size()));
        std::printf("pixel (%d, %d): %.5f +- %.5f, quadrature %.5f (ratio %.4f)\n", pixels[i].first, pixels[i].second,
                    mv.mean, se, expected, mv.mean / expected);
        EXPECT_LT(se, 0.01 * expected) << "too noisy to test";
        EXPECT_NEAR(mv.mean, expected, 4 * se) << pixels[i].first << ", " << pixels[i].second;
    }
}

TEST(FilmLight, LampPixelVarianceFallsAsOneOverPasses) {
    const Scene scene = fogBoxWithLampAtImage(0.0f);
    const std::vector<std::pair<int, int>> pixel = {{4, 4}};
    const int seeds = 64;
    double variance[2][2];  // [film light off, on][8, 32 passes]
    for (int film = 0; film < 2; ++film)
        for (int c = 0; c < 2; ++c) {
            const PixelRuns runs = renderSeeds(scene, singleScattering(film == 1), pixel, seeds, 500, c ? 32 : 8);
            const test::MeanVar mv = test::meanVar(runs.means[0]);
            variance[film][c] = mv.var / (mv.mean * mv.mean);
        }
    const double slopeOn = std::log(variance[1][1] / variance[1][0]) / std::log(4.0);
    const double slopeOff = std::log(variance[0][1] / variance[0][0]) / std::log(4.0);
    std::printf("relative variance of the lamp's pixel, 8 and 32 passes: on %.3e, %.3e (slope %.3f); off %.3e, %.3e "
                "(slope %.3f)\n",
                variance[1][0], variance[1][1], slopeOn, variance[0][0], variance[0][1], slopeOff);
    // 64 seeds estimate a variance within ~18%, the slope over a factor of 4 within ~0.2.
    EXPECT_NEAR(slopeOn, -1.0, 0.3);
    // Measured 0.072 of the uniform position's (whose own estimate is heavy-tailed).
    EXPECT_LT(variance[1][1], 0.25 * variance[0][1]);
}

TEST(FilmLight, ThinLensAgreesWithUniformFilmPositions) {
    Scene scene = fogBoxWithLampAtImage(0.0f);
    scene.camera.lensRadius = 0.2f;  // the lamp 1.1 away, in focus at 0.5: a blur of ~1.4 pixels' radius
    scene.camera.focusDistance = 0.5f;
    std::vector<std::pair<int, int>> pixels;
    for (int y = 3; y <= 5; ++y)
        for (int x = 3; x <= 5; ++x) pixels.emplace_back(x, y);
    const PixelRuns on = renderSeeds(scene, singleScattering(true), pixels, 48, 1, 64);
    const PixelRuns off = renderSeeds(scene, singleScattering(false), pixels, 48, 1, 64);
    for (size_t i = 0; i < pixels.size(); ++i) {
        const test::MeanVar a = test::meanVar(on.means[i]), b = test::meanVar(off.means[i]);
        const double se = std::sqrt((a.var + b.var) / double(on.means[i].size()));
        std::printf("pixel (%d, %d): on %.5f +- %.5f, off %.5f +- %.5f\n", pixels[i].first, pixels[i].second, a.mean,
                    std::sqrt(a.var / on.means[i].size()), b.mean, std::sqrt(b.var / off.means[i].size()));
        // The lens sample's own spread (the image moves over ~3 pixels) is most of both; the
        // uniform position's is heavy-tailed besides (its standard error measured 1.5-13% here,
        // against 1.3-2.2% with the mixture).
        EXPECT_LT(std::sqrt(a.var / double(on.means[i].size())), 0.03 * a.mean) << "too noisy to test";
        EXPECT_NEAR(a.mean, b.mean, 4 * se) << pixels[i].first << ", " << pixels[i].second;
        if (pixels[i] == std::pair{4, 4}) {
            EXPECT_LT(a.var, 0.5 * b.var) << "the lamp's pixel";
        }
    }
}

/// fogBoxWithLampAtImage(0.5) with the back wall behind the lamp's pixel split at the film's
/// x = kImageX + 0.5: a mirror to the left of it (the image's side) and an emitter of radiance
/// `emission` to the right.
Scene fogBoxWithMirrorAndEmitter(float emission) {
    const Camera camera = Camera::lookAt({0, 0, 0.95f}, {0, 0, -1}, {0, 1, 0}, kFov);
    const Ray r = camera.generateRay(float(kImageX), float(kImageY), kSize, kSize, {0.5f, 0.5f});
    const Ray edge = camera.generateRay(float(kImageX + 0.5), float(kImageY), kSize, kSize, {0.5f, 0.5f});
    constexpr float kWall = -0.99f;
    const float xEdge = edge.o.x + edge.d.x * (kWall - edge.o.z) / edge.d.z;
    Scene s;
    s.name = "fog-box-lamp-mirror";
    s.source = "<test scene>";
    const int white = test::addMaterial(s, "white", MaterialType::Diffuse, Rgb(0.5f));
    const int mirror = test::addMaterial(s, "mirror", MaterialType::Mirror, Rgb(0.9f));
    const int lamp = test::addMaterial(s, "lamp", MaterialType::Diffuse, Rgb(0.0f), Rgb(emission));
    s.meshes.push_back(makeBox("room", {-1, -1, -1}, {1, 1, 1}, white, true));
    s.meshes.push_back(makeQuad("mirror", {-0.9f, -0.9f, kWall}, {xEdge + 0.9f, 0, 0}, {0, 1.8f, 0}, mirror));
    s.meshes.push_back(makeQuad("emitter", {xEdge, -0.9f, kWall}, {0.9f - xEdge, 0, 0}, {0, 1.8f, 0}, lamp));
    s.media.push_back(test::homogeneousMedium(Rgb(kSigmaS), Rgb(kSigmaA), kG));
    s.globalMedium = 0;
    s.lights.push_back(test::pointLight(r.o + r.d * 1.1f, kIntensity));
    s.camera = camera;
    s.finalize();
    s.validate();
    return s;
}

TEST(FilmLight, BrightSurfaceInTheLampsPixelKeepsItsUniformVariance) {
    const Scene scene = fogBoxWithMirrorAndEmitter(2.0f);
    RenderSettings ps = singleScattering(true);
    ps.maxPathLength = 0;  // the whole transport: the emitter, the mirror, beams
    const std::vector<std::pair<int, int>> pixel = {{4, 4}};
    const int seeds = 64;
    const PixelRuns on = renderSeeds(scene, ps, pixel, seeds, 700, 16);
    ps.filmLightSampling = false;
    const PixelRuns off = renderSeeds(scene, ps, pixel, seeds, 700, 16);
    const test::MeanVar a = test::meanVar(on.means[0]), b = test::meanVar(off.means[0]);
    const double se = std::sqrt((a.var + b.var) / double(seeds));
    std::printf("pixel (4, 4) over %d seeds: on %.5f (sd %.5f), off %.5f (sd %.5f), variance ratio %.3f\n", seeds,
                a.mean, std::sqrt(a.var), b.mean, std::sqrt(b.var), a.var / b.var);
    EXPECT_NEAR(a.mean, b.mean, 4 * se);
    // The same seeds draw the same camera paths (the uniform one's streams do not move): what
    // differs is the lamp's single scattering alone, whose variance is below uniform's.
    EXPECT_LT(a.var, 1.1 * b.var);
}

TEST(FilmLightPpb, LampInViewAgreesWithThePathTracer) {
    // The whole light transport (grey walls, beams, surface photons, shadow rays) at 8 x 8, where
    // the lamp's image and its neighbours are a quarter of their quadrant.
    Scene scene = fogBoxWithLampAtImage(0.5f);
    RenderSettings ps = test::constantRadiusSettings(8, 2000, 5, true, 0.06f);
    ps.radius = 0.03f;
    ps.photonAngle = 0;
    ps.equiangular = true;
    ps.filmLightSampling = true;
    test::expectBatchesAgreeWithThePathTracer(scene, ps, 0.03, 0.02);
}

}  // namespace
}  // namespace tyndall
