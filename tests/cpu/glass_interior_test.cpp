// A camera path that ends inside glass: fog filling a smooth glass cube, seen through one face and
// lit through another by a directional light, against the closed form of single scattering.
// Every other glass test enters and leaves the glass, so the radiance scaling (eta_i / eta_t)^2 at
// the interface cancels over the round trip; here the camera path gathers its light inside the glass,
// so the factor 1 / 1.5^2 is seen alone (and photons, which carry power, must not get it).
#include <gtest/gtest.h>

#include <cmath>

#include "tests/cpu/reference_fixtures.h"

namespace tyndall {
namespace {

constexpr float kIor = 1.5f;
constexpr float kSigmaS = 0.3f, kSigmaA = 0.9f;  // absorbing: light trapped by TIR dies out
constexpr float kSun = 3.0f;                     // irradiance, W/m^2
constexpr int kSize = 16;

/// Glass cube [-0.5, 0.5]^3 filled with fog, vacuum outside; the sun shines straight down onto its
/// top face; a distant narrow camera on +z looks at its front face at (nearly) normal incidence.
Scene fogInGlassScene() {
    Scene s;
    s.name = "fog-in-glass";
    s.source = "<test>";
    Material glass;
    glass.name = "glass";
    glass.type = MaterialType::Dielectric;
    glass.ior = kIor;
    glass.albedo = Rgb(1.0f);
    s.materials = {glass};
    Medium fog;
    fog.name = "fog";
    fog.sigmaS = Rgb(kSigmaS);
    fog.sigmaA = Rgb(kSigmaA);
    s.media.push_back(fog);
    TriangleMesh cube = makeBox("cube", Vec3(-0.5f), Vec3(0.5f), 0);
    cube.interiorMedium = 0;
    cube.exteriorMedium = kVacuum;
    s.meshes.push_back(cube);
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = {0, -1, 0};
    sun.intensity = Rgb(kSun);
    s.lights.push_back(sun);
    s.camera = Camera::lookAt({0, 0, 20}, {0, 0, 0}, {0, 1, 0}, 2.0f * kPi / 180.0f);
    s.finalize();
    s.validate();
    return s;
}

/// Radiance leaving the front face at height y, single scattering: the sun enters the top face
/// with 1 - F, reaches depth 0.5 - y attenuated, scatters isotropically toward the camera along
/// z in [-0.5, 0.5]; the camera path enters with 1 - F and the radiance factor 1 / eta^2, and
/// bounces between the faces (F each, e^{-sigma_t} per crossing) gathering again.
double closedForm(double y) {
    const double F = std::pow((kIor - 1.0) / (kIor + 1.0), 2), st = kSigmaS + kSigmaA;
    const double inside = kSigmaS * kSun * (1 - F) * std::exp(-st * (0.5 - y)) / (4 * kPi) * (1 - std::exp(-st)) / st;
    return (1 - F) / (kIor * kIor) * inside / (1 - F * std::exp(-st));
}

TEST(GlassInterior, FogInsideGlassSeenThroughOneFaceMatchesSingleScattering) {
    Scene s = fogInGlassScene();
    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = 20000;
    ps.seed = 21;
    // Two vertices: the refraction into the top face and the first beam; so the light is single
    // scattering, the closed form's (the beam is stored to the bottom face, not cut at a collision).
    ps.maxPhotonBounces = 2;
    PassRenderer renderer(s, ps);
    const int kPasses = 8;
    Image img = test::renderPpbPasses(renderer, 0, kPasses);
    // The central pixels (away from the cube's edges, where the beams' kernel is cut off).
    EmbreeScene rt(s);
    double sum = 0, expected = 0;
    int n = 0;
    for (int py = 4; py < kSize - 4; ++py)
        for (int px = 4; px < kSize - 4; ++px) {
            Ray r = s.camera.generateRay(px + 0.5f, py + 0.5f, kSize, kSize, {0.5f, 0.5f});
            SurfaceHit hit;
            ASSERT_TRUE(rt.intersect(r, &hit));
            ASSERT_NEAR(hit.p.z, 0.5f, 1e-4f) << "the front face";
            for (int c = 0; c < 3; ++c) sum += img.at(px, py)[c] / 3.0;
            expected += closedForm(hit.p.y);
            ++n;
        }
    sum /= n;
    expected /= n;
    std::printf("fog in glass: PPB %.6f, closed form %.6f (ratio %.4f)\n", sum, expected, sum / expected);
    if (std::abs(sum / expected - 1) > 0.05) test::writeEvidence("glass_interior_fog", img);
    // Measured over seeds 21-26: ratio 0.995 to 1.020 (mean 1.008, standard deviation 0.008: the
    // noise, and the multiple scattering the closed form leaves out); 5% stays far from what a
    // wrong scaling gives (1.5^2 = 2.25 and beyond).
    EXPECT_NEAR(sum / expected, 1.0, 0.05);
}

}  // namespace
}  // namespace tyndall
