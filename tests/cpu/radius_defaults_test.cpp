// The automatic radii (cpu/radius_defaults.h, cpu/pixel_footprint.h): the footprint they are
// measured in, the radius in pixels at the end of the planned budget, scale independence, and
// that explicit settings keep their meaning. Quick: no rendering beyond a few tiny passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/radius_schedule.h"
#include "cpu/beam_cone.h"
#include "cpu/pass_renderer.h"
#include "cpu/photon_tracer.h"
#include "cpu/pixel_footprint.h"
#include "cpu/radius_defaults.h"
#include "loading/mesh_builders.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

/// A tunnel of fog: the camera at z = 0 looks down -z at a back wall `depth` away that fills the
/// whole view (the side walls are 10 away), everything inside filled with a global fog. Scaled by
/// `scale` (positions and depth).
Scene fogTunnel(float depth, float scale = 1.0f, bool fog = true) {
    Scene s;
    s.name = "fog-tunnel";
    s.source = "<test>";
    Material wall;
    wall.name = "wall";
    wall.albedo = Rgb(0.5f);
    s.materials = {wall};
    if (fog) {
        Medium m;
        m.name = "fog";
        m.sigmaS = Rgb(0.1f / scale);
        s.media.push_back(m);
        s.globalMedium = 0;
    }
    s.meshes.push_back(makeBox("tunnel", Vec3(-10, -10, -depth) * scale, Vec3(10, 10, 1) * scale, 0, true));
    Light l;
    l.name = "bulb";
    l.type = LightType::Point;
    l.position = Vec3(0.3f, 0.5f, -0.5f * depth) * scale;
    l.intensity = Rgb(scale * scale);
    s.lights.push_back(l);
    s.camera = Camera::lookAt(Vec3(0, 0, 0), Vec3(0, 0, -1) * scale, {0, 1, 0}, 1.0f);
    s.finalize();
    return s;
}

double footprintAt(double depth, const Scene& s, int height) {
    return depth * 2.0 * std::tan(0.5 * s.camera.yFov) / height;
}

TEST(PixelFootprint, MatchesThePinholeFootprintAtTheMediaAndSurfaceDepths) {
    Scene s = fogTunnel(4.0f);
    EmbreeScene rt(s);
    PixelFootprint f = measurePixelFootprint(rt, s.camera, 200, 100);
    // Every ray ends on the back wall at view depth 4; the fog between fills depths 0..4
    // uniformly on every ray, so its weighted median depth is 2 (within the 1/32 sampling step).
    EXPECT_NEAR(f.surface, footprintAt(4.0, s, 100), 1e-4 * footprintAt(4.0, s, 100));
    EXPECT_NEAR(f.media, footprintAt(2.0, s, 100), 0.04 * footprintAt(2.0, s, 100));
    EXPECT_DOUBLE_EQ(f.mediaFraction, 1.0);

    Scene clear = fogTunnel(4.0f, 1.0f, false);
    EmbreeScene rtClear(clear);
    PixelFootprint g = measurePixelFootprint(rtClear, clear.camera, 200, 100);
    EXPECT_EQ(g.media, 0.0) << "no medium in view";
    EXPECT_DOUBLE_EQ(g.beam(7.0), g.surface) << "the beam radius falls back to the surfaces' footprint";
}

/// The beam radius of the last planned photon path over the media footprint.
double endRadiusInFootprints(const Scene& s, const RenderSettings& in) {
    PassRenderer r(s, in);
    EmbreeScene rt(s);
    double fp = measurePixelFootprint(rt, s.camera, in.width, in.height).media;
    return r.radii().beamRadiusOf(r.settings().plannedPaths - 1) / fp;
}

TEST(RadiusDefaults, BeamRadiusEndsThePlannedBudgetAtThePixelFootprint) {
    Scene s = fogTunnel(4.0f);
    for (uint64_t passes : {1ull, 30ull, 2000ull}) {
        RenderSettings in;
        in.width = 64;
        in.height = 48;
        in.photonsPerPass = 1000;
        in.passes = passes;
        PassRenderer r(s, in);
        const RenderSettings& out = r.settings();
        EXPECT_EQ(out.plannedPaths, passes * 1000);
        double end = endRadiusInFootprints(s, in);
        EXPECT_NEAR(end, RadiusDefaults::kBeamEndFootprints, 0.02 * RadiusDefaults::kBeamEndFootprints)
            << passes << " passes";
        // The first radius is kStartOverEnd times the end radius (the offset rounds to a path).
        EXPECT_NEAR(out.radius / r.radii().beamRadiusOf(out.plannedPaths), RadiusDefaults::kStartOverEnd, 0.05);
        // The surface radius ends at kSurfaceEndFootprints surface footprints.
        EmbreeScene rt(s);
        double fs = measurePixelFootprint(rt, s.camera, in.width, in.height).surface;
        EXPECT_NEAR(r.radii().surfaceRadiusOf(out.plannedPaths) / fs, RadiusDefaults::kSurfaceEndFootprints, 0.05);
    }
    // The planted bug this guards against: the old scene-relative default (0.5% of the diagonal,
    // offset 1000) ends 2000 passes of 1000 paths at a small fraction of a pixel.
    RenderSettings legacy;
    legacy.width = 64;
    legacy.height = 48;
    legacy.photonsPerPass = 1000;
    legacy.passes = 2000;
    legacy.radius = 0.005f * length(s.bounds.diagonal());
    legacy.radiusOffset = 1000;
    EXPECT_LT(endRadiusInFootprints(s, legacy), 0.5);
}

TEST(RadiusDefaults, AnUnboundedPassCountIsOpenEnded) {
    // The viewer renders "until stopped" with passes = 2^64 - 1: the plan must not overflow.
    RenderSettings s;
    s.width = 40;
    s.height = 30;
    s.passes = ~uint64_t(0);
    EXPECT_EQ(plannedPhotonPaths(s), RadiusDefaults::kOpenEndedPathsPerPixel * 1200);
    s.passes = 10;
    EXPECT_EQ(plannedPhotonPaths(s), 10u * s.photonsPerPass);
    s.timeBudget = 5;
    EXPECT_EQ(plannedPhotonPaths(s), RadiusDefaults::kOpenEndedPathsPerPixel * 1200);
}

TEST(RadiusDefaults, AreScaleFreeAndFollowTheImageSize) {
    RenderSettings in;
    in.width = 64;
    in.height = 48;
    in.photonsPerPass = 500;
    in.passes = 10;
    Scene a = fogTunnel(4.0f), b = fogTunnel(4.0f, 100.0f);
    RenderSettings ra = PassRenderer(a, in).settings(), rb = PassRenderer(b, in).settings();
    EXPECT_EQ(ra.radiusOffset, rb.radiusOffset) << "the schedule does not depend on the scene's units";
    EXPECT_NEAR(rb.radius / ra.radius, 100.0, 0.5);
    EXPECT_NEAR(rb.surfaceRadius / ra.surfaceRadius, 100.0, 0.5);
    RenderSettings big = in;
    big.width = 128;
    big.height = 96;
    big.plannedPaths = in.passes * in.photonsPerPass;  // the same plan, twice the resolution
    RenderSettings rbig = PassRenderer(a, big).settings();
    EXPECT_NEAR(rbig.radius / ra.radius, 0.5, 0.02) << "half the footprint, half the radius";
}

TEST(RadiusDefaults, ExplicitSettingsKeepTheirMeaning) {
    Scene s = fogTunnel(4.0f);
    RenderSettings in;
    in.width = 32;
    in.height = 32;
    in.radius = 0.03f;
    in.surfaceRadius = 0.1f;
    in.radiusOffset = 1000;
    in.alpha = 0.7;
    PassRenderer r(s, in);
    EXPECT_EQ(r.settings().radius, 0.03f);
    EXPECT_EQ(r.settings().surfaceRadius, 0.1f);
    EXPECT_EQ(r.settings().radiusOffset, 1000u);
    EXPECT_EQ(r.settings().plannedPaths, 0u) << "nothing automatic, nothing planned";
    RadiusSchedule schedule(0.7, 1000);
    EXPECT_EQ(r.radii().beamRadiusOf(12345), float(0.03 * schedule.beamFactor(12345)));
    // An explicit offset with automatic radii: the radii start at kStartOverEnd end footprints.
    RenderSettings offsetOnly;
    offsetOnly.width = 32;
    offsetOnly.height = 32;
    offsetOnly.radiusOffset = 77;
    PassRenderer ro(s, offsetOnly);
    EXPECT_EQ(ro.settings().radiusOffset, 77u);
    EmbreeScene rt(s);
    double fp = measurePixelFootprint(rt, s.camera, 32, 32).media;
    EXPECT_NEAR(ro.settings().radius / fp, RadiusDefaults::kStartOverEnd * RadiusDefaults::kBeamEndFootprints, 1e-3);
}

TEST(RadiusDefaults, ResolvedSettingsReproduceTheImageBitForBit) {
    Scene s = fogTunnel(4.0f);
    RenderSettings in;
    in.width = 24;
    in.height = 16;
    in.photonsPerPass = 200;
    in.passes = 3;
    PassRenderer automatic(s, in);
    RenderSettings resolved = RenderSettings::fromJson(automatic.settings().toJson(), "resolved");
    PassRenderer replay(s, resolved);
    EXPECT_FALSE(hasAutomaticRadii(resolved));
    for (uint64_t pass : {0ull, 2ull})
        EXPECT_TRUE(test::identicalImages(automatic.renderPass(pass), replay.renderPass(pass))) << pass;
}

TEST(RadiusDefaults, ThePhotonConeIsOnForALightInViewAndShapesTheBeams) {
    // The point light in view at depth 0.5, the fog's median depth 2: the kernel at the end of the
    // plan is wider than the light's own pixel (kConeMinLightFootprints), so the cone is on.
    Scene s = fogTunnel(4.0f);
    s.lights[0].position = Vec3(0.1f, 0.15f, -0.5f);
    s.finalize();
    RenderSettings in;
    in.width = 48;
    in.height = 32;
    in.photonsPerPass = 300;
    in.passes = 20;
    in.equiangular = false;  // the beams that start at the light are what the cone shapes
    PassRenderer r(s, in);
    const RenderSettings& out = r.settings();
    const double endFactor = RadiusSchedule(out.alpha, out.radiusOffset).beamFactor(out.plannedPaths);
    EXPECT_NEAR(out.photonAngle * endFactor, photonConeAngle(out.plannedPaths), 1e-6)
        << "the automatic angle at the end of the plan";
    const double reach = r.radii().coneReach;
    ASSERT_GT(reach, 0.0);
    EXPECT_NEAR(reach, double(out.radius) / out.photonAngle, 1e-6 * reach);

    // Every beam that starts at the light (a first segment, path distance = distance from the
    // light) is no wider than the cone at its far end, and has the full radius beyond the reach.
    // Planted bug: storing the first segment whole (appendConeBeam skipped) fails the first check.
    const uint64_t pass = 7;
    PhotonMap map = r.photonTracer().trace(pass);
    const Vec3 light = s.lights[0].position;
    int inside = 0, beyond = 0;
    for (const PhotonBeam& b : map.beams) {
        const Vec3 toOrigin = b.origin - light;
        const double s0 = length(toOrigin);
        if (s0 > 1e-4 && std::fabs(dot(toOrigin, b.dir) - s0) > 1e-4 * s0) continue;  // not radial
        // The path index is unknown per beam: bound by the pass's widest radius (its first path).
        const double rPass = r.radii().beamRadiusOf(pass * in.photonsPerPass);
        const double rLast = r.radii().beamRadiusOf((pass + 1) * in.photonsPerPass - 1);
        if (s0 + b.tMax <= reach * (1 - 1e-5)) {
            EXPECT_LE(b.radius, rPass / reach * (s0 + b.tMax) * (1 + 1e-5)) << "at " << s0;
            ++inside;
        } else if (s0 >= reach * (1 - 1e-4)) {
            EXPECT_GE(b.radius, rLast * (1 - 1e-6));
            ++beyond;
        }
    }
    EXPECT_GT(inside, 100) << "first segments split near the light";
    EXPECT_GT(beyond, 100);

    // On for a light at the fog's median depth: the first radius of the plan (4 x 0.5 footprints)
    // is wider than the light's pixel there, and the early passes' blur stays in the mean. Off where
    // the light's own pixel is wider than even that kernel (a light far behind the fog: the cone
    // would only add beams and variance), where no point light is near the image, and with an
    // explicit radius. Planted bugs (run): no footprint condition fails the far light's check; the
    // end radius in the condition (the rule before) fails the median-depth check.
    EXPECT_GT(PassRenderer(fogTunnel(4.0f), in).settings().photonAngle, 0.0f) << "light at the fog's median depth";
    Scene far = fogTunnel(4.0f);
    far.lights[0].position = Vec3(0.3f, 0.5f, -12.0f);  // 6x the fog's median depth, in view
    far.finalize();
    EXPECT_EQ(PassRenderer(far, in).settings().photonAngle, 0.0f) << "light far behind the fog";
    Scene away = fogTunnel(4.0f);
    away.lights[0].position = Vec3(0.0f, 0.0f, 0.9f);  // behind the camera, out of its reach
    away.finalize();
    EXPECT_EQ(PassRenderer(away, in).settings().photonAngle, 0.0f);
    RenderSettings explicitRadius = in;
    explicitRadius.radius = 0.05f;
    EXPECT_EQ(PassRenderer(s, explicitRadius).settings().photonAngle, 0.0f) << "an explicit radius keeps its meaning";
    RenderSettings explicitAngle = explicitRadius;
    explicitAngle.photonAngle = 0.3f;
    EXPECT_EQ(PassRenderer(s, explicitAngle).settings().photonAngle, 0.3f);
}

TEST(RadiusDefaults, ThePhotonConeIsOnForALightSeenOnlyInAMirror) {
    // The light behind the camera (out of the view and out of the cone's reach of the eye), a small
    // flat mirror 0.5 in front of the camera: the light's reflection sits 1.3 deep in the image,
    // nearer than the fog's median depth (3), its glow in view. Planted bug (run):
    // resolveRadiusDefaults without the mirror rule (pointLightNearTheImage alone) leaves the angle
    // at 0 and fails the first check.
    Scene s = fogTunnel(6.0f);
    s.lights[0].position = Vec3(0.02f, 0.03f, 0.3f);
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    mirror.albedo = Rgb(0.9f);
    s.materials.push_back(mirror);
    s.meshes.push_back(makeQuad("mirror", Vec3(-0.15f, -0.15f, -0.5f), Vec3(0.3f, 0, 0), Vec3(0, 0.3f, 0), 1));
    s.finalize();
    RenderSettings in;
    in.width = 48;
    in.height = 32;
    in.photonsPerPass = 300;
    in.passes = 20;
    const RenderSettings out = PassRenderer(s, in).settings();
    EXPECT_GT(out.photonAngle, 0.0f) << "the light's reflection is in view";
    const double reach = double(out.radius) / out.photonAngle;
    EXPECT_FALSE(pointLightNearTheImage(s, in.width, in.height, reach)) << "the light itself is not";

    Scene matte = s;
    matte.materials[1].type = MaterialType::Diffuse;
    matte.finalize();
    EXPECT_EQ(PassRenderer(matte, in).settings().photonAngle, 0.0f) << "no mirror, no glow in view";
    Scene aside = s;
    aside.lights[0].position = Vec3(3.0f, 3.0f, 0.3f);  // its reflection misses the mirror
    aside.finalize();
    EXPECT_FALSE(pointLightSeenInAMirror(EmbreeScene(aside), in.width, in.height, reach));
    EXPECT_TRUE(pointLightSeenInAMirror(EmbreeScene(s), in.width, in.height, reach));
}

TEST(RadiusDefaults, SurfacePhotonsNearALightGetTheConesRadius) {
    // The light 5 cm in front of the tunnel's back wall, in view: direct photons land within the
    // cone's reach. A direct photon (it arrives radially from the light) at distance d has at most
    // the pass's first surface radius x max(1/8, d / reach); every photon at least the pass's last
    // radius x max(1/8, d / reach) (its path distance is at least d).
    // Planted bug (run): storing every photon with the full radius fails the first check.
    Scene s = fogTunnel(4.0f);
    s.lights[0].position = Vec3(0.0f, 0.0f, -3.95f);
    s.finalize();
    RenderSettings in;
    in.width = 48;
    in.height = 32;
    in.photonsPerPass = 2000;
    in.passes = 20;
    in.directLight = false;  // photons for the direct light too (with shadow rays none are stored)
    // The light sits deeper than the fog's median depth, where the automatic cone stays off
    // (kConeMinLightFootprints): the angle is given, the radii automatic.
    in.photonAngle = 0.5f;
    PassRenderer r(s, in);
    const double reach = r.radii().coneReach;
    ASSERT_GT(reach, 0.1) << "the cone is on and reaches the back wall";
    const uint64_t pass = 3;
    const double first = r.radii().surfaceRadiusOf(pass * in.photonsPerPass);
    const double last = r.radii().surfaceRadiusOf((pass + 1) * in.photonsPerPass - 1);
    PhotonMap map = r.photonTracer().trace(pass);
    const Vec3 light = s.lights[0].position;
    int direct = 0, narrowed = 0;
    for (const SurfacePhoton& p : map.surfacePhotons) {
        const double d = length(p.position - light);
        const double scale = std::clamp(d / reach, 1.0 / 8.0, 1.0);
        EXPECT_GE(p.radius, last * scale * (1 - 1e-5)) << "at " << d;
        if (dot(p.wi, (light - p.position) / float(d)) < 1 - 1e-5f) continue;  // not direct
        ++direct;
        EXPECT_LE(p.radius, first * scale * (1 + 1e-5)) << "direct photon at " << d;
        narrowed += scale < 0.5;
    }
    EXPECT_GT(narrowed, 100) << "direct photons within half the reach (of " << direct << " direct)";
    EXPECT_EQ(surfaceConeScale(0.0, 0.0), 1.0) << "no cone: no scale";
}

TEST(RadiusDefaults, TheSurfaceRadiusIsCappedByTheSceneInCoarseImages) {
    // 3 footprints of a 12 x 8 image are 6% of the tunnel's diagonal: the cap (2%) binds there (a
    // kernel that wide loses the light near surfaces' edges); at 256 x 170 (0.3%) it does not.
    Scene s = fogTunnel(4.0f);
    const double diagonal = length(s.bounds.diagonal());
    EmbreeScene rt(s);
    for (int width : {12, 64, 256}) {
        RenderSettings in;
        in.width = width;
        in.height = width * 2 / 3;
        in.photonsPerPass = 1000;
        in.passes = 10;
        PassRenderer r(s, in);
        const double end = r.radii().surfaceRadiusOf(r.settings().plannedPaths);
        const double footprints = RadiusDefaults::kSurfaceEndFootprints *
                                  measurePixelFootprint(rt, s.camera, in.width, in.height).surface;
        const double cap = RadiusDefaults::kSurfaceEndMaxDiagonal * diagonal;
        EXPECT_NEAR(end, std::min(footprints, cap), 1e-3 * end) << width << " pixels wide";
        if (width == 12) {
            EXPECT_GT(footprints, 2 * cap) << "the coarse image is one the cap binds in";
        } else if (width == 256) {
            EXPECT_LT(footprints, cap) << "the fine image is one it does not";
        }
    }
}

TEST(RadiusSchedule, OffsetForRatioInvertsTheSchedule) {
    for (double alpha : {0.3, 0.5, 0.8})
        for (uint64_t paths : {1000ull, 1000000ull, 100000000ull}) {
            uint64_t n0 = RadiusSchedule::offsetForRatio(alpha, paths, 0.25);
            EXPECT_GE(RadiusSchedule(alpha, n0).beamFactor(paths), 0.25);
            if (n0 > 0) {
                EXPECT_LT(RadiusSchedule(alpha, n0 - 1).beamFactor(paths), 0.25) << "the smallest such offset";
            }
            if (paths >= 1000000) {
                EXPECT_GT(n0, 0u) << "the paper's schedule shrinks far below 1/4 here";
            }
        }
    EXPECT_EQ(RadiusSchedule::offsetForRatio(0.5, 1000, 1e-9), 0u) << "the paper's schedule shrinks enough";
}

}  // namespace
}  // namespace tyndall
