// The CPU beam rasterizer must find exactly the beam x pixel pairs that brute force finds: its
// footprints may over-cover but never miss. Checked on real passes of the default scene and on
// adversarial beams (end-on, through and behind the camera, grazing the frustum, thin lens).
#include "cpu/beam_rasterizer.h"

#include <gtest/gtest.h>

#include "loading/default_scene.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "cpu/pass_renderer.h"

using namespace tyndall;

namespace {

// Exact equality: both sum a pixel's beams in beam-index order with the same arithmetic (the
// scalar kernel; tests/cpu/beam_splat_simd_test.cpp holds the SIMD one to it).
void expectSameImage(const Image& a, const Image& b, const char* what) {
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    size_t differing = 0, nonZero = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            if (a.pixels[i][c] != b.pixels[i][c]) ++differing;
            if (b.pixels[i][c] != 0) ++nonZero;
        }
    }
    EXPECT_EQ(differing, 0u) << what;
    EXPECT_GT(nonZero, 0u) << what << ": the comparison saw no beam at all";
}

PrimarySegments primaryRays(const Scene& scene, int w, int h, float tMax, uint64_t seed) {
    PrimarySegments p;
    p.width = w;
    p.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            Rng rng = Rng::forKey(seed, 0, uint64_t(y) * w + x, StreamPurpose::Test);
            float jx = rng.uniform(), jy = rng.uniform();
            Vec2 lens{rng.uniform(), rng.uniform()};
            Ray r = scene.camera.generateRay(float(x) + jx, float(y) + jy, w, h, lens);
            p.rays.push_back(PrimaryRay{r.o, tMax, r.d, 0});
        }
    return p;
}

Scene fogScene(const Camera& camera) {
    Scene s;
    s.name = "raster-test";
    s.source = "<test>";
    Medium fog;
    fog.sigmaS = Rgb(0.3f, 0.4f, 0.5f);
    fog.sigmaA = Rgb(0.05f);
    fog.g = 0.4f;
    s.media.push_back(fog);
    s.globalMedium = 0;
    s.camera = camera;
    return s;
}

}  // namespace

TEST(BeamRasterizer, MatchesBruteForceOnDefaultScenePasses) {
    Scene scene = makeDefaultScene();
    RenderSettings settings;
    settings.width = 80;
    settings.height = 60;
    settings.photonsPerPass = 300;
    PassRenderer renderer(scene, settings);
    BeamRasterizer raster(scene, SplatKernel::Scalar);
    for (uint64_t pass : {0ull, 40ull}) {
        PhotonMap photons = renderer.tracePhotons(pass);
        CameraPassResult camera = renderer.traceCamera(pass, photons);
        expectSameImage(raster.rasterize(camera.primary, photons), raster.bruteForce(camera.primary, photons),
                        pass == 0 ? "pass 0" : "pass 40");
    }
}

TEST(BeamRasterizer, MatchesBruteForceOnAdversarialBeams) {
    for (float lensRadius : {0.0f, 0.15f}) {
        Camera cam = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.2f);
        cam.lensRadius = lensRadius;
        cam.focusDistance = 2.0f;
        Scene scene = fogScene(cam);
        const int w = 48, h = 36;
        PrimarySegments primary = primaryRays(scene, w, h, 8.0f, 3);
        PhotonMap photons;
        Rng rng(11, 5);
        auto add = [&](Vec3 o, Vec3 d, float len, float r) {
            PhotonBeam b;
            b.origin = o;
            b.dir = normalize(d);
            b.tMax = len;
            b.radius = r;
            b.power = Rgb(1.0f, 0.5f, 0.25f);
            b.medium = 0;
            photons.beams.push_back(b);
        };
        add({0, 0, -3}, {0, 0, 1}, 2.9f, 0.05f);         // end-on, pointing at the camera
        add({0.01f, 0, -1}, {0, 0, 1}, 5.0f, 0.08f);     // through and behind the camera
        add({-5, 0.02f, 0.05f}, {1, 0, 0}, 10.0f, 0.1f); // crossing just in front of the lens plane
        add({-5, 0, -0.3f}, {1, 0, 0}, 10.0f, 0.2f);     // close, wide, lateral
        add({0, 0, -6}, {0.8f, 0.5f, 0.2f}, 9.0f, 0.3f); // leaves the frustum sideways
        add({3, 3, -2}, {-1, -1, -0.1f}, 4.0f, 0.02f);   // grazes the frustum corner
        add({0, 0, 1}, {0, 0, 1}, 3.0f, 0.5f);           // entirely behind the camera
        for (int i = 0; i < 300; ++i) {                  // random beams around and behind the camera
            Vec3 o{rng.uniform() * 8 - 4, rng.uniform() * 8 - 4, rng.uniform() * 8 - 6};
            add(o, sampleUniformSphere(rng.uniform(), rng.uniform()), rng.uniform() * 6, 0.01f + rng.uniform() * 0.3f);
        }
        BeamRasterizer raster(scene, SplatKernel::Scalar);
        expectSameImage(raster.rasterize(primary, photons), raster.bruteForce(primary, photons),
                        lensRadius > 0 ? "thin lens" : "pinhole");
    }
}

TEST(BeamRasterizer, RowSpanContainsEveryPointOfTheTaperedCapsule) {
    Rng rng(5, 9);
    for (int trial = 0; trial < 2000; ++trial) {
        BeamFootprint fp;
        fp.visible = true;
        fp.ax = rng.uniform() * 100, fp.ay = rng.uniform() * 100, fp.ra = rng.uniform() * 20;
        fp.bx = rng.uniform() * 100, fp.by = rng.uniform() * 100, fp.rb = rng.uniform() * 20;
        if (trial % 7 == 0) fp.bx = fp.ax, fp.by = fp.ay + rng.uniform();  // nearly degenerate
        for (int k = 0; k < 50; ++k) {
            // A random point of the hull: on a random disc of the segment between the two ends.
            float t = rng.uniform(), ang = rng.uniform() * 2 * kPi, rad = std::sqrt(rng.uniform());
            float cx = fp.ax + t * (fp.bx - fp.ax), cy = fp.ay + t * (fp.by - fp.ay);
            float r = fp.ra + t * (fp.rb - fp.ra);
            float px = cx + r * rad * std::cos(ang) * 0.999f, py = cy + r * rad * std::sin(ang) * 0.999f;
            float x0, x1;
            ASSERT_TRUE(footprintRowSpan(fp, py, &x0, &x1)) << "trial " << trial;
            ASSERT_LE(x0, px + 1e-3f) << "trial " << trial;
            ASSERT_GE(x1, px - 1e-3f) << "trial " << trial;
        }
        // And the span is not wildly larger than the hull's extent.
        float x0, x1;
        if (footprintRowSpan(fp, fp.ay, &x0, &x1)) {
            EXPECT_GE(x0, std::min(fp.ax - fp.ra, fp.bx - fp.rb) - 1e-3f);
            EXPECT_LE(x1, std::max(fp.ax + fp.ra, fp.bx + fp.rb) + 1e-3f);
        }
    }
}

TEST(BeamRasterizer, FastEvaluatorAgreesWithTheCoreEstimator) {
    // The rasterizer's hoisted, u^2-only evaluator against intersectBeamRay + beamRadiance, per
    // pixel, for a chromatic and a grey medium and g of both signs.
    for (int variant = 0; variant < 2; ++variant) {
        Camera cam = Camera::lookAt({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.0f);
        Scene scene = fogScene(cam);
        if (variant == 1) {
            scene.media[0].sigmaS = Rgb(0.2f);
            scene.media[0].sigmaA = Rgb(0.1f);
            scene.media[0].g = -0.6f;
        }
        const int w = 40, h = 30;
        PrimarySegments primary = primaryRays(scene, w, h, 6.0f, 5);
        PhotonMap photons;
        Rng rng(21, 2);
        for (int i = 0; i < 200; ++i) {
            PhotonBeam b;
            b.origin = {rng.uniform() * 4 - 2, rng.uniform() * 4 - 2, -rng.uniform() * 5};
            b.dir = sampleUniformSphere(rng.uniform(), rng.uniform());
            b.tMax = rng.uniform() * 4;
            b.radius = 0.02f + 0.2f * rng.uniform();
            b.power = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
            b.medium = 0;
            photons.beams.push_back(b);
        }
        Image fast = BeamRasterizer(scene).bruteForce(primary, photons);
        const Medium& m = scene.media[0];
        double maxRel = 0;
        int lit = 0;
        for (size_t p = 0; p < primary.rays.size(); ++p) {
            Rgb ref;
            const PrimaryRay& ray = primary.rays[p];
            for (const PhotonBeam& b : photons.beams) {
                BeamRayHit hit;
                if (!intersectBeamRay(ray.origin, ray.dir, ray.tMax, b, &hit)) continue;
                ref += beamRadiance(hit, b, m.sigmaS, m.g, m.transmittance(hit.s), m.transmittance(hit.t));
            }
            if (ref.maxComponent() <= 0) {
                EXPECT_EQ(fast.pixels[p].maxComponent(), 0.0f);
                continue;
            }
            ++lit;
            for (int c = 0; c < 3; ++c) maxRel = std::max(maxRel, std::abs(double(fast.pixels[p][c]) / ref[c] - 1.0));
        }
        EXPECT_GT(lit, 200);
        EXPECT_LT(maxRel, 2e-5) << "variant " << variant;
    }
}
