// The homogeneous twin's region (loading/homogeneous_twin.h): confined to the grid's support box,
// the twin is clear air outside it and holds the grid's own amount of medium inside (exact for a
// block of voxels, Monte Carlo for the smoke plume in the room); meshes that cross the box are
// taken whole; the domain twin keeps the old global medium. An emitting grid's twin sends the
// grid's photon power, from inside its box only (a block whose density and Le vary against each
// other, and the campfire's procedural fire).
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/grid_emission.h"
#include "core/rng.h"
#include "cpu/embree_scene.h"
#include "cpu/medium_emitters.h"
#include "loading/default_scene.h"
#include "loading/default_smoke_scene.h"
#include "loading/homogeneous_twin.h"
#include "loading/scene_file.h"
#include "loading/vdb_grid.h"
#include "tests/test_scenes.h"

namespace tyndall {
namespace {

double volume(const Bounds3& b) {
    Vec3 d = b.diagonal();
    return double(d.x) * d.y * d.z;
}

/// A 4x4x4 block of voxels of value 2 (with a zero border) on anisotropic voxels 0.1 x 0.2 x 0.05,
/// its corner at `corner`, as the global medium of the test caustic box.
Scene blockScene(const Vec3& corner) {
    Scene s = test::causticScene();
    const int dims[3] = {6, 6, 6};
    std::vector<float> values(216, 0.0f);
    for (int k = 1; k <= 4; ++k)
        for (int j = 1; j <= 4; ++j)
            for (int i = 1; i <= 4; ++i) values[size_t(i + 6 * (j + 6 * k))] = 2.0f;
    s.media[0].density = VdbDensityGrid::fromDense(dims, values, Affine3::scaleTranslate({0.1f, 0.2f, 0.05f}, corner),
                                                  "block");
    s.finalize();
    s.validate();
    return s;
}

TEST(HomogeneousTwin, SupportBoxHoldsTheGridsExactMass) {
    Scene s = blockScene({0.6f, -1.2f, -1.0f});  // clear of the glass ball
    const DensityGrid& grid = *s.media[0].density;
    // 64 voxels of 2, each hat integrating to one voxel volume 0.1 * 0.2 * 0.05.
    const double mass = 64 * 2.0 * 0.1 * 0.2 * 0.05;
    EXPECT_NEAR(grid.integratedDensity(), mass, 1e-6 * mass);
    EXPECT_NEAR(integrateDensity(grid, grid.bounds()), mass, 1e-3 * mass);

    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(s, -1.0f, nullptr, TwinRegion::Support, &conv);
    twin.validate();
    ASSERT_EQ(conv.size(), 1u);
    // The box is the support: voxels 1..4 widened by one, i.e. index 0..5.
    const Bounds3 b = conv[0].box;
    EXPECT_NEAR(b.lo.x, 0.6f, 1e-5f);
    EXPECT_NEAR(b.hi.x, 0.6f + 0.5f, 1e-5f);
    EXPECT_NEAR(b.hi.y, -1.2f + 1.0f, 1e-5f);
    EXPECT_NEAR(b.hi.z, -1.0f + 0.25f, 1e-5f);
    const float d = float(mass / volume(b));
    EXPECT_NEAR(conv[0].density, d, 1e-5f * d);
    const Medium& hom = twin.media[0];
    ASSERT_TRUE(hom.homogeneous());
    EXPECT_NEAR(hom.sigmaT().r, s.media[0].sigmaT().r * d, 1e-5f * hom.sigmaT().r);
    EXPECT_NEAR(hom.albedo().g, s.media[0].albedo().g, 1e-6f);
    EXPECT_EQ(twin.globalMedium, kVacuum);
    ASSERT_EQ(twin.meshes.size(), s.meshes.size() + 1);
    EXPECT_EQ(twin.meshes.back().interiorMedium, 0);
    EXPECT_EQ(twin.meshes.back().exteriorMedium, kVacuum);
    EXPECT_EQ(twin.bounds.lo.x, s.bounds.lo.x);  // the hull lies inside the room
    // The ball sits outside the box: it is now in clear air.
    EXPECT_EQ(twin.meshes[1].exteriorMedium, kVacuum);

    // An explicit density fills the same box.
    std::vector<TwinMedium> fixed;
    makeHomogeneousTwin(s, 0.5f, nullptr, TwinRegion::Support, &fixed);
    EXPECT_EQ(fixed[0].density, 0.5f);
    EXPECT_EQ(fixed[0].box.hi.x, b.hi.x);
}

TEST(HomogeneousTwin, SupportTakesCrossingTransmissiveMeshesWhole) {
    // The block's box reaches into the glass ball (radius 0.3 at the origin).
    Scene s = blockScene({0.2f, -0.2f, -0.1f});
    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(s, -1.0f, nullptr, TwinRegion::Support, &conv);
    twin.validate();
    const Bounds3 b = conv[0].box;
    EXPECT_LE(b.lo.x, -0.3f);
    EXPECT_LE(b.lo.y, -0.3f);
    EXPECT_GE(b.hi.z, 0.29f);
    EXPECT_EQ(twin.meshes[1].exteriorMedium, 0);  // the ball now sits in the twin's medium
    EXPECT_EQ(twin.meshes[1].interiorMedium, kVacuum);
    // The mass is the same; the box is larger, so the mean is lower.
    const double mass = 64 * 2.0 * 0.1 * 0.2 * 0.05;
    EXPECT_NEAR(conv[0].density * volume(b), mass, 1e-5 * mass);
}

TEST(HomogeneousTwin, PlumeInARoomIsClearAirOutsideItsSupport) {
    Scene smoke = makeDefaultSmokeScene();
    const Medium& grid = smoke.media[smoke.globalMedium];
    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(smoke, -1.0f, nullptr, TwinRegion::Support, &conv);
    twin.validate();
    ASSERT_EQ(conv.size(), 1u);
    const Bounds3 box = conv[0].box;
    const MediumId id = conv[0].medium;
    // The box is the plume's support box grown only to take the glass ball whole; it is much
    // smaller than the room.
    const Bounds3 support = grid.density->bounds();
    std::printf("support box %.3f, twin box %.3f, room %.3f (world units^3)\n", volume(support), volume(box),
                volume(smoke.bounds));
    EXPECT_LT(volume(box), 0.25 * volume(smoke.bounds));
    const TriangleMesh& ball = twin.meshes[8];
    ASSERT_EQ(ball.name, "glass sphere");
    EXPECT_EQ(ball.exteriorMedium, id);

    // Random points in the room, asked the way the renderer asks (EmbreeScene::mediumAt): where
    // the grid scene has its medium, the twin has its own inside the box and clear air outside
    // it, and every point with density lies inside; elsewhere (inside the glass ball) the two
    // scenes agree.
    EmbreeScene rtGrid(smoke), rtTwin(twin);
    Rng rng(2026, 24);
    const Vec3 lo = smoke.bounds.lo, ext = smoke.bounds.diagonal();
    int inside = 0, outside = 0, withDensity = 0, other = 0;
    for (int i = 0; i < 4000; ++i) {
        Vec3 p = lo + Vec3(rng.uniform() * ext.x, rng.uniform() * ext.y, rng.uniform() * ext.z);
        const MediumId was = rtGrid.mediumAt(p), m = rtTwin.mediumAt(p);
        if (was != id) {
            ++other;
            EXPECT_EQ(m, was);
            continue;
        }
        if (grid.density->density(p) > 0) {
            ++withDensity;
            EXPECT_TRUE(box.contains(p)) << "at " << p.x << " " << p.y << " " << p.z;
        }
        if (box.contains(p)) {
            ++inside;
            EXPECT_EQ(m, id);
        } else {
            ++outside;
            EXPECT_EQ(m, kVacuum) << "at " << p.x << " " << p.y << " " << p.z;
        }
    }
    EXPECT_GT(other, 5);
    EXPECT_GT(withDensity, 50);
    EXPECT_GT(inside, 200);
    EXPECT_GT(outside, 2000);
    // Mean extinction inside the box: stratified Monte Carlo over the box (64^3 strata).
    const Vec3 bl = box.lo, be = box.diagonal();
    const int n = 64;
    double sum = 0;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                sum += grid.density->density(bl + Vec3((i + rng.uniform()) / n * be.x, (j + rng.uniform()) / n * be.y,
                                                       (k + rng.uniform()) / n * be.z));
    const double mcMean = sum / (double(n) * n * n);
    const Medium& hom = twin.media[size_t(id)];
    std::printf("mean density over the box: twin %.5f, Monte Carlo %.5f, over active voxels %.5f\n", conv[0].density,
                mcMean, grid.density->meanDensity());
    EXPECT_NEAR(conv[0].density, mcMean, 0.01 * mcMean);
    EXPECT_NEAR(hom.sigmaT().r, grid.sigmaT().r * mcMean, 0.01 * hom.sigmaT().r);
}

/// Mean photon power of `e` over `n` photons with its standard error, per channel; `box`, when not
/// empty, must hold every photon that carries power (`*outside` counts those that do not).
void meanPower(const MediumEmitters& e, int n, Rgb* mean, Rgb* se, const Bounds3& box = {}, int* outside = nullptr) {
    Rng rng(2026, 12);
    double sum[3] = {}, sum2[3] = {};
    for (int i = 0; i < n; ++i) {
        const MediumEmitters::Photon ph = e.sample(rng);
        if (outside && !ph.power.isBlack() && !box.contains(ph.ray.o)) ++*outside;
        for (int c = 0; c < 3; ++c) sum[c] += ph.power[c], sum2[c] += double(ph.power[c]) * ph.power[c];
    }
    for (int c = 0; c < 3; ++c) {
        const double m = sum[c] / n;
        (*mean)[c] = float(m);
        (*se)[c] = float(std::sqrt(std::max(0.0, sum2[c] / n - m * m) / n));
    }
}

/// The twin of the emitting grid medium `grid` (the global medium of `s`): its Le is constant
/// and its photons' power, all from inside the support box, is the grid's photon power: the
/// closed form 4 pi sigma_a Le x the box's volume against the grid's photons (Monte Carlo), and
/// the twin's own photons against that closed form. Returns the twin's medium.
Medium checkTwinPower(const Scene& s, const char* what, double tolerance) {
    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(s, -1.0f, nullptr, TwinRegion::Support, &conv);
    twin.validate();
    const Medium& hom = twin.media[size_t(conv[0].medium)];
    EXPECT_TRUE(hom.homogeneous() && hom.emissive() && !hom.emissionField) << what;
    EXPECT_EQ(hom.constantEmission().r, conv[0].emission.r * hom.emissionScale) << what;
    const Bounds3 box = conv[0].box;
    const Rgb closed = hom.sigmaA * hom.constantEmission() * float(4 * kPi * volume(box));

    EmbreeScene rtGrid(s), rtTwin(twin);
    MediumEmitters grid(rtGrid), hull(rtTwin);
    Rgb gridMean, gridSe, twinMean, twinSe;
    meanPower(grid, 100000, &gridMean, &gridSe);
    int outside = 0;
    meanPower(hull, 20000, &twinMean, &twinSe, box, &outside);
    EXPECT_EQ(outside, 0) << what << ": twin photons with power outside the support box";
    for (int c = 0; c < 3; ++c) {
        std::printf("%s, channel %d: grid photons %.5g +- %.2g, twin closed form %.5g, twin photons %.5g\n", what, c,
                    gridMean[c], gridSe[c], closed[c], twinMean[c]);
        EXPECT_NEAR(closed[c], gridMean[c], 4 * gridSe[c] + tolerance * gridMean[c]) << what << " channel " << c;
        EXPECT_NEAR(twinMean[c], closed[c], 4 * twinSe[c] + 1e-4f * closed[c]) << what << " channel " << c;
    }
    return hom;
}

TEST(HomogeneousTwin, EmittingTwinSendsTheGridsPowerFromItsBoxOnly) {
    // A 4x4x4 block (clear of the glass ball) whose density rises along x (1..4) while its Le falls
    // (colour grid 4..1 x (1, 0.5, 0.25) x 3): the plain mean of Le over the voxels is not the
    // density-weighted mean the power needs.
    Scene s = blockScene({0.6f, -1.2f, -1.0f});
    const int dims[3] = {6, 6, 6};
    std::vector<float> density(216, 0.0f), le(216, 0.0f);
    for (int k = 1; k <= 4; ++k)
        for (int j = 1; j <= 4; ++j)
            for (int i = 1; i <= 4; ++i) {
                density[size_t(i + 6 * (j + 6 * k))] = float(i);
                le[size_t(i + 6 * (j + 6 * k))] = float(5 - i);
            }
    const Affine3 xf = Affine3::scaleTranslate({0.1f, 0.2f, 0.05f}, {0.6f, -1.2f, -1.0f});
    Medium& m = s.media[0];
    m.sigmaS = Rgb(0.3f);
    m.sigmaA = Rgb(0.2f);
    m.density = VdbDensityGrid::fromDense(dims, density, xf, "block");
    m.emissionField = std::make_shared<GridEmission>(VdbDensityGrid::fromDense(dims, le, xf, "le"),
                                                     Rgb(1.0f, 0.5f, 0.25f), 3.0f);
    m.emissionScale = 0.5f;  // kept by the twin, not folded into its Le
    s.lights.clear();
    s.finalize();
    s.validate();
    const Medium hom = checkTwinPower(s, "block", 2e-3);
    EXPECT_EQ(hom.emissionScale, 0.5f);

    // Outside the box the twin is clear air: nothing there emits (room points, as the renderer
    // asks for the medium at a point).
    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(s, -1.0f, nullptr, TwinRegion::Support, &conv);
    EmbreeScene rt(twin);
    Rng rng(7, 3);
    int outside = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 e = s.bounds.diagonal();
        const Vec3 p = s.bounds.lo + Vec3(rng.uniform() * e.x, rng.uniform() * e.y, rng.uniform() * e.z);
        if (conv[0].box.contains(p)) continue;
        ++outside;
        EXPECT_EQ(rt.mediumAt(p), kVacuum) << "at " << p.x << " " << p.y << " " << p.z;
    }
    EXPECT_GT(outside, 1500);
}

TEST(HomogeneousTwin, CampfireTwinSendsTheFiresPower) {
    SceneFile f = loadSceneFile(std::string(TYNDALL_SOURCE_DIR) + "/scenes/campfire.json");
    f.scene.validate();
    checkTwinPower(f.scene, "campfire", 1e-2);
}

TEST(HomogeneousTwin, DomainKeepsTheGlobalMediumAtTheActiveMean) {
    Scene smoke = makeDefaultSmokeScene();
    const Medium& grid = smoke.media[smoke.globalMedium];
    std::vector<TwinMedium> conv;
    Scene twin = makeHomogeneousTwin(smoke, -1.0f, nullptr, TwinRegion::Domain, &conv);
    EXPECT_EQ(twin.globalMedium, smoke.globalMedium);
    EXPECT_EQ(twin.meshes.size(), smoke.meshes.size());
    EXPECT_TRUE(conv[0].box.empty());
    EXPECT_FLOAT_EQ(conv[0].density, grid.density->meanDensity());
}

TEST(HomogeneousTwin, RegionNames) {
    EXPECT_EQ(parseTwinRegion("support"), TwinRegion::Support);
    EXPECT_EQ(parseTwinRegion("domain"), TwinRegion::Domain);
    EXPECT_STREQ(twinRegionName(TwinRegion::Domain), "domain");
    EXPECT_THROW(parseTwinRegion("box"), Error);
}

}  // namespace
}  // namespace tyndall
