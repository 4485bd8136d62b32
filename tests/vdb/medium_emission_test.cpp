// Emissive media (core/medium.h: source sigma_a Le), against closed forms:
//   - the blackbody colour (core/blackbody.h): chromaticity on the Planckian locus at 1500, 3000,
//     6500 and 10000 K (published CIE 1931 2-degree xy), its RGB back to xy inside the gamut,
//     the table against the exact integral;
//   - ratio tracking's emission estimate (cpu/free_flight.h, the reference path tracer's) on
//     analytic densities along a ray, averaged, against quadrature of integral Tr sigma_a Le ds
//     with the exact transmittance; homogeneous estimates exact;
//   - the camera segments' estimator (cpu/segment_emission.h) against the closed form on a
//     constant density and quadrature on a ramp and a slab, with and without an importance grid
//     and with one that misses half the emission; its variance far below ratio tracking's;
//   - whole renders of emission-only media: L = Le (1 - exp(-sigma_a d)) along each camera ray
//     through a slab (homogeneous and as an OpenVDB grid; PPB and the reference path tracer) and
//     through a sphere (chord from the mesh itself).
#include <gtest/gtest.h>

#include <cmath>

#include "core/accumulator.h"
#include "core/blackbody.h"
#include "core/pixel_jitter.h"
#include "cpu/embree_scene.h"
#include "cpu/free_flight.h"
#include "cpu/medium_emitters.h"
#include "cpu/pass_renderer.h"
#include "cpu/reference_tracer.h"
#include "cpu/segment_emission.h"
#include "loading/mesh_builders.h"
#include "tests/test_scenes.h"
#include "tests/vdb/analytic_density.h"

namespace tyndall {
namespace {

// ---- Blackbody

Vec3 xyOf(const Vec3& xyz) {
    const float s = xyz.x + xyz.y + xyz.z;
    return {xyz.x / s, xyz.y / s, 0.0f};
}
/// Linear Rec.709 (D65) to XYZ (IEC 61966-2-1), to read the RGB's chromaticity.
Vec3 rec709ToXyz(const Rgb& c) {
    return {0.4124564f * c.r + 0.3575761f * c.g + 0.1804375f * c.b,
            0.2126729f * c.r + 0.7151522f * c.g + 0.0721750f * c.b,
            0.0193339f * c.r + 0.1191920f * c.g + 0.9503041f * c.b};
}

TEST(Blackbody, ChromaticityLiesOnThePlanckianLocus) {
    // Planckian locus, CIE 1931 2-degree observer: 1500, 3000, 6500 and 10000 K from Charity's
    // blackbody colour table (which agrees with Wyszecki & Stiles' tables to the 4th decimal);
    // 2856 K is CIE standard illuminant A, defined as a Planckian radiator at that temperature
    // (c2 = 1.4388e-2 m K), whose xy CIE 15:2004 gives as (0.44757, 0.40745).
    struct Point {
        float kelvin, x, y;
    };
    const Point locus[] = {{1500, 0.5857f, 0.3931f},    {2856, 0.44757f, 0.40745f}, {3000, 0.4369f, 0.4041f},
                           {6500, 0.3135f, 0.3236f},    {10000, 0.2807f, 0.2884f}};
    for (const Point& p : locus) {
        const Vec3 xy = xyOf(blackbodyXyz(p.kelvin));
        EXPECT_NEAR(xy.x, p.x, 0.002f) << p.kelvin << " K";
        EXPECT_NEAR(xy.y, p.y, 0.002f) << p.kelvin << " K";
        const Rgb c = blackbodyRgb(p.kelvin);
        EXPECT_GE(c.r, 0.0f);
        EXPECT_GE(c.g, 0.0f);
        EXPECT_GE(c.b, 0.0f);
        if (p.kelvin >= 2800) {  // inside the Rec.709 gamut: the RGB keeps the chromaticity
            const Vec3 back = xyOf(rec709ToXyz(c));
            EXPECT_NEAR(back.x, p.x, 0.002f) << p.kelvin << " K (from RGB)";
            EXPECT_NEAR(back.y, p.y, 0.002f) << p.kelvin << " K (from RGB)";
        }
    }
    // Normalisation: a spectrum of peak 1 against Y of a flat spectrum of 1; at 6500 K the peak
    // (446 nm) is near the visible band's middle, so Y is near 1; at 1500 K far below.
    EXPECT_NEAR(blackbodyXyz(6500).y, 0.886f, 0.005f);
    EXPECT_NEAR(blackbodyXyz(1500).y, 0.0034f, 0.0002f);
}

TEST(Blackbody, TableFollowsTheExactIntegralAndRejectsNonsense) {
    for (float t = 1000; t < 20000; t *= 1.07f) {
        const Rgb a = blackbodyRgb(t), e = blackbodyRgbExact(t);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], e[c], 1e-3f * e.maxComponent() + 1e-9f) << t << " K";
    }
    for (float t : {0.0f, -300.0f, std::nanf(""), -kInfinity}) {
        EXPECT_TRUE(blackbodyRgb(t).isBlack()) << t;
        EXPECT_TRUE(blackbodyRgbExact(t).isBlack()) << t;
    }
    EXPECT_TRUE(isFinite(blackbodyRgb(1e7f)));
}

// ---- Estimators along one ray

/// Le(p) = (1 + x, 0.5, 2 - x): linear along the test ray, so a lookup at the wrong point shows.
class LinearEmission : public EmissionField {
public:
    Rgb radiance(const Vec3& p) const override { return {1.0f + p.x, 0.5f, 2.0f - p.x}; }
};

/// Integral over [a, b] of f by composite Simpson with `steps` (even) intervals.
template <class F>
Rgb simpson(F f, double a, double b, int steps) {
    const double h = (b - a) / steps;
    Rgb sum(0.0f);
    for (int i = 0; i <= steps; ++i) {
        const float w = (i == 0 || i == steps) ? 1.0f : (i % 2 ? 4.0f : 2.0f);
        sum += f(a + i * h) * w;
    }
    return sum * float(h / 3.0);
}

TEST(MediumEmission, RatioTrackingEmissionAveragesToTheEmissionIntegral) {
    const Ray ray{Vec3(-0.2f, 0.5f, 0.5f), Vec3(1, 0, 0)};
    const float tEnd = 1.4f;
    for (auto kind : {test::AnalyticDensity::Kind::Ramp, test::AnalyticDensity::Kind::Slab}) {
        auto field = std::make_shared<test::AnalyticDensity>(kind, 8);
        Medium m;
        m.sigmaS = Rgb(1.5f);
        m.sigmaA = Rgb(0.5f);
        m.density = field;
        m.emissionField = std::make_shared<LinearEmission>();
        ASSERT_TRUE(m.emissive());
        // Exact: Tr(s) = exp(-sigma_t tau(s)); integrate piecewise between the profile's kinks.
        auto integrand = [&](double s) {
            const double x = -0.2 + s;
            const double tr = std::exp(-2.0 * field->integral(0.0, x));
            const Vec3 p = ray.at(float(s));
            return m.emissionAt(p) * m.sigmaA * float(tr * field->profile(float(x)));
        };
        Rgb exact(0.0f);
        const double cuts[] = {0.0, 0.2, 0.5, 0.8, 1.2, 1.4};
        for (int i = 0; i + 1 < 6; ++i) exact += simpson(integrand, cuts[i], cuts[i + 1], 2000);

        const int runs = 40000;
        Rng rng(24, uint64_t(kind));
        double sum[3] = {}, sum2[3] = {};
        for (int r = 0; r < runs; ++r) {
            const Rgb ratio = estimateEmission(m, ray, tEnd, rng);
            for (int c = 0; c < 3; ++c) sum[c] += ratio[c], sum2[c] += double(ratio[c]) * ratio[c];
        }
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / runs;
            const double se = std::sqrt(std::max(0.0, sum2[c] / runs - mean * mean) / runs);
            EXPECT_NEAR(mean, exact[c], 4.5 * se + 1e-4 * exact[c])
                << test::kindName(kind) << " channel " << c << " (standard error " << se << ")";
        }
    }
}

TEST(MediumEmission, HomogeneousEstimatesAreExact) {
    Medium m;
    m.sigmaS = Rgb(0.5f, 1.0f, 0.0f);
    m.sigmaA = Rgb(0.25f, 0.0f, 2.0f);
    m.emission = Rgb(2.0f, 3.0f, 0.5f);
    const float d = 0.8f;
    Rng rng(1, 2);
    const Rgb e = estimateSegmentEmission(m, EmissionImportance(m), Ray{Vec3(0.0f), Vec3(0, 0, 1)}, d, rng, 8);
    const Rgb st = m.sigmaT();
    for (int c = 0; c < 3; ++c) {
        const float expected = m.sigmaA[c] * m.emission[c] * (1 - std::exp(-st[c] * d)) / st[c];
        EXPECT_NEAR(e[c], expected, 1e-6f * (1 + expected)) << c;
        EXPECT_NEAR(estimateEmission(m, Ray{Vec3(0.0f), Vec3(0, 0, 1)}, d, rng)[c], expected, 1e-6f * (1 + expected));
    }
    EXPECT_EQ(e.g, 0.0f);  // no absorption in green: no emission
    // A medium without absorption does not emit; sigma_t = 0 in a channel falls back to sigma_a Le d.
    Medium clear;
    clear.sigmaS = Rgb(0.0f);
    clear.sigmaA = Rgb(0.0f);
    clear.emission = Rgb(1.0f);
    EXPECT_FALSE(clear.emissive());
    EXPECT_TRUE(homogeneousEmission(clear, 1.0f).isBlack());
}

/// Le(p) = LinearEmission's for x < 0.5, 0 beyond: an importance grid built from it misses the
/// emission of half the test ray.
class HalfLinearEmission : public EmissionField {
public:
    Rgb radiance(const Vec3& p) const override { return p.x < 0.5f ? Rgb(1.0f + p.x, 0.5f, 2.0f - p.x) : Rgb(0.0f); }
};

TEST(MediumEmission, SegmentEstimatorAveragesToTheClosedFormAndQuadrature) {
    const Ray ray{Vec3(-0.2f, 0.5f, 0.5f), Vec3(1, 0, 0)};
    const float tEnd = 1.4f;
    using Kind = test::AnalyticDensity::Kind;
    // importance: 0 none, 1 from the medium itself, 2 from a field that misses half the emission.
    for (Kind kind : {Kind::Constant, Kind::Ramp, Kind::Slab})
        for (int cells : {8, 0})
            for (int importance = 0; importance < 3; ++importance) {
                if (cells == 0 && importance > 0) continue;  // no majorant grid: no importance grid
                auto field = std::make_shared<test::AnalyticDensity>(kind, cells);
                Medium m;
                m.sigmaS = Rgb(1.5f);
                m.sigmaA = Rgb(0.5f);
                m.density = field;
                const bool constant = kind == Kind::Constant;
                if (constant) {
                    m.emission = Rgb(2.0f, 1.0f, 0.5f);
                } else {
                    m.emissionField = std::make_shared<LinearEmission>();
                }
                Medium decoy = m;
                decoy.emissionField = std::make_shared<HalfLinearEmission>();
                const EmissionImportance grid = importance == 0   ? EmissionImportance()
                                                : importance == 1 ? EmissionImportance(m)
                                                                  : EmissionImportance(decoy);
                ASSERT_EQ(grid.none(), importance == 0);
                Rgb exact(0.0f);
                if (constant) {
                    // Density 1 over x in [0, 1]: L = Le sigma_a / sigma_t (1 - exp(-sigma_t)).
                    exact = m.emission * m.sigmaA * float(-std::expm1(-2.0) / 2.0);
                } else {
                    auto integrand = [&](double s) {
                        const double x = -0.2 + s;
                        const double tr = std::exp(-2.0 * field->integral(0.0, x));
                        return m.emissionAt(ray.at(float(s))) * m.sigmaA * float(tr * field->profile(float(x)));
                    };
                    const double cuts[] = {0.0, 0.2, 0.5, 0.8, 1.2, 1.4};
                    for (int i = 0; i + 1 < 6; ++i) exact += simpson(integrand, cuts[i], cuts[i + 1], 2000);
                }
                const int runs = 8000;
                Rng rng(31, uint64_t(kind) * 8 + uint64_t(cells + importance));
                double sum[2][3] = {}, sum2[2][3] = {};
                for (int r = 0; r < runs; ++r) {
                    const Rgb e[2] = {estimateSegmentEmission(m, grid, ray, tEnd, rng, 8),
                                      estimateEmission(m, ray, tEnd, rng)};
                    for (int est = 0; est < 2; ++est)
                        for (int c = 0; c < 3; ++c) sum[est][c] += e[est][c], sum2[est][c] += double(e[est][c]) * e[est][c];
                }
                for (int c = 0; c < 3; ++c) {
                    double mean[2], sd[2];
                    for (int est = 0; est < 2; ++est) {
                        mean[est] = sum[est][c] / runs;
                        sd[est] = std::sqrt(std::max(0.0, sum2[est][c] / runs - mean[est] * mean[est]));
                    }
                    const double se = sd[0] / std::sqrt(double(runs));
                    const std::string what = std::string(test::kindName(kind)) + ", " + std::to_string(cells) +
                                             " majorant cells, importance " + std::to_string(importance) + ", channel " +
                                             std::to_string(c);
                    EXPECT_NEAR(mean[0], exact[c], 4.5 * se + 1e-4 * exact[c]) << what << " (standard error " << se << ")";
                    // Stratified distances and a residual tracker: below ratio tracking's spread
                    // (measured: 0.4-0.7 of it on these smooth profiles; the fire's is in
                    // docs/performance.md). A wrong importance costs variance, never bias.
                    if (importance < 2) {
                        EXPECT_LT(sd[0], 0.75 * sd[1]) << what << ": " << sd[0] << " vs ratio tracking's " << sd[1];
                    }
                }
            }
}

// ---- Renders

constexpr float kSigmaA = 2.0f;
const Rgb kLe(1.0f, 0.5f, 0.25f);

/// An emission-only medium (sigma_s = 0) inside an invisible box or sphere, nothing else in the
/// scene, no lights; the camera on +z looks at it from vacuum. `room`: instead the medium fills
/// a closed room of black walls (the global medium) with the camera inside it.
Scene emissionOnlyScene(bool sphere, bool grid, bool room = false) {
    Scene s;
    s.name = sphere ? "emitting-sphere" : "emitting-slab";
    s.source = "<test>";
    Material hull;
    hull.name = "hull";
    hull.type = MaterialType::Interface;
    s.materials = {hull};
    Medium m;
    m.name = "glow";
    m.sigmaS = Rgb(0.0f);
    m.sigmaA = Rgb(kSigmaA);
    m.emission = kLe;
    if (grid) {
        // Density 1 on voxels of 0.1 over [-1.3, 1.3]^3: exactly 1 inside the hull.
        const int n = 27;
        const int dims[3] = {n, n, n};
        std::vector<float> ones(size_t(n) * n * n, 1.0f);
        m.density = VdbDensityGrid::fromDense(dims, ones, Affine3::scaleTranslate(Vec3(0.1f), Vec3(-1.3f)), "ones");
    }
    s.media = {m};
    if (room) {
        Material black;
        black.name = "black";
        black.albedo = Rgb(0.0f);
        s.materials = {black};
        s.globalMedium = 0;
        s.meshes.push_back(makeBox("room", Vec3(-1.2f), Vec3(1.2f), 0, /*inward=*/true));
        s.camera = Camera::lookAt({0.3f, -0.2f, 1.0f}, {0, 0, -1.2f}, {0, 1, 0}, 0.9f);
        s.finalize();
        s.validate();
        return s;
    }
    TriangleMesh mesh = sphere ? makeSphere("hull", Vec3(0.0f), 1.0f, 5, 0)
                               : makeBox("hull", Vec3(-1.0f, -1.0f, -0.25f), Vec3(1.0f, 1.0f, 0.25f), 0);
    mesh.interiorMedium = 0;
    mesh.exteriorMedium = kVacuum;
    s.meshes.push_back(mesh);
    s.camera = Camera::lookAt({0.1f, -0.05f, 3.0f}, {0, 0, 0}, {0, 1, 0}, 0.75f);
    s.finalize();
    s.validate();
    return s;
}

/// Distance the ray through film point (fx, fy) travels inside the hull (0 when it misses), from
/// the mesh itself; for the room, the distance to its wall.
float chordThrough(const Scene& s, const EmbreeScene& rt, float fx, float fy, int size) {
    Ray ray = s.camera.generateRay(fx, fy, size, size, {0.5f, 0.5f});
    SurfaceHit in, out;
    if (!rt.intersect(ray, &in)) return 0;
    if (s.globalMedium == 0) return in.t;
    Ray inside{rt.offsetOrigin(in.p, in.t, in.ng, ray.d), ray.d};
    if (!rt.intersect(inside, &out)) return 0;
    return length(out.p - in.p);
}

constexpr int kSize = 24;

/// Pixels whose centre ray crosses the hull well inside its outline: their chord.
std::vector<std::pair<int, float>> innerPixels(const Scene& s, bool sphere) {
    EmbreeScene rt(s);
    std::vector<std::pair<int, float>> out;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            // Every ray through the pixel (its corners) leaves the slab through its back face
            // (chord 0.5 / cos) or crosses the sphere well inside its silhouette (chord > 1).
            bool inner = true;
            for (int corner = 0; corner < 4; ++corner) {
                const float d = chordThrough(s, rt, float(px + corner % 2), float(py + corner / 2), kSize);
                inner = inner && (sphere ? d > 1.0f : (d > 0.499f && d < 0.56f));
            }
            if (inner) out.push_back({py * kSize + px, chordThrough(s, rt, px + 0.5f, py + 0.5f, kSize)});
        }
    return out;
}

Rgb expectedRadiance(float chord) {
    return kLe * (1.0f - std::exp(-kSigmaA * chord));
}

RenderSettings smallSettings() {
    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = 200;
    ps.seed = 9;
    ps.gpu = GpuMode::Off;
    return ps;
}

TEST(MediumEmission, HomogeneousSlabSphereAndRoomGiveLeOneMinusExp) {
    for (int kind = 0; kind < 3; ++kind) {
        const bool sphere = kind == 1, room = kind == 2;
        Scene s = emissionOnlyScene(sphere, false, room);
        const auto pixels = innerPixels(s, sphere || room);
        ASSERT_GE(pixels.size(), 100u);
        const RenderSettings ps = smallSettings();
        PassRenderer renderer(s, ps);
        EmbreeScene rt(s);
        for (uint64_t pass = 0; pass < 4; ++pass) {
            const Image img = renderer.renderPass(pass);
            for (const auto& [pixel, centreChord] : pixels) {
                // Homogeneous emission is exact per ray: the closed form along this pass's ray
                // through the pixel (its film jitter).
                const Vec2 j = pixelJitter(ps.seed, pass, uint64_t(pixel));
                const float chord =
                    chordThrough(s, rt, float(pixel % kSize) + j.x, float(pixel / kSize) + j.y, kSize);
                const Rgb expected = expectedRadiance(chord);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(img.pixels[size_t(pixel)][c], expected[c], 1e-4f * expected[c])
                        << (room ? "room" : sphere ? "sphere" : "slab") << " pixel " << pixel << " channel " << c;
            }
        }
    }
}

/// Mean over `pixels` of an image's red channel, and of the closed form.
std::pair<double, double> meanAndExpected(const Image& img, const std::vector<std::pair<int, float>>& pixels) {
    double m = 0, e = 0;
    for (const auto& [pixel, chord] : pixels) {
        m += img.pixels[size_t(pixel)].r;
        e += expectedRadiance(chord).r;
    }
    return {m / pixels.size(), e / pixels.size()};
}

TEST(MediumEmission, GridSlabAndRoomGiveLeOneMinusExpInPpbAndTheReference) {
    for (bool room : {false, true}) {
        const char* what = room ? "grid room" : "grid slab";
        Scene s = emissionOnlyScene(false, true, room);
        const auto pixels = innerPixels(s, room);
        ASSERT_GE(pixels.size(), 100u);
        // PPB: the pass images' inner means are independent; their spread gives the standard error.
        PassRenderer renderer(s, smallSettings());
        const int passes = 64;
        std::vector<double> means;
        double expected = 0;
        for (int p = 0; p < passes; ++p) {
            auto [m, e] = meanAndExpected(renderer.renderPass(uint64_t(p)), pixels);
            means.push_back(m);
            expected = e;
        }
        double mean = 0, var = 0;
        for (double m : means) mean += m / passes;
        for (double m : means) var += (m - mean) * (m - mean) / (passes - 1);
        const double se = std::sqrt(var / passes);
        std::printf("%s, PPB: inner mean %.5f, closed form %.5f, standard error %.5f\n", what, mean, expected, se);
        EXPECT_NEAR(mean, expected, 4.5 * se + 1e-3 * expected) << what;
        EXPECT_GT(se, 0.0);

        ReferenceSettings rs;
        rs.width = rs.height = kSize;
        rs.samplesPerPixel = 64;
        rs.seed = 5;
        EmbreeScene rt(s);
        ReferenceTracer ref(rt, rs);
        ReferenceImage r = ref.render();
        auto [rm, re] = meanAndExpected(r.mean, pixels);
        double rvar = 0;
        for (const auto& [pixel, chord] : pixels) rvar += r.varianceOfMean.pixels[size_t(pixel)].r;
        const double rse = std::sqrt(rvar) / pixels.size();
        std::printf("%s, reference: inner mean %.5f, closed form %.5f, standard error %.5f\n", what, rm, re, rse);
        EXPECT_NEAR(rm, re, 4.5 * rse + 1e-3 * re) << what;
    }
}

/// The room of emissionOnlyScene(room) filled with a grid whose density and Le both vary (density
/// 0.2-1.8 in voxels of 0.1, Le = LinearEmission): the camera's primary segments cross it.
Scene varyingEmissionRoom() {
    Scene s = emissionOnlyScene(false, true, true);
    const int n = 27;
    const int dims[3] = {n, n, n};
    std::vector<float> values(size_t(n) * n * n);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                values[(size_t(k) * n + j) * n + i] = 1.0f + 0.8f * std::sin(0.7f * i + 0.3f * j) * std::cos(0.5f * k);
    s.media[0].density = VdbDensityGrid::fromDense(dims, values, Affine3::scaleTranslate(Vec3(0.1f), Vec3(-1.3f)), "wavy");
    s.media[0].emissionField = std::make_shared<LinearEmission>();
    return s;
}

TEST(MediumEmission, VaryingGridRoomMatchesTheReferenceAndItsVarianceFallsAsOneOverPasses) {
    const Scene s = varyingEmissionRoom();
    RenderSettings ps = smallSettings();
    PassRenderer renderer(s, ps);
    const int passes = 64, pixels = kSize * kSize;
    std::vector<Image> images;
    for (int p = 0; p < passes; ++p) images.push_back(renderer.renderPass(uint64_t(p)));
    // Per pixel (red): the spread of single passes and of means of 4 consecutive passes; with
    // independent passes the second is a quarter of the first.
    double single = 0, ofFour = 0, ppbMean = 0;
    for (int i = 0; i < pixels; ++i) {
        double m = 0, v1 = 0, v4 = 0;
        for (const Image& img : images) m += img.pixels[size_t(i)].r / passes;
        for (const Image& img : images) v1 += std::pow(img.pixels[size_t(i)].r - m, 2) / (passes - 1);
        for (int b = 0; b < passes / 4; ++b) {
            double mb = 0;
            for (int q = 0; q < 4; ++q) mb += images[size_t(4 * b + q)].pixels[size_t(i)].r / 4;
            v4 += (mb - m) * (mb - m) / (passes / 4 - 1);
        }
        single += v1 / pixels, ofFour += v4 / pixels, ppbMean += m / pixels;
    }
    std::printf("varying grid room: pass variance %.3g, of 4-pass means %.3g (ratio %.2f)\n", single, ofFour,
                single / ofFour);
    EXPECT_GT(single, 0.0);
    // 576 pixels x 15 block means: the ratio's own spread is a few percent.
    EXPECT_NEAR(single / ofFour, 4.0, 0.6);

    ReferenceSettings rs;
    rs.width = rs.height = kSize;
    rs.samplesPerPixel = 64;
    rs.seed = 5;
    EmbreeScene rt(s);
    const ReferenceImage ref = ReferenceTracer(rt, rs).render();
    double refMean = 0, refVar = 0;
    for (int i = 0; i < pixels; ++i) refMean += ref.mean.pixels[size_t(i)].r / pixels;
    for (int i = 0; i < pixels; ++i) refVar += ref.varianceOfMean.pixels[size_t(i)].r / (double(pixels) * pixels);
    // The PPB image mean's variance: the pass variance over all pixels and passes (pixels are
    // nearly independent, so this is close).
    const double se = std::sqrt(refVar + single / (double(pixels) * passes));
    std::printf("varying grid room: PPB %.5f, reference %.5f (standard error %.5f)\n", ppbMean, refMean, se);
    EXPECT_NEAR(ppbMean, refMean, 4.5 * se + 1e-3 * refMean);
}

// ---- Photons from emissive media (cpu/medium_emitters.h)

/// Volume enclosed by a closed, outward mesh (divergence theorem).
double meshVolume(const TriangleMesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) v += dot(m.vertex(t, 0), cross(m.vertex(t, 1), m.vertex(t, 2))) / 6.0;
    return v;
}

/// Mean photon power over `n` samples, with its standard error, per channel.
void meanPower(const MediumEmitters& e, int n, Rgb* mean, Rgb* se) {
    Rng rng(77, 5);
    double sum[3] = {}, sum2[3] = {};
    for (int i = 0; i < n; ++i) {
        const Rgb p = e.sample(rng).power;
        for (int c = 0; c < 3; ++c) sum[c] += p[c], sum2[c] += double(p[c]) * p[c];
    }
    for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / n;
        (*mean)[c] = float(m);
        (*se)[c] = float(std::sqrt(std::max(0.0, sum2[c] / n - m * m) / n));
    }
}

TEST(MediumEmission, PhotonPowerIsTheIntegralOfFourPiSigmaALe) {
    {
        // A homogeneous emitting sphere: the box's corners lie outside it (mediumAt) and emit 0.
        Scene s = emissionOnlyScene(true, false);
        EmbreeScene rt(s);
        MediumEmitters e(rt);
        ASSERT_FALSE(e.empty());
        Rgb mean, se;
        meanPower(e, 200000, &mean, &se);
        const Rgb exact = kLe * float(4 * kPi * kSigmaA * meshVolume(s.meshes[0]));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], exact[c], 5 * se[c] + 1e-4f * exact[c]) << "sphere " << c;
    }
    {
        // A block of voxels (value 2 on 4^3 voxels of 0.1) with Le linear in x, as a global
        // medium in a room: each voxel's trilinear hat integrates to one voxel volume, and a
        // linear Le over a symmetric hat to its value at the voxel centre.
        Scene s = test::causticScene();
        s.lights.clear();
        const int dims[3] = {6, 6, 6};
        std::vector<float> values(216, 0.0f);
        double exactR = 0, exactB = 0;
        const Vec3 corner(-0.35f, -1.2f, 0.6f);
        for (int k = 1; k <= 4; ++k)
            for (int j = 1; j <= 4; ++j)
                for (int i = 1; i <= 4; ++i) {
                    values[size_t(i + 6 * (j + 6 * k))] = 2.0f;
                    const float x = corner.x + 0.1f * float(i);
                    exactR += 2.0 * (1.0 + x) * 1e-3;
                    exactB += 2.0 * (2.0 - x) * 1e-3;
                }
        Medium& m = s.media[0];
        m.density = VdbDensityGrid::fromDense(dims, values, Affine3::scaleTranslate(Vec3(0.1f), corner), "block");
        m.emissionField = std::make_shared<LinearEmission>();
        s.finalize();
        s.validate();
        EmbreeScene rt(s);
        MediumEmitters e(rt);
        Rgb mean, se;
        meanPower(e, 200000, &mean, &se);
        const double k = 4 * kPi * m.sigmaA.r;
        EXPECT_NEAR(mean.r, k * exactR, 5 * se.r + 1e-4 * k * exactR);
        EXPECT_NEAR(mean.b, k * exactB, 5 * se.b + 1e-4 * k * exactB);
    }
}

TEST(MediumEmission, EmittingSmokeSphereLightsTheFloorAsInTheReference) {
    // A homogeneous emitting, scattering sphere over a diffuse floor, nothing else emitting: the
    // floor and the smoke's scattered light come from photons that leave the medium in PPB and
    // from paths that cross it in the reference path tracer.
    Scene s;
    s.name = "emitting-smoke-sphere";
    s.source = "<test>";
    Material hull, floor;
    hull.name = "hull";
    hull.type = MaterialType::Interface;
    floor.name = "floor";
    floor.albedo = Rgb(0.7f);
    s.materials = {hull, floor};
    Medium m;
    m.name = "glowing smoke";
    m.sigmaS = Rgb(1.5f);
    m.sigmaA = Rgb(1.0f);
    m.g = 0.2f;
    m.emission = Rgb(2.0f, 1.2f, 0.5f);
    s.media = {m};
    TriangleMesh ball = makeSphere("ball", Vec3(0, 0.8f, 0), 0.5f, 4, 0);
    ball.interiorMedium = 0;
    ball.exteriorMedium = kVacuum;
    s.meshes.push_back(ball);
    s.meshes.push_back(makeQuad("floor", {-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 1));
    s.camera = Camera::lookAt({0, 1.6f, 2.6f}, {0, 0.45f, 0}, {0, 1, 0}, 0.8f);
    s.finalize();
    s.validate();
    const int w = 32, h = 24;

    RenderSettings ps;
    ps.width = w;
    ps.height = h;
    ps.photonsPerPass = 4000;
    ps.seed = 3;
    ps.gpu = GpuMode::Off;
    PassRenderer renderer(s, ps);
    Accumulator acc(w, h);
    for (uint64_t p = 0; p < 48; ++p) acc.addPass(renderer.renderPass(p));
    const Image ppb = acc.mean();

    ReferenceSettings rs;
    rs.width = w;
    rs.height = h;
    rs.samplesPerPixel = 256;
    rs.seed = 8;
    EmbreeScene rt(s);
    const ReferenceImage ref = ReferenceTracer(rt, rs).render();

    // Regions: pixels whose centre ray meets the ball (smoke), and floor pixels below it.
    double sums[2][2] = {}, vars[2] = {};
    int counts[2] = {};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            SurfaceHit hit;
            if (!rt.intersect(s.camera.generateRay(x + 0.5f, y + 0.5f, w, h, {0.5f, 0.5f}), &hit)) continue;
            const int region = hit.mesh == 0 ? 0 : 1;
            const size_t i = size_t(y) * w + x;
            sums[region][0] += ppb.pixels[i].luminance();
            sums[region][1] += ref.mean.pixels[i].luminance();
            vars[region] += ref.varianceOfMean.pixels[i].luminance();
            ++counts[region];
        }
    for (int r = 0; r < 2; ++r) {
        ASSERT_GT(counts[r], 40);
        const double p = sums[r][0] / counts[r], q = sums[r][1] / counts[r], se = std::sqrt(vars[r]) / counts[r];
        std::printf("%s: PPB %.4f, reference %.4f (standard error %.4f)\n", r == 0 ? "smoke sphere" : "floor", p, q, se);
        EXPECT_GT(q, 0.0);
        // PPB is consistent but biased at finite radii: 5% + 4 of the reference's standard errors.
        EXPECT_NEAR(p, q, 0.05 * q + 4 * se) << (r == 0 ? "smoke sphere" : "floor");
    }
}

}  // namespace
}  // namespace tyndall
