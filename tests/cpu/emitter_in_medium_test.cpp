// Lights inside a medium-filled mesh start in that medium, in PPB and in the path tracer, checked
// against a closed form computed here with nothing from the renderer (own camera rays, own
// ray-box intersection, own quadrature).
//
// The scene: vacuum everywhere except a cube [-1, 1]^3 bounded by an index-matched Interface and
// filled with a homogeneous medium (coloured sigma_s, sigma_a, HG g = 0.3). At its centre either a
// point light of intensity I, or a small emitting sphere (radius r = 0.06, radiance Le from its
// front side, black otherwise) that states no medium of its own: finalize() must find it inside
// the cube (core/medium_nesting.h). The camera looks at the cube from outside.
//
// Single scattering only (PPB stores each photon path's first beam, the path tracer stops after
// one scattering vertex). Along a camera ray o + s d crossing the cube over [s_in, s_out]:
//     L = int sigma_s exp(-sigma_t (s - s_in)) S(x) ds,   x = o + s d,
// with S(x) the light arriving at x, times the phase function for light travelling along w and
// leaving toward the camera, p(w . -d):
//   - point light: S = I / |x|^2 exp(-sigma_t |x|) p(x/|x| . -d);
//   - emitting sphere: S = int over the cone of directions w' from x toward the sphere of
//     Le exp(-sigma_t t(w')) p(-w' . -d) dw', t(w') the distance to the sphere's surface along w',
//     cone half-angle asin(r/|x|); the sphere is the tessellated one, so r is taken from its
//     area (r = sqrt(A / 4 pi)).
// The s integral uses s = s_c + h tan(u) (h: the ray's distance to the centre) and Simpson's rule
// in double (200 intervals), the cone a midpoint rule in cos(theta) and phi (16 x 8); each pixel
// is the mean over a 3 x 3 grid of rays inside it (film convention of core/camera.h: pixel (0, 0)
// at the top left, vertical field of view).
//
// Comparison as in analytic_sphere_test.cpp: pixels are grouped by h (those with h < 0.15 left out:
// the emitter itself and the 1/h peak, where PPB's kernel blurs); per group the ratio
// sum(estimate) / sum(closed form) must be within 4 standard errors plus a bias allowance
// (path tracer 0.5%: quadrature, pixel averaging and the tessellated emitter; PPB 2%: the beam
// kernel, radius 0.02, blur, about (r/h)^2 / 7 = 0.3% at h = 0.15). The standard errors come from
// the path tracer's per-pixel variance and from 8 independent PPB batches, and must stay below
// 1.5% so that the test can fail. An emitter whose photons start in the vacuum outside the cube
// (the defect this guards against) gives PPB no beams at all.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "cpu/photon_tracer.h"
#include "cpu/reference_tracer.h"
#include "loading/mesh_builders.h"
#include "tests/cpu/closed_form_bins.h"
#include "tests/cpu/reference_fixtures.h"
#include "tests/test_util.h"

namespace tyndall {
namespace {

constexpr int kSize = 32;
constexpr double kHalf = 1.0;            // the cube's half size
constexpr float kEmitterRadius = 0.06f;  // of the tessellated sphere's vertices

struct V {
    double x, y, z;
};
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dotv(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V crossv(V a, V b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double lenv(V a) { return std::sqrt(dotv(a, a)); }
V unit(V a) { return a * (1.0 / lenv(a)); }
V v(const Vec3& a) { return {a.x, a.y, a.z}; }

double hg(double cosTheta, double g) {
    double denom = 1.0 + g * g - 2.0 * g * cosTheta;
    return (1.0 - g * g) / (4.0 * M_PI * denom * std::sqrt(denom));
}

Medium cubeMedium() {
    Medium m;
    m.name = "haze";
    m.sigmaS = Rgb(0.5f, 0.4f, 0.3f);
    m.sigmaA = Rgb(0.2f, 0.3f, 0.45f);
    m.g = 0.3f;
    return m;
}

/// The cube of medium with a point light (emitter = false) or an emitting sphere at its centre.
Scene makeScene(bool emitter, const Rgb& power) {
    Scene s;
    s.name = emitter ? "emitter-in-medium" : "point-light-in-medium";
    s.source = "<test scene>";
    Material hull;
    hull.name = "hull";
    hull.type = MaterialType::Interface;
    Material lamp;
    lamp.name = "lamp";
    lamp.albedo = Rgb(0.0f);
    lamp.emission = power;
    s.materials = {hull, lamp};
    s.media.push_back(cubeMedium());
    TriangleMesh cube = makeBox("cube", Vec3(float(-kHalf)), Vec3(float(kHalf)), 0);
    cube.interiorMedium = 0;  // the exterior comes from containment: the global vacuum
    s.meshes.push_back(cube);
    if (emitter) {
        s.meshes.push_back(makeSphere("lamp", Vec3(0.0f), kEmitterRadius, 3, 1));  // media: by containment
    } else {
        Light l;
        l.name = "point";
        l.position = Vec3(0.0f);
        l.intensity = power;
        s.lights.push_back(l);
    }
    s.camera = Camera::lookAt({0.15f, 0.1f, 4.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 2.0f * std::atan(1.1f / 3.0f));
    s.finalize();
    s.validate();
    return s;
}

/// Where o + s d runs inside the cube (slabs); false if it misses.
bool cubeInterval(V o, V d, double* s0, double* s1) {
    double lo = 0, hi = 1e30;
    const double oc[3] = {o.x, o.y, o.z}, dc[3] = {d.x, d.y, d.z};
    for (int k = 0; k < 3; ++k) {
        double a = (-kHalf - oc[k]) / dc[k], b = (kHalf - oc[k]) / dc[k];
        if (a > b) std::swap(a, b);
        lo = std::max(lo, a);
        hi = std::min(hi, b);
    }
    *s0 = lo;
    *s1 = hi;
    return hi > lo;
}

class ClosedForm {
public:
    ClosedForm(const Scene& scene, bool emitter, const Rgb& power) : m_emitter(emitter), m_power(power) {
        const Medium& m = scene.media[0];
        for (int c = 0; c < 3; ++c) m_sigmaS[c] = m.sigmaS[c], m_sigmaT[c] = m.sigmaS[c] + m.sigmaA[c];
        m_g = m.g;
        const Camera& cam = scene.camera;
        m_eye = v(cam.position), m_forward = v(cam.forward), m_right = v(cam.right), m_up = v(cam.up);
        m_tanHalf = std::tan(0.5 * double(cam.yFov));
        if (emitter) {
            double area = 0;
            const TriangleMesh& lamp = scene.meshes[1];
            for (size_t t = 0; t < lamp.triangleCount(); ++t)
                area += 0.5 * lenv(crossv(v(lamp.vertex(t, 1)) - v(lamp.vertex(t, 0)),
                                          v(lamp.vertex(t, 2)) - v(lamp.vertex(t, 0))));
            m_r = std::sqrt(area / (4.0 * M_PI));
        }
    }

    /// The pinhole ray through film position (fx, fy) of a kSize x kSize film.
    V direction(double fx, double fy) const {
        double nx = 2.0 * fx / kSize - 1.0, ny = 1.0 - 2.0 * fy / kSize;
        return unit(m_forward + m_right * (nx * m_tanHalf) + m_up * (ny * m_tanHalf));
    }

    /// Distance from the centre to the ray through the pixel's centre; -1 when it misses the cube.
    double pixelH(int x, int y) const {
        V d = direction(x + 0.5, y + 0.5);
        double s0, s1;
        if (!cubeInterval(m_eye, d, &s0, &s1)) return -1;
        return lenv(m_eye - d * dotv(m_eye, d));
    }

    void pixel(int x, int y, double out[3]) const {
        out[0] = out[1] = out[2] = 0;
        const int k = 3;
        for (int j = 0; j < k; ++j)
            for (int i = 0; i < k; ++i) {
                double L[3];
                ray(direction(x + (i + 0.5) / k, y + (j + 0.5) / k), L);
                for (int c = 0; c < 3; ++c) out[c] += L[c] / (k * k);
            }
    }

private:
    void ray(V d, double L[3]) const {
        L[0] = L[1] = L[2] = 0;
        double sIn, sOut;
        if (!cubeInterval(m_eye, d, &sIn, &sOut)) return;
        const double sc = -dotv(m_eye, d), h = lenv(m_eye + d * sc);
        const double a = std::atan2(sIn - sc, h), b = std::atan2(sOut - sc, h);
        const int n = 200;
        const double step = (b - a) / n;
        for (int i = 0; i <= n; ++i) {
            double u = a + i * step, s = sc + h * std::tan(u);
            double w = (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * step / 3.0 * h / (std::cos(u) * std::cos(u));
            double S[3];
            source(m_eye + d * s, d, S);
            for (int c = 0; c < 3; ++c) L[c] += w * m_sigmaS[c] * std::exp(-m_sigmaT[c] * (s - sIn)) * S[c];
        }
    }

    /// S(x) of the file comment for the camera ray direction d.
    void source(V x, V d, double S[3]) const {
        const double dist = lenv(x);
        if (!m_emitter) {
            double p = hg(dotv(x * (1.0 / dist), d * -1.0), m_g);
            for (int c = 0; c < 3; ++c) S[c] = m_power[c] / (dist * dist) * std::exp(-m_sigmaT[c] * dist) * p;
            return;
        }
        S[0] = S[1] = S[2] = 0;
        if (dist <= m_r) return;
        const V axis = x * (-1.0 / dist);  // toward the sphere's centre
        const V e1 = unit(std::abs(axis.x) < 0.9 ? crossv(axis, {1, 0, 0}) : crossv(axis, {0, 1, 0}));
        const V e2 = crossv(axis, e1);
        const double cosMax = std::sqrt(1.0 - m_r * m_r / (dist * dist));
        const int nMu = 16, nPhi = 8;
        const double dMu = (1.0 - cosMax) / nMu, dPhi = 2.0 * M_PI / nPhi;
        for (int i = 0; i < nMu; ++i) {
            double mu = cosMax + (i + 0.5) * dMu, sinT = std::sqrt(std::max(0.0, 1.0 - mu * mu));
            double t = dist * mu - std::sqrt(std::max(0.0, m_r * m_r - dist * dist * sinT * sinT));
            for (int j = 0; j < nPhi; ++j) {
                double phi = (j + 0.5) * dPhi;
                V w = axis * mu + e1 * (sinT * std::cos(phi)) + e2 * (sinT * std::sin(phi));  // toward the light
                double p = hg(dotv(w * -1.0, d * -1.0), m_g) * dMu * dPhi;
                for (int c = 0; c < 3; ++c) S[c] += m_power[c] * std::exp(-m_sigmaT[c] * t) * p;
            }
        }
    }

    bool m_emitter;
    Rgb m_power;
    double m_sigmaS[3], m_sigmaT[3], m_g = 0, m_r = 0, m_tanHalf = 1;
    V m_eye, m_forward, m_right, m_up;
};

const std::vector<test::HBin> kBins = {{0.15, 0.4}, {0.4, 0.9}};

test::ClosedFormImage expected(const ClosedForm& form) {
    test::ClosedFormImage e{Image(kSize, kSize), std::vector<double>(size_t(kSize) * kSize, -1.0)};
    tbb::parallel_for(0, kSize, [&](int y) {
        for (int x = 0; x < kSize; ++x) {
            const size_t i = size_t(y) * kSize + x;
            e.h[i] = form.pixelH(x, y);
            if (e.h[i] < kBins.front().hLo || e.h[i] >= kBins.back().hHi) continue;
            double L[3];
            form.pixel(x, y, L);
            e.radiance.pixels[i] = Rgb(float(L[0]), float(L[1]), float(L[2]));
        }
    });
    return e;
}

void run(bool emitter, const Rgb& power, uint32_t referenceSpp) {
    Scene scene = makeScene(emitter, power);
    const char* what = emitter ? "emitting sphere" : "point light";
    if (emitter) {
        ASSERT_EQ(scene.meshes[1].exteriorMedium, 0) << "the emitter is not in the cube's medium";
    }
    test::ClosedFormImage e = expected(ClosedForm(scene, emitter, power));

    EmbreeScene rt(scene);
    ReferenceSettings rs;
    rs.width = rs.height = kSize;
    rs.samplesPerPixel = referenceSpp;
    rs.maxDepth = 1;
    rs.seed = 5;
    ReferenceImage ref = ReferenceTracer(rt, rs).render();
    test::expectReferenceMatches(what, ref, e, kBins, {0.015, 0.005});

    RenderSettings ps;
    ps.width = ps.height = kSize;
    ps.photonsPerPass = 20000;
    ps.maxPhotonBounces = 1;
    ps.radius = 0.02f;
    ps.radiusOffset = 1000000000000ull;  // a constant radius
    ps.seed = 9;
    ps.equiangular = false;  // the photons' first beams are what this checks (equiangular: its own tests)
    PassRenderer renderer(scene, ps);
    std::vector<Image> batches;
    for (int b = 0; b < 8; ++b) batches.push_back(test::renderPpbPasses(renderer, uint64_t(b) * 2, 2));
    test::expectPpbMatches(what, batches, e, kBins, {0.015, 0.02});

    if (::testing::Test::HasFailure()) {
        std::string base = emitter ? "emitter_in_medium" : "point_light_in_medium";
        test::writeEvidence(base + "_exact", e.radiance);
        test::writeEvidence(base + "_reference", ref.mean);
        test::writeEvidence(base + "_ppb", batches[0]);
    }
}

// Smoke in a hollow glass jar in fog: the first photon segments of a point light, a spot and an
// emitting sphere standing in the smoke are smoke beams; a sun's first beams are fog beams.
TEST(EmitterInMedium, PhotonsStartInTheMediumThatHoldsTheLight) {
    for (int source = 0; source < 4; ++source) {
        Scene s;
        s.name = "jar";
        s.source = "<test scene>";
        Material glass, hull, lamp, floor;
        glass.type = MaterialType::Dielectric;
        hull.type = MaterialType::Interface;
        lamp.albedo = Rgb(0.0f);
        lamp.emission = Rgb(source == 2 ? 5.0f : 0.0f);
        s.materials = {glass, hull, lamp, floor};
        Medium fog = cubeMedium(), smoke = cubeMedium();
        fog.name = "fog";
        smoke.name = "smoke";
        s.media = {fog, smoke};
        s.globalMedium = 0;
        s.meshes.push_back(makeBox("jar outside", {-1, -1, -1}, {1, 1, 1}, 0));
        s.meshes.push_back(makeBox("jar inside", {-0.9f, -0.9f, -0.9f}, {0.9f, 0.9f, 0.9f}, 0, true));
        TriangleMesh smokeHull = makeSphere("smoke", Vec3(0.0f), 0.8f, 3, 1);
        smokeHull.interiorMedium = 1;
        s.meshes.push_back(smokeHull);
        s.meshes.push_back(makeSphere("lamp", {0.1f, 0, 0}, 0.05f, 2, 2));
        // Widens the scene's bounds (where the fog ends) beyond the jar, so that sunlight crosses fog.
        s.meshes.push_back(makeQuad("floor", {-3, -1, 3}, {6, 0, 0}, {0, 0, -6}, 3));
        Light l;
        l.name = "light";
        l.type = source == 0 ? LightType::Point : source == 1 ? LightType::Spot : LightType::Directional;
        l.position = {-0.1f, 0.1f, 0};
        l.direction = normalize(Vec3(0.2f, -1, 0.1f));
        l.intensity = Rgb(source == 2 ? 0.0f : 1.0f);
        s.lights.push_back(l);
        s.camera = Camera::lookAt({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, 0.8f);
        s.finalize();
        s.validate();
        EmbreeScene rt(s);
        RenderSettings settings;
        settings.photonsPerPass = 2000;
        settings.maxPhotonBounces = 1;
        settings.radius = 0.01f;
        settings.equiangular = false;  // the lights' own first beams are what this checks
        PhotonMap map = PhotonTracer(rt, settings, RadiusSetup::resolve(settings, s)).trace(0);
        const MediumId expected = source == 3 ? 0 : 1;
        ASSERT_GT(map.beams.size(), 100u) << "source " << source;
        size_t wrong = 0;
        for (const PhotonBeam& b : map.beams) wrong += b.medium != expected;
        EXPECT_EQ(wrong, 0u) << "source " << source << ": beams outside the medium that holds the light";
    }
}

TEST(EmitterInMedium, PointLightAtTheCentreOfAMediumCube) { run(false, Rgb(2.0f, 1.6f, 1.2f), 256); }

TEST(EmitterInMedium, EmittingSphereAtTheCentreOfAMediumCube) {
    // The path tracer reaches the small sphere by light samples and by phase-sampled directions
    // (MIS): noisier per sample than the point light's equiangular estimate.
    run(true, Rgb(60.0f, 50.0f, 40.0f), 1024);
}

}  // namespace
}  // namespace tyndall
