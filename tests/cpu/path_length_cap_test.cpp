// --max-path-length (RenderSettings::maxPathLength, ReferenceSettings::maxPathLength): the camera
// segments plus the photon segments of one light path, as Mitsuba's max_depth and Tungsten's
// max_bounces count them; crossing an index-matched Interface starts no segment.
//   - cap 1: the emitters seen directly, and nothing else: every pixel that does not see the lamp
//     reads exactly 0 in both renderers (not even the lamp in the mirror, a second segment); those
//     that see it read Le x the fog's transmittance along the way (computed here);
//   - caps 2 and 3 (and uncapped): PPB agrees with the path tracer, whole image and quadrants, on a
//     foggy room with diffuse walls, a mirror, an area light and a denser fog ball behind an
//     Interface; each cap adds light the one below leaves out (by more than the tolerance).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr int kSize = 24;
const Rgb kLe(4.0f, 3.6f, 3.0f);
const Rgb kFogSigmaT(0.30f, 0.32f, 0.35f);

Scene cappedRoom() {
    Scene s;
    s.name = "capped-room";
    s.source = "<test scene>";
    int white = test::addMaterial(s, "white", MaterialType::Diffuse, Rgb(0.7f));
    int red = test::addMaterial(s, "red", MaterialType::Diffuse, Rgb(0.7f, 0.25f, 0.2f));
    int mirror = test::addMaterial(s, "mirror", MaterialType::Mirror, Rgb(0.9f));
    int hull = test::addMaterial(s, "hull", MaterialType::Interface, Rgb(1.0f));
    int lamp = test::addMaterial(s, "lamp", MaterialType::Diffuse, Rgb(0.0f), kLe);
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = kFogSigmaT - Rgb(0.05f);
    fog.sigmaA = Rgb(0.05f);
    fog.g = 0.3f;
    Medium thick = fog;
    thick.name = "thick fog";
    thick.sigmaS = Rgb(1.2f, 1.0f, 0.9f);
    s.media = {fog, thick};
    s.globalMedium = 0;
    test::addRoomWalls(s, white, red, white);
    // On the back wall, facing the camera: it shows the lamp (2 segments) and the lit room (3+).
    s.meshes.push_back(makeQuad("mirror", {-0.8f, 0.2f, -0.98f}, {1.0f, 0, 0}, {0, 1.2f, 0}, mirror));
    TriangleMesh ball = makeSphere("fog ball", {0.45f, 0.45f, -0.3f}, 0.35f, 3, hull);
    ball.interiorMedium = 1;
    s.meshes.push_back(ball);
    // Emits downward (the quad's normal is -y), slightly below the ceiling.
    s.meshes.push_back(makeQuad("lamp", {-0.3f, 1.9f, -0.3f}, {0.6f, 0, 0}, {0, 0, 0.6f}, lamp));
    s.camera = Camera::lookAt({0.0f, 1.1f, 0.95f}, {-0.1f, 1.0f, -1.0f}, {0, 1, 0}, 80.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

ReferenceImage pathTraced(const Scene& scene, int cap, uint32_t spp) {
    ReferenceSettings rs;
    rs.width = rs.height = kSize;
    rs.samplesPerPixel = spp;
    rs.seed = 21;
    rs.maxPathLength = cap;
    EmbreeScene rt(scene);
    return ReferenceTracer(rt, rs).render();
}

/// PPB's mean image and its batches (8 of passes / 8 passes each) for standard errors.
struct PpbRender {
    Image mean;
    std::vector<Image> batches;
};

PpbRender ppb(const Scene& scene, int cap, int passes) {
    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = 3000;
    ps.seed = 22;
    ps.passes = uint64_t(passes);
    ps.maxPathLength = cap;
    PassRenderer renderer(scene, ps);
    PpbRender out{Image(kSize, kSize), {}};
    Accumulator all(kSize, kSize), batch(kSize, kSize);
    for (int p = 0; p < passes; ++p) {
        Image img = renderer.renderPass(uint64_t(p));
        all.addPass(img);
        batch.addPass(img);
        if ((p + 1) % (passes / 8) == 0) {
            out.batches.push_back(batch.mean());
            batch = Accumulator(kSize, kSize);
        }
    }
    out.mean = all.mean();
    return out;
}

/// Mean over channels and the pixels of [x0, x1) x [y0, y1).
double regionMean(const Image& img, int x0, int y0, int x1, int y1) { return test::regionMean(img, x0, y0, x1, y1); }

/// PPB's region mean against the path tracer's, within 4 combined standard errors plus `bias`
/// (relative); returns the path tracer's mean.
double expectRegionAgrees(const char* what, const PpbRender& p, const ReferenceImage& ref, int x0, int y0, int x1,
                          int y1, double bias) {
    const double n = 3.0 * (x1 - x0) * (y1 - y0);
    double refVar = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            double sd = 0;
            for (int c = 0; c < 3; ++c) sd += std::sqrt(double(ref.varianceOfMean.at(x, y)[c]));
            refVar += sd * sd / (n * n);
        }
    double m = 0, v = 0;
    for (const Image& b : p.batches) m += regionMean(b, x0, y0, x1, y1) / double(p.batches.size());
    for (const Image& b : p.batches) {
        double d = regionMean(b, x0, y0, x1, y1) - m;
        v += d * d / double(p.batches.size() * (p.batches.size() - 1));
    }
    const double r = regionMean(ref.mean, x0, y0, x1, y1);
    const double se = std::sqrt(v + refVar);
    std::printf("%s: PPB %.4f, path tracer %.4f (ratio %.4f, standard error %.4f)\n", what, m, r, m / r, se);
    EXPECT_LT(se, 0.03 * r) << what << ": too noisy to test";
    EXPECT_NEAR(m, r, 4 * se + bias * r) << what;
    return r;
}

TEST(PathLengthCap, OneSegmentIsTheEmitterSeenDirectly) {
    Scene scene = cappedRoom();
    EmbreeScene rt(scene);
    int lampMesh = -1;
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        if (scene.meshes[m].name == "lamp") lampMesh = int(m);
    ReferenceImage ref = pathTraced(scene, 1, 256);
    PpbRender p = ppb(scene, 1, 64);  // no photons at this cap: 64 passes cost little
    int dark = 0, lit = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            // 8 x 8 pinhole rays through the pixel: the fraction that meets the lamp and Le x the
            // fog's transmittance averaged over them (the pixel jitter averages the same).
            const int sub = 8;
            int hits = 0;
            Rgb expected;
            for (int j = 0; j < sub; ++j)
                for (int i = 0; i < sub; ++i) {
                    SurfaceHit hit;
                    Ray r = scene.camera.generateRay(x + (i + 0.5f) / sub, y + (j + 0.5f) / sub, kSize, kSize,
                                                     {0.5f, 0.5f});
                    if (!rt.intersect(r, &hit) || hit.mesh != lampMesh) continue;
                    ++hits;
                    for (int c = 0; c < 3; ++c) expected[c] += kLe[c] * std::exp(-kFogSigmaT[c] * hit.t) / (sub * sub);
                }
            for (int c = 0; c < 3; ++c) {
                if (hits == 0) {
                    EXPECT_EQ(ref.mean.at(x, y)[c], 0.0f) << "path tracer, pixel " << x << ", " << y;
                    EXPECT_EQ(p.mean.at(x, y)[c], 0.0f) << "PPB, pixel " << x << ", " << y;
                } else if (hits == sub * sub) {
                    const double se = std::sqrt(double(ref.varianceOfMean.at(x, y)[c]));
                    EXPECT_NEAR(ref.mean.at(x, y)[c], expected[c], 5 * se + 1e-3 * expected[c])
                        << "path tracer, pixel " << x << ", " << y;
                    EXPECT_NEAR(p.mean.at(x, y)[c], expected[c], 5e-3 * expected[c]) << "PPB, pixel " << x << ", " << y;
                }
            }
            dark += hits == 0;
            lit += hits == sub * sub;
        }
    std::printf("cap 1: %d pixels that do not see the lamp read 0, %d that see only the lamp checked\n", dark, lit);
    EXPECT_GE(lit, 4) << "the lamp should fill a few pixels";
    EXPECT_GT(dark, kSize * kSize / 2);
}

TEST(PathLengthCap, PpbAndThePathTracerAgreeAtEachCap) {
    Scene scene = cappedRoom();
    double previous = 0;
    for (int cap : {2, 3, 0}) {
        ReferenceImage ref = pathTraced(scene, cap, 512);
        PpbRender p = ppb(scene, cap, 64);
        const std::string what = "cap " + std::to_string(cap);
        const double mean = expectRegionAgrees((what + ", image").c_str(), p, ref, 0, 0, kSize, kSize, 0.03);
        const int h = kSize / 2;
        for (int q = 0; q < 4; ++q) {
            const int x0 = (q % 2) * h, y0 = (q / 2) * h;
            expectRegionAgrees((what + ", quadrant " + std::to_string(q)).c_str(), p, ref, x0, y0, x0 + h, y0 + h, 0.06);
        }
        // Each cap lets in light the one below leaves out, well beyond the tolerances above.
        if (previous > 0) {
            EXPECT_GT(mean, 1.15 * previous) << what << " adds too little to be told apart";
        }
        previous = mean;
    }
}

TEST(PathLengthCap, SettingsReadWriteAndRejectNegative) {
    RenderSettings s = RenderSettings::fromJson(nlohmann::json{{"max_path_length", 3}}, "test.json/render");
    EXPECT_EQ(s.maxPathLength, 3);
    EXPECT_EQ(s.toJson().at("max_path_length"), 3);
    EXPECT_EQ(RenderSettings().maxPathLength, 0) << "uncapped by default";
    s.maxPathLength = -1;
    EXPECT_THROW(s.validate(), Error);
    ReferenceSettings r;
    r.maxPathLength = -2;
    EXPECT_THROW(r.validate(), Error);
}

}  // namespace
}  // namespace tyndall
