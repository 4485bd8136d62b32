// A pass is a pure function of (scene, settings, seed, pass index): any thread count, any order
// of passes, gives bit-identical pass images; and the beam radius really shrinks in the renderer
// along the per-path schedule (not only in the schedule function).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "loading/default_scene.h"
#include "loading/default_smoke_scene.h"

#include <algorithm>
#include <cstring>
#include "cpu/pass_renderer.h"
#include "tests/test_scenes.h"
#include "tests/test_util.h"

using namespace tyndall;

TEST(Determinism, PassImagesDoNotDependOnThreadsOrOrder) {
    Scene scene = makeDefaultScene();
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.photonsPerPass = 400;
    s.seed = 77;
    PassRenderer renderer(scene, s);
    Image pass3Many = renderer.renderPass(3);
    Image pass7Many = renderer.renderPass(7);
    Image pass3One;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        (void)renderer.renderPass(7);  // a different order first
        pass3One = renderer.renderPass(3);
    }
    EXPECT_TRUE(test::identicalImages(pass3Many, pass3One));
    EXPECT_FALSE(test::identicalImages(pass3Many, pass7Many));
    RenderSettings other = s;
    other.seed = 78;
    PassRenderer renderer2(scene, other);
    EXPECT_FALSE(test::identicalImages(pass3Many, renderer2.renderPass(3)));
}

TEST(Determinism, RadiusShrinksPerPhotonPathInTheRenderer) {
    Scene scene = test::causticScene();
    RenderSettings s;
    s.photonsPerPass = 100;
    s.alpha = 0.5;
    s.radius = 0.05f;
    s.radiusOffset = 1000;
    s.scatteredBeamMfp = 0;  // every beam the schedule's radius (the wider beams after a scattering: ScatteredBeams.*)
    PassRenderer renderer(scene, s);
    PhotonMap first = renderer.tracePhotons(0), later = renderer.tracePhotons(200);
    ASSERT_FALSE(first.beams.empty());
    ASSERT_FALSE(later.beams.empty());
    float rFirst = first.beams.front().radius, rLater = later.beams.front().radius;
    EXPECT_NEAR(rFirst, 0.05f, 0.05f * 0.06f);  // path 0..: within the first path's ~5% drift
    RadiusSchedule schedule(s.alpha, s.radiusOffset);
    // The beams of pass 200 come from paths 20000..20099; each uses its own path's factor.
    EXPECT_GE(rLater, float(0.05 * schedule.beamFactor(20099)) * 0.9999f);
    EXPECT_LE(rLater, float(0.05 * schedule.beamFactor(20000)) * 1.0001f);
    EXPECT_LT(rLater, 0.4f * rFirst);
    // Surface photons: the same two-sided window on their own (2D) schedule. One-sided, a surface
    // radius that never shrank from a smaller start, or shrank twice as fast, would pass.
    ASSERT_FALSE(later.surfacePhotons.empty());
    const float surfaceRadius = renderer.radii().surfaceRadius;
    for (const SurfacePhoton& p : later.surfacePhotons) {
        ASSERT_GE(p.radius, surfaceRadius * float(schedule.surfaceFactor(20099)) * 0.9999f);
        ASSERT_LE(p.radius, surfaceRadius * float(schedule.surfaceFactor(20000)) * 1.0001f);
    }
    ASSERT_FALSE(first.surfacePhotons.empty());
    EXPECT_NEAR(first.surfacePhotons.front().radius, surfaceRadius, surfaceRadius * 0.06f);
}

// CameraTracer recycles the primary hits, rays and stored free flights of finished passes: a
// pass traced into another pass's buffers (different image size too) equals a fresh renderer's.
TEST(Determinism, RecycledPassBuffersCarryNothingOver) {
    Scene scene = makeDefaultSmokeScene();  // a grid medium: stored free flights per pixel
    RenderSettings s;
    s.width = 48;
    s.height = 40;
    s.photonsPerPass = 300;
    s.seed = 5;
    PassRenderer fresh(scene, s);
    const Image want = fresh.renderPass(2);
    PassRenderer reused(scene, s);
    (void)reused.renderPass(5);
    (void)reused.renderPass(6);
    EXPECT_TRUE(test::identicalImages(want, reused.renderPass(2)));
    {
        const PrimaryPass a = reused.tracePrimary(4);  // held while the next one is traced
        const PrimaryPass b = reused.tracePrimary(2);
        const PrimaryPass c = fresh.tracePrimary(2);
        ASSERT_EQ(b.segments.rays.size(), c.segments.rays.size());
        ASSERT_EQ(b.segments.freeFlights.size(), c.segments.freeFlights.size());
        EXPECT_GT(b.segments.freeFlights.size(), 0u);
        EXPECT_EQ(0, std::memcmp(b.segments.rays.data(), c.segments.rays.data(),
                                 b.segments.rays.size() * sizeof(PrimaryRay)));
        EXPECT_EQ(0, std::memcmp(b.segments.freeFlights.data(), c.segments.freeFlights.data(),
                                 b.segments.freeFlights.size() * sizeof(float)));
        EXPECT_GT(std::count_if(b.segments.freeFlights.begin(), b.segments.freeFlights.end(),
                                [](float f) { return f < kInfinity; }),
                  100);  // collisions in the smoke: finite distances the next pass's buffer holds
    }
    // The camera moves out of the smoke (the viewer's reset): rays that meet no grid medium store
    // no distances (all infinite), whatever the recycled buffer held.
    scene.camera.position = Vec3(1e4f);
    const PrimaryPass out = reused.tracePrimary(3);
    for (size_t p = 0; p < out.segments.rays.size(); ++p) ASSERT_EQ(out.segments.rays[p].medium, kVacuum);
    for (float f : out.segments.freeFlights) ASSERT_EQ(f, kInfinity);
}

// The beam BVH's pieces per beam follow the pixels whose camera ray meets a non-diffuse surface
// first (BeamBvh::piecesFor): tracePrimary counts them while it traces, in parallel; the count
// must be the hits' own at any thread count, with and without a render region.
TEST(Determinism, NonDiffuseHitsCountedWhileTracingAreTheHitsCount) {
    Scene scene = makeDefaultScene();
    for (bool region : {false, true}) {
        RenderSettings s;
        s.width = 96;
        s.height = 72;
        s.photonsPerPass = 100;
        s.seed = 3;
        if (region) s.region = PixelRegion{13, 9, 50, 31};
        PassRenderer renderer(scene, s);
        for (int threads : {1, 2, 4}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
            const PrimaryPass primary = renderer.tracePrimary(uint64_t(threads));
            uint64_t want = 0, surface = 0;
            for (const PrimaryHit& ph : *primary.hits) {
                surface += ph.surface;
                want += ph.surface && scene.materials[size_t(scene.meshes[size_t(ph.hit.mesh)].material)].type !=
                                          MaterialType::Diffuse;
            }
            EXPECT_GT(want, 50u) << "the glass sphere fills part of the image";
            EXPECT_LT(want, surface) << "the box's diffuse walls do not count";
            EXPECT_EQ(primary.nonDiffuseHits, want) << threads << " threads, region " << region;
        }
    }
}

// The viewer edits lights in place and calls sceneChanged(): the next pass must be the pass of a
// renderer built on the edited scene, shadow rays included (their light choice follows the powers;
// a sampler built once never picks a light edited up from zero power). Explicit radii: the
// automatic ones are planned from the lights at construction.
TEST(Determinism, LightsEditedInPlaceGiveTheImageOfAFreshRenderer) {
    Scene scene = makeDefaultScene();
    ASSERT_GE(scene.lights.size(), 2u);
    const Rgb fill = scene.lights[1].intensity;
    scene.lights[1].intensity = Rgb(0.0f);
    RenderSettings s;
    s.width = 48;
    s.height = 40;
    s.photonsPerPass = 300;
    s.seed = 9;
    s.radius = 0.05f;
    s.surfaceRadius = 0.1f;
    s.radiusOffset = 1000;
    s.photonAngle = 0.0f;
    PassRenderer edited(scene, s);
    (void)edited.renderPass(0);
    scene.lights[0].intensity = scene.lights[0].intensity * 0.25f;
    scene.lights[1].intensity = fill * 4.0f;
    scene.lights[1].position = scene.lights[1].position + Vec3(0.3f, -0.2f, 0.1f);
    edited.sceneChanged();
    Image afterEdit = edited.renderPass(2);
    PassRenderer fresh(scene, s);
    EXPECT_TRUE(test::identicalImages(afterEdit, fresh.renderPass(2)));
}
