#pragma once
// Scenes and helpers shared by the reference-tracer tests (self-checks, analytic scene,
// PPB-versus-reference consistency).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/accumulator.h"
#include "core/density_grid.h"
#include "core/image_io.h"
#include "core/scene.h"
#include "cpu/pass_renderer.h"
#include "cpu/radius_defaults.h"
#include "cpu/reference_tracer.h"
#include "loading/mesh_builders.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

namespace tyndall::test {

/// A density field rho(x) = a + b dot(x, axis) over the unit sphere (grid media): linear, so the
/// optical depth of any segment inside the sphere is its length times rho at its midpoint.
class LinearRampDensity : public DensityGrid {
public:
    LinearRampDensity(float a, float b, Vec3 axis) : m_a(a), m_b(b), m_axis(normalize(axis)) {}
    float density(const Vec3& p) const override {
        return bounds().contains(p) ? std::max(0.0f, m_a + m_b * dot(p, m_axis)) : 0.0f;
    }
    Bounds3 bounds() const override { return {Vec3(-1.01f), Vec3(1.01f)}; }
    float maxDensity() const override { return m_a + std::abs(m_b) * 1.01f * std::sqrt(3.0f); }
    float meanDensity() const override { return m_a; }

private:
    float m_a, m_b;
    Vec3 m_axis;
};

/// A sphere of radius `radius` at the origin filled with `medium`, `light` (a point or spot light,
/// normally at the centre), nothing else (vacuum outside). The hull is an index-matched Interface
/// (light passes straight through) unless `diffuseWall` makes it a diffuse inner wall of albedo
/// `wallAlbedo` (a closed room with the medium inside).
inline Scene makeMediumSphereScene(const Medium& medium, float radius, const Light& light, const Camera& camera,
                                   bool diffuseWall = false, Rgb wallAlbedo = Rgb(0.5f)) {
    Scene s;
    s.name = "medium-sphere";
    s.source = "<test scene>";
    Material hull;
    hull.name = diffuseWall ? "wall" : "hull";
    hull.type = diffuseWall ? MaterialType::Diffuse : MaterialType::Interface;
    hull.albedo = wallAlbedo;
    s.materials.push_back(hull);
    s.media.push_back(medium);
    TriangleMesh sphere = makeSphere("sphere", Vec3(0.0f), radius, 5, 0);
    sphere.interiorMedium = 0;
    sphere.exteriorMedium = kVacuum;
    s.meshes.push_back(sphere);
    s.lights.push_back(light);
    s.camera = camera;
    s.finalize();
    s.validate();
    return s;
}

/// The six walls of the room x in [-1, 1], y in [0, 2], z in [-1, 1], facing inward, as quads in
/// the order floor, ceiling, back, front, left (material `left`), right (`right`); the others `white`.
inline void addRoomWalls(Scene& s, int white, int left, int right) {
    s.meshes.push_back(makeQuad("floor", {-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, white));
    s.meshes.push_back(makeQuad("ceiling", {-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white));
    s.meshes.push_back(makeQuad("back wall", {-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white));
    s.meshes.push_back(makeQuad("front wall", {1, 0, 1}, {-2, 0, 0}, {0, 2, 0}, white));
    s.meshes.push_back(makeQuad("left wall", {-1, 0, 1}, {0, 0, -2}, {0, 2, 0}, left));
    s.meshes.push_back(makeQuad("right wall", {1, 0, -1}, {0, 0, 2}, {0, 2, 0}, right));
}

/// A point light at `p` of grey intensity `intensity`.
inline Light pointLight(Vec3 p, float intensity) {
    Light l;
    l.name = "point";
    l.position = p;
    l.intensity = Rgb(intensity);
    return l;
}

/// A closed 2-unit box (x, y, z in [-1, 1]) of albedo-0.5 diffuse walls full of fog (the global
/// medium: `sigmaS`, `sigmaA`, Henyey-Greenstein `g`) round a point light of intensity 1 at
/// `light`, seen from (0, 0, 0.95) looking down -z with the vertical field of view `fov` (radians).
inline Scene makeFogBoxWithLamp(Rgb sigmaS, Rgb sigmaA, float g, Vec3 light, float fov) {
    Scene s;
    s.name = "fog-box-lamp";
    s.source = "<test scene>";
    addMaterial(s, "white", MaterialType::Diffuse, Rgb(0.5f));
    s.meshes.push_back(makeBox("room", {-1, -1, -1}, {1, 1, 1}, 0, true));
    s.media.push_back(homogeneousMedium(sigmaS, sigmaA, g));
    s.globalMedium = 0;
    s.lights.push_back(pointLight(light, 1.0f));
    s.camera = Camera::lookAt({0, 0, 0.95f}, {0, 0, -1}, {0, 1, 0}, fov);
    s.finalize();
    s.validate();
    return s;
}

/// The consistency scene: a 2 x 2 x 2 room full of fog, coloured walls, a spot light shining down
/// onto the floor (its cone misses both specular objects, so the reference can reach everything
/// it lights), a small area light on the ceiling, a mirror on the back wall and a glass sphere.
/// Secondary camera segments (through the mirror and the glass) gather beams on the CPU; primary
/// ones go through the beam rasterizer; diffuse hits use surface photons.
inline Scene makeConsistencyScene() {
    Scene s;
    s.name = "consistency-room";
    s.source = "<test scene>";
    int white = addMaterial(s, "white", MaterialType::Diffuse, Rgb(0.7f));
    int red = addMaterial(s, "red", MaterialType::Diffuse, Rgb(0.7f, 0.2f, 0.15f));
    int green = addMaterial(s, "green", MaterialType::Diffuse, Rgb(0.2f, 0.6f, 0.3f));
    int mirror = addMaterial(s, "mirror", MaterialType::Mirror, Rgb(0.9f));
    int glass = addMaterial(s, "glass", MaterialType::Dielectric, Rgb(1.0f));
    int lamp = addMaterial(s, "lamp", MaterialType::Diffuse, Rgb(0.5f), Rgb(3.0f, 2.8f, 2.4f));

    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(0.15f, 0.16f, 0.18f);
    fog.sigmaA = Rgb(0.02f);
    fog.g = 0.3f;
    s.media.push_back(fog);
    s.globalMedium = 0;

    addRoomWalls(s, white, red, green);
    s.meshes.push_back(makeQuad("mirror", {-0.9f, 0.3f, -0.99f}, {0.8f, 0, 0}, {0, 1.3f, 0}, mirror));
    s.meshes.push_back(makeSphere("glass sphere", {0.45f, 0.36f, -0.45f}, 0.3f, 3, glass));
    // Emits downward (the quad's normal is -y), slightly below the ceiling.
    s.meshes.push_back(makeQuad("lamp", {0.35f, 1.98f, 0.25f}, {0.4f, 0, 0}, {0, 0, 0.4f}, lamp));

    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {-0.45f, 1.9f, -0.2f};
    spot.direction = normalize(Vec3(0.05f, -1.0f, 0.05f));
    spot.cosOuterAngle = std::cos(18.0f * kPi / 180.0f);
    spot.cosInnerAngle = std::cos(12.0f * kPi / 180.0f);
    spot.intensity = Rgb(6.0f, 5.6f, 4.8f);
    s.lights.push_back(spot);

    s.camera = Camera::lookAt({0.1f, 1.1f, 0.95f}, {-0.05f, 0.75f, -1.0f}, {0, 1, 0}, 70.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// Mean of `passes` PPB passes [firstPass, firstPass + passes) of `renderer`.
inline Image renderPpbPasses(const PassRenderer& renderer, uint64_t firstPass, uint64_t passes) {
    Accumulator acc(renderer.settings().width, renderer.settings().height);
    for (uint64_t p = firstPass; p < firstPass + passes; ++p) acc.addPass(renderer.renderPass(p));
    return acc.mean();
}

/// Writes `image` to TYNDALL_TEST_OUTPUT_DIR/<name>.exr (evidence for a failed test).
inline void writeEvidence(const std::string& name, const Image& image) {
    writeImage(std::string(TYNDALL_TEST_OUTPUT_DIR) + "/" + name + ".exr", image);
}

/// Per-pixel |a - b| (for the error image written on failure).
inline Image absDifference(const Image& a, const Image& b) {
    Image d(a.width, a.height);
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) d.pixels[i][c] = std::abs(a.pixels[i][c] - b.pixels[i][c]);
    return d;
}

/// relMSE of a PPB image against a reference image: mean over pixels and channels of
/// (ppb - ref)^2 / (ref^2 + eps), eps = (0.1 mean(ref))^2 so dark pixels do not dominate, with
/// the reference's own variance (its share of that expectation) kept apart.
struct RelMse {
    double raw = 0;           ///< against the (noisy) reference
    double referenceVar = 0;  ///< the reference's own share of it
    double corrected() const { return raw - referenceVar; }
};

inline RelMse relMse(const Image& ppb, const ReferenceImage& ref) {
    double mean = 0;
    for (const Rgb& p : ref.mean.pixels) mean += p.r + p.g + p.b;
    mean /= 3.0 * ref.mean.pixels.size();
    const double eps = 0.01 * mean * mean;
    RelMse r;
    for (size_t i = 0; i < ppb.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            double x = ref.mean.pixels[i][c], d = ppb.pixels[i][c] - x;
            r.raw += d * d / (x * x + eps);
            r.referenceVar += ref.varianceOfMean.pixels[i][c] / (x * x + eps);
        }
    double n = 3.0 * ppb.pixels.size();
    r.raw /= n;
    r.referenceVar /= n;
    return r;
}

inline double regionMean(const Image& img, int x0, int y0, int x1, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += img.at(x, y).r + img.at(x, y).g + img.at(x, y).b;
    return sum / (3.0 * (x1 - x0) * (y1 - y0));
}

struct ConsistencyBounds {
    double finalRelMse;                 ///< relMSE after 64 passes
    double imageMean = 0.03;            ///< |PPB/reference - 1| of the image mean
    double quadrantMean = 0.06;         ///< same for each 16 x 16 quadrant
    double regionBias = 0.03;           ///< PPB's kernel bias allowed per region, on top of 4 standard errors
    bool glassRegion = true;            ///< also check the pixels that see the glass sphere
    /// PPB passes in all (>= 64, a multiple of 8): the relMSE is judged at 4, 16 and 64, the image,
    /// quadrant and region means after all of them (regions from 8 batches of passes / 8).
    uint64_t passes = 64;
    /// The reference's own variance may be at most this share of the corrected relMSE it judges.
    double referenceVarianceShare = 0.3;
};

/// For each pixel of a size x size image of `scene`, the mesh its primary rays hit (through the
/// pixel's centre and its four corners, pinhole), or -1 where they disagree or miss: the pixels
/// that see one object only.
inline std::vector<int> pixelMeshes(const Scene& scene, int size) {
    EmbreeScene rt(scene);
    std::vector<int> out(size_t(size) * size, -1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            int mesh = -2;
            const float corners[5][2] = {{0.5f, 0.5f}, {0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 1.0f}};
            for (const auto& c : corners) {
                SurfaceHit hit;
                Ray ray = scene.camera.generateRay(x + c[0], y + c[1], size, size, {0.5f, 0.5f});
                int m = rt.intersect(ray, &hit) ? hit.mesh : -1;
                mesh = (mesh == -2 || mesh == m) ? m : -1;
            }
            out[size_t(y) * size + x] = mesh;
        }
    return out;
}

/// Mean over the pixels i with classOfPixel[i] == cls (all three channels); 0 when there are none.
inline double meanOverPixels(const Image& img, const std::vector<int>& classOfPixel, int cls) {
    double sum = 0;
    int n = 0;
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (classOfPixel[i] == cls) sum += img.pixels[i].r + img.pixels[i].g + img.pixels[i].b, ++n;
    return n ? sum / (3.0 * n) : 0.0;
}

constexpr float kOpenFogSigmaS = 0.25f, kOpenFogSigmaA = 0.1f;

/// Open space filled with homogeneous fog (extinction 0.35): a marker quad far away sets the scene
/// bounds (where the global medium exists) to enclose everything the tests use.
inline Scene openFog(const std::vector<Light>& lights, float g) {
    Scene s;
    s.name = "open-fog";
    s.source = "<test>";
    Material white;
    white.name = "white";
    white.albedo = Rgb(0.5f);
    s.materials.push_back(white);
    s.meshes.push_back(makeQuad("far", {-10, -10, -10}, {20, 0, 0}, {0, 0, 20}, 0));
    s.meshes.push_back(makeQuad("far-top", {-10, 10, 10}, {20, 0, 0}, {0, 0, -20}, 0));
    Medium m;
    m.name = "fog";
    m.sigmaS = Rgb(kOpenFogSigmaS);
    m.sigmaA = Rgb(kOpenFogSigmaA);
    m.g = g;
    s.media.push_back(m);
    s.globalMedium = 0;
    s.lights = lights;
    s.camera = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f);
    return s;
}

/// PPB settings with constant radii (beam 0.02, surface `surfaceRadius`: a huge schedule offset),
/// so that passes are independent and alike and the spread of batch means is their standard error.
inline RenderSettings constantRadiusSettings(int size, uint32_t photons, uint64_t seed, bool directLight,
                                             float surfaceRadius) {
    RenderSettings ps;
    ps.width = ps.height = size;
    ps.photonsPerPass = photons;
    ps.seed = seed;
    ps.directLight = directLight;
    ps.radius = 0.02f;
    ps.surfaceRadius = surfaceRadius;
    ps.radiusOffset = 1000000000000ull;
    return ps;
}

// Equiangular sampling on with constant radii (an offset that never shrinks them), so the passes
// are independent and alike: batches of them are a standard error's worth apart, and a pixel's
// variance over seeds falls as 1/passes where no kernel remains.
inline RenderSettings equiangularConstantRadii(int size, uint32_t photons) {
    const RenderSettings defaults;
    RenderSettings ps = constantRadiusSettings(size, photons, defaults.seed, defaults.directLight, 0.06f);
    ps.radius = 0.03f;
    ps.photonAngle = 0;
    ps.equiangular = true;
    return ps;
}

struct RegionEstimate {
    double mean = 0, se = 0;
};

/// A unit sphere of `medium` with a diffuse inner wall round a point light of intensity 1 at its
/// centre, seen from (0, 0, 0.5) down -z: the scene of the tests of what becomes of the beams after
/// a scattering in a dense medium.
inline Scene litMediumSphere(const Medium& medium) {
    return makeMediumSphereScene(medium, 1.0f, pointLight(Vec3(0.0f), 1.0f),
                                 Camera::lookAt({0, 0, 0.5f}, {0, 0, -1}, {0, 1, 0}, 1.0f), true);
}

/// Their settings: 16x16, 2000 paths a pass, seed 3, no shadow rays, no equiangular samples, no
/// photon cone, the beams' radius 0.02 a million paths into a plan of two million (it shrinks by
/// 0.71 over the first million), the surface radius 0.05.
inline RenderSettings litMediumSphereSettings() {
    RenderSettings ps = constantRadiusSettings(16, 2000, 3, false, 0.05f);
    ps.radiusOffset = 1000000;
    ps.plannedPaths = 2000000;
    ps.photonAngle = 0;
    ps.equiangular = false;
    return ps;
}

/// PPB's whole-image mean (regionMean over the size x size image) across `batches` batches of
/// passes / batches passes of `renderer`, with the standard error from the batches' spread.
inline RegionEstimate ppbImageMean(const PassRenderer& renderer, int size, int passes, int batches = 8) {
    std::vector<double> means;
    for (int b = 0; b < batches; ++b) {
        const Image img = renderPpbPasses(renderer, uint64_t(b * passes / batches), uint64_t(passes / batches));
        means.push_back(regionMean(img, 0, 0, size, size));
    }
    const MeanVar mv = meanVar(means);
    return {mv.mean, std::sqrt(mv.var / batches)};
}

/// The path tracer's whole-image mean of a size x size image of `scene` (`spp` samples, `seed`),
/// with its standard error from the green channel's variance of the mean.
inline RegionEstimate referenceImageMean(const Scene& scene, int size, uint32_t spp, uint64_t seed) {
    ReferenceSettings rs;
    rs.width = rs.height = size;
    rs.samplesPerPixel = spp;
    rs.seed = seed;
    EmbreeScene rt(scene);
    const ReferenceImage ref = ReferenceTracer(rt, rs).render();
    double var = 0;
    for (const Rgb& v : ref.varianceOfMean.pixels) var += v.g;
    return {regionMean(ref.mean, 0, 0, size, size), std::sqrt(var) / double(size * size)};
}

/// For each class in `wanted` (`classes`: one per pixel, as pixelMeshes gives): PPB's mean over
/// its pixels across `batches` batches of `passes` passes, with the standard error from their
/// spread. `mean`, when given, receives the mean image.
inline std::vector<RegionEstimate> ppbRegionMeans(const Scene& scene, const RenderSettings& ps, int batches, int passes,
                                                  const std::vector<int>& classes, const std::vector<int>& wanted,
                                                  Image* mean = nullptr) {
    PassRenderer renderer(scene, ps);
    std::vector<std::vector<double>> m(wanted.size());
    Image sum(ps.width, ps.height);
    for (int b = 0; b < batches; ++b) {
        Image img = renderPpbPasses(renderer, uint64_t(b) * passes, passes);
        sum += img;
        for (size_t k = 0; k < wanted.size(); ++k) m[k].push_back(meanOverPixels(img, classes, wanted[k]));
    }
    if (mean) {
        for (Rgb& p : sum.pixels) p *= 1.0f / float(batches);
        *mean = sum;
    }
    std::vector<RegionEstimate> out;
    for (const auto& v : m) {
        MeanVar mv = meanVar(v);
        out.push_back({mv.mean, std::sqrt(mv.var / double(v.size()))});
    }
    return out;
}

/// PPB against the reference over the pixels that see one mesh (named `meshName`): the ratio of
/// the region's means must be within 4 combined standard errors plus `bias` of 1. PPB's standard
/// error comes from the spread of `batches` (independent batches of passes whose mean is the
/// PPB image), the reference's from its per-pixel variance of the mean (pixels independent,
/// channels bounded by Cauchy-Schwarz). A normalisation error confined to what is seen through
/// one object (a mirror's or a glass's secondary paths, a lit floor's surface photons) is diluted
/// below the relMSE's and the quadrants' tolerances; here it stands alone.
inline void expectRegionAgrees(const Scene& scene, const std::vector<int>& meshOfPixel, const char* meshName,
                               const std::vector<Image>& batches, const ReferenceImage& ref, double bias) {
    int mesh = -1;
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        if (scene.meshes[m].name == meshName) mesh = int(m);
    ASSERT_GE(mesh, 0) << "no mesh named " << meshName;
    double refSum = 0, refVar = 0;
    std::vector<double> batchSums(batches.size(), 0.0);
    int pixels = 0;
    for (size_t i = 0; i < meshOfPixel.size(); ++i) {
        if (meshOfPixel[i] != mesh) continue;
        ++pixels;
        double sd = 0;
        for (int c = 0; c < 3; ++c) {
            refSum += ref.mean.pixels[i][c];
            sd += std::sqrt(double(ref.varianceOfMean.pixels[i][c]));
            for (size_t b = 0; b < batches.size(); ++b) batchSums[b] += batches[b].pixels[i][c];
        }
        refVar += sd * sd;
    }
    ASSERT_GE(pixels, 12) << meshName << ": too few pixels see it to test";
    ASSERT_GT(refSum, 0.0) << meshName << ": dark in the reference";
    std::vector<double> ratios;
    for (double b : batchSums) ratios.push_back(b / refSum);
    double mean = 0, var = 0;
    for (double r : ratios) mean += r / double(ratios.size());
    for (double r : ratios) var += (r - mean) * (r - mean) / double(ratios.size() - 1);
    double sePpb = std::sqrt(var / double(ratios.size())), seRef = mean * std::sqrt(refVar) / refSum;
    double se = std::hypot(sePpb, seRef);
    std::printf("region '%s' (%d pixels): PPB / reference %.4f +- %.4f (PPB %.4f, reference %.4f)\n", meshName, pixels,
                mean, se, sePpb, seRef);
    // 0.04: with direct light by shadow rays (the default) the camera paths through the glass sphere
    // end at diffuse surfaces with one shadow ray per pass, noise the photon kernel had smoothed:
    // that region's standard error went from 0.028 (photons only) to 0.033 (measured, seed as here).
    // 0.05: the glass region's spread is heavy-tailed (Fresnel-split paths through the glass) and
    // moves with the random streams, not with the estimator: with the same estimator it read 0.031
    // (the film jitter drawn from the PixelJitter stream), 0.046 (drawn from another stream) and
    // 0.045 (the low-discrepancy film jitter, core/pixel_jitter.h; 16 batches of 4: 0.044).
    EXPECT_LT(se, 0.05) << meshName << ": too noisy to test";
    EXPECT_NEAR(mean, 1.0, 4.0 * se + bias) << "region seeing '" << meshName << "'";
}

/// PPB against the reference over the whole image and its four quadrants: `means` are the mean
/// images of independent batches of passes (their spread gives PPB's standard error), the
/// reference's from its per-pixel variance of the mean (green channel). Each region's ratio must
/// be within 4 combined standard errors plus `bias` of 1, and the combined standard error below
/// `noise` of the reference (else the test could not tell).
inline void expectQuadrantsAgree(const std::vector<Image>& means, const ReferenceImage& ref, double noise, double bias) {
    const int w = ref.mean.width, hgt = ref.mean.height, hw = w / 2, hh = hgt / 2;
    const int regions[5][4] = {{0, 0, w, hgt}, {0, 0, hw, hh}, {hw, 0, w, hh}, {0, hh, hw, hgt}, {hw, hh, w, hgt}};
    for (const auto& r : regions) {
        std::vector<double> m;
        for (const Image& img : means) m.push_back(regionMean(img, r[0], r[1], r[2], r[3]));
        const MeanVar mv = meanVar(m);
        const double se = std::sqrt(mv.var / double(m.size()));
        const double reference = regionMean(ref.mean, r[0], r[1], r[2], r[3]);
        double refVar = 0;
        for (int y = r[1]; y < r[3]; ++y)
            for (int x = r[0]; x < r[2]; ++x) refVar += ref.varianceOfMean.at(x, y).g;
        const double seRef = std::sqrt(refVar) / ((r[2] - r[0]) * (r[3] - r[1]));
        const double seBoth = std::sqrt(se * se + seRef * seRef);
        std::printf("region %d,%d-%d,%d: PPB %.5f +- %.5f, reference %.5f +- %.5f\n", r[0], r[1], r[2], r[3], mv.mean,
                    se, reference, seRef);
        EXPECT_LT(seBoth, noise * reference) << "too noisy to test";
        EXPECT_NEAR(mv.mean / reference, 1.0, 4 * seBoth / reference + bias) << r[0] << "," << r[1];
    }
}

/// PPB with `ps` (constant radii, so batches are independent and alike) against a 512-spp reference
/// of the same size (seed 21): 8 batches of 4 passes, then expectQuadrantsAgree with `noise` and
/// `bias`.
inline void expectBatchesAgreeWithThePathTracer(const Scene& scene, const RenderSettings& ps, double noise,
                                                double bias) {
    PassRenderer renderer(scene, ps);
    const int batches = 8, passesPerBatch = 4;
    std::vector<Image> means;
    for (int b = 0; b < batches; ++b) means.push_back(renderPpbPasses(renderer, uint64_t(b) * passesPerBatch, passesPerBatch));

    ReferenceSettings rs;
    rs.width = ps.width;
    rs.height = ps.height;
    rs.samplesPerPixel = 512;
    rs.seed = 21;
    EmbreeScene rt(scene);
    ReferenceImage ref = ReferenceTracer(rt, rs).render();
    expectQuadrantsAgree(means, ref, noise, bias);
}

/// The variance law of a renderer whose passes are independent and unbiased: renders `scene` with
/// `ps` and `seeds` seeds (firstSeed, firstSeed + 1, ...) for 4 and for 16 passes; per pixel the
/// variance over seeds relative to the pixel's mean squared, averaged over pixels; returns the slope
/// of its logarithm against that of the pass count (-1 for a variance falling as 1/passes).
inline double varianceSlopeOverPasses(const Scene& scene, const RenderSettings& ps, int seeds, uint64_t firstSeed) {
    const int counts[2] = {4, 16};
    double variance[2] = {0, 0};
    const size_t pixels = size_t(ps.width) * size_t(ps.height);
    for (int c = 0; c < 2; ++c) {
        std::vector<Image> runs;
        for (int k = 0; k < seeds; ++k) {
            RenderSettings sk = ps;
            sk.seed = firstSeed + uint64_t(k);
            PassRenderer renderer(scene, sk);
            runs.push_back(renderPpbPasses(renderer, 0, uint64_t(counts[c])));
        }
        for (size_t i = 0; i < pixels; ++i) {
            std::vector<double> v;
            for (const Image& r : runs) v.push_back(r.pixels[i].g);
            const MeanVar mv = meanVar(v);
            variance[c] += mv.var / (mv.mean * mv.mean) / double(pixels);
        }
    }
    const double slope = std::log(variance[1] / variance[0]) / std::log(double(counts[1]) / counts[0]);
    std::printf("relative variance %.3e after %d passes, %.3e after %d: slope %.3f\n", variance[0], counts[0],
                variance[1], counts[1], slope);
    EXPECT_GT(variance[0], 0.0);
    return slope;
}

/// The consistency check shared by the homogeneous and the VDB tests: at 32 x 32, a 4096-spp
/// reference against PPB with 2000 photon paths per pass. relMSE must fall by at least a quarter
/// from 4 to 16 and from 16 to 64 passes (for alpha = 0.5 the variance alone halves per 4x
/// passes) and end below `bounds.finalRelMse`; the reference's variance must be well below what
/// it judges; image and quadrant means must agree (they expose normalisation errors the relMSE's
/// noise hides); and so must the pixels that see the mirror, the glass sphere and the floor, each
/// on its own (expectRegionAgrees, with PPB's standard errors from 8 batches of bounds.passes / 8
/// passes). On
/// failure the PPB, reference and error images go to the test output folder as
/// `<evidence>_ppb.exr` etc.
inline void expectPpbConvergesToReference(const Scene& scene, const ConsistencyBounds& bounds, uint64_t referenceSeed,
                                          uint64_t ppbSeed, const std::string& evidence) {
    const int size = 32;
    ReferenceSettings rs;
    rs.width = rs.height = size;
    rs.samplesPerPixel = 4096;
    rs.seed = referenceSeed;
    EmbreeScene rt(scene);
    ReferenceImage ref = ReferenceTracer(rt, rs).render();

    RenderSettings ps;
    ps.width = ps.height = size;
    ps.photonsPerPass = 2000;
    ps.alpha = 0.5;
    ps.seed = ppbSeed;
    // The scene-relative radii (0.5% / 2% of the diagonal, offset 1000) the bounds were measured
    // with, on purpose: they judge the estimator, and the reference's noise budget was sized for
    // them. With the default radii (surface radius capped at 2% of the diagonal) this scene
    // renders far closer to the reference (relMSE 0.0043 after 64 passes, image mean 0.998, floor
    // 0.997), so close that the 4096-spp reference is too noisy to judge it (its variance 0.0023)
    // and the glass region's batches too few; before the cap the defaults' 3-footprint surface
    // kernel lost 5% of the floor's light at this size (0.945).
    ps = withSceneRelativeRadii(ps, scene);
    PassRenderer renderer(scene, ps);
    Accumulator acc(size, size);
    const uint64_t checkpoints[] = {4, 16, 64};
    const uint64_t passesPerBatch = bounds.passes / 8;
    std::vector<RelMse> errors;
    std::vector<Image> batches;
    Accumulator batch(size, size);
    for (uint64_t pass = 0; pass < bounds.passes; ++pass) {
        Image passImage = renderer.renderPass(pass);
        acc.addPass(passImage);
        batch.addPass(passImage);
        if ((pass + 1) % passesPerBatch == 0) {
            batches.push_back(batch.mean());
            batch = Accumulator(size, size);
        }
        if (errors.size() < 3 && pass + 1 == checkpoints[errors.size()]) {
            errors.push_back(relMse(acc.mean(), ref));
            std::printf("%3llu passes: relMSE %.5f (raw %.5f, reference variance %.5f)\n",
                        (unsigned long long)(pass + 1), errors.back().corrected(), errors.back().raw,
                        errors.back().referenceVar);
        }
    }
    EXPECT_LT(errors.back().referenceVar, bounds.referenceVarianceShare * errors.back().corrected())
        << "reference too noisy to judge PPB";
    EXPECT_LT(errors[1].corrected(), 0.75 * errors[0].corrected()) << "relMSE did not fall from 4 to 16 passes";
    EXPECT_LT(errors[2].corrected(), 0.75 * errors[1].corrected()) << "relMSE did not fall from 16 to 64 passes";
    EXPECT_LT(errors[2].corrected(), bounds.finalRelMse) << "relMSE after 64 passes";

    Image ppb = acc.mean();
    double ratio = regionMean(ppb, 0, 0, size, size) / regionMean(ref.mean, 0, 0, size, size);
    std::printf("image mean PPB / reference: %.4f\n", ratio);
    EXPECT_NEAR(ratio, 1.0, bounds.imageMean) << "image means";
    const int half = size / 2;
    for (int qy = 0; qy < 2; ++qy)
        for (int qx = 0; qx < 2; ++qx) {
            int x0 = qx * half, y0 = qy * half;
            double q =
                regionMean(ppb, x0, y0, x0 + half, y0 + half) / regionMean(ref.mean, x0, y0, x0 + half, y0 + half);
            std::printf("quadrant (%d, %d) mean PPB / reference: %.4f\n", qx, qy, q);
            EXPECT_NEAR(q, 1.0, bounds.quadrantMean) << "quadrant (" << qx << ", " << qy << ") means";
        }
    const std::vector<int> meshOfPixel = pixelMeshes(scene, size);
    for (const char* region : {"mirror", "glass sphere", "floor"})
        if (bounds.glassRegion || std::string(region) != "glass sphere")
            expectRegionAgrees(scene, meshOfPixel, region, batches, ref, bounds.regionBias);
    if (::testing::Test::HasFailure()) {
        writeEvidence(evidence + "_ppb", ppb);
        writeEvidence(evidence + "_reference", ref.mean);
        writeEvidence(evidence + "_error", absDifference(ppb, ref.mean));
    }
}

}  // namespace tyndall::test
