// GLSL twin vs C++: gpu/shaders/beam_estimator.glsl and media.glsl against core/beam_estimator.h,
// core/phase.h, core/transmittance.h and core/density_volume.h, evaluated on the same inputs by a
// compute shader. Cases are built around the decision boundaries (u ~ r, s ~ 0 and sMax, t ~ 0
// and tMax, near-parallel lines at the 1/sin clamp and the skip threshold), with HG g of both signs.
#include <gtest/gtest.h>

#include <cmath>

#include "core/beam_estimator.h"
#include "core/rng.h"
#include "core/transmittance.h"
#include "gpu/gl_context.h"
#include "gpu/gl_layout.h"
#include "gpu/gl_program.h"
#include "gpu/media_table.h"
#include "tests/gpu/gpu_test_util.h"

using namespace tyndall;

namespace {

constexpr int kOutputs = 16;

const char* kParityShader = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 7) writeonly buffer Results { float results[]; };
layout(std430, binding = 8) readonly buffer Params { vec4 params[]; };

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= frame.beamCount) return;
    PrimaryRay ray = rays[i];
    PhotonBeam beam = beams[i];
    vec4 a = params[2 * i], b = params[2 * i + 1];  // (sigmaS, g), (trCam, trBeam, u, cos)
    BeamRayHit hit = BeamRayHit(0.0, 0.0, 0.0, 0.0, 0.0);
    bool ok = intersectBeamRay(ray.origin, ray.dir, ray.tMax, beam, hit);
    vec3 l = ok ? beamRadiance(hit, beam, a.xyz, a.w, vec3(b.x), vec3(b.y)) : vec3(0.0);
    float o[16] = float[16](ok ? 1.0 : 0.0, hit.u, hit.s, hit.t, hit.invSinTheta, hit.cosTheta, l.x, l.y, l.z,
                            beamKernel(b.z, beam.radius), hgPhase(b.w, a.w),
                            volumeDensity(0, ray.origin + ray.dir * b.z), rayTransmittance(i, b.z),
                            beamTransmittance(i, b.z), 0.0, 0.0);
    for (int k = 0; k < 16; ++k) results[16 * i + k] = o[k];
}
)";

struct Cases {
    std::vector<PrimaryRay> rays;
    std::vector<PhotonBeam> beams;
    std::vector<float> params;  // 8 per case
    std::vector<float> rayFreeFlights, beamFreeFlights;
};

Vec3 randomDir(Rng& rng) {
    return sampleUniformSphere(rng.uniform(), rng.uniform());
}

Cases makeCases(int n) {
    Cases c;
    Rng rng(2024, 1);
    const float gs[] = {-0.9f, -0.3f, 0.0f, 0.25f, 0.6f, 0.95f};
    for (int i = 0; i < n; ++i) {
        Vec3 o{4 * rng.uniform() - 2, 2 * rng.uniform(), 6 * rng.uniform() - 3};
        Vec3 d = randomDir(rng);
        float sMax = 0.5f + 4 * rng.uniform();
        float r = 0.01f + 0.2f * rng.uniform();
        // Beam direction: random, or within a hair of (anti)parallel to the ray.
        Vec3 w = randomDir(rng);
        int kind = i % 8;
        if (kind == 6 || kind == 7) {
            float angle = std::pow(10.0f, -7.0f + 5.0f * rng.uniform());  // 1e-7 .. 1e-2 rad
            Frame f(d);
            Vec3 side = f.s * std::cos(6.28f * rng.uniform()) + f.t * std::sin(6.28f * rng.uniform());
            w = normalize(d * (kind == 6 ? 1.0f : -1.0f) + normalize(side) * angle);
        }
        // Closest points placed at, inside and just outside the accepting ranges.
        auto edgy = [&](float max) {
            float x = rng.uniform();
            return x < 0.15f  ? -0.001f * max * rng.uniform()
                   : x < 0.3f ? max * (1 + 0.001f * rng.uniform())
                              : 1.1f * max * rng.uniform();
        };
        float s0 = edgy(sMax), tMax = 0.3f + 3 * rng.uniform(), t0 = edgy(tMax);
        float u = r * (rng.uniform() < 0.2f ? 1.0f - 1e-4f * rng.uniform() : 1.1f * rng.uniform());
        Vec3 perp = cross(d, w);
        perp = lengthSquared(perp) > 1e-12f ? normalize(perp) : Frame(d).s;
        Vec3 q = o + d * s0 + perp * u;
        PhotonBeam b;
        b.origin = q - w * t0;
        b.dir = w;
        b.tMax = tMax;
        b.radius = r;
        b.power = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
        b.medium = 0;
        c.beams.push_back(b);
        c.rays.push_back(PrimaryRay{o, sMax, d, 0});
        float g = gs[i % 6];
        c.params.insert(c.params.end(),
                        {0.1f + rng.uniform(), 0.2f + rng.uniform(), 0.3f + rng.uniform(), g, rng.uniform(),
                         rng.uniform(), 1.2f * r * rng.uniform(), 2 * rng.uniform() - 1});
        for (int k = 0; k < 4; ++k) {
            c.rayFreeFlights.push_back(sMax * rng.uniform());
            c.beamFreeFlights.push_back(0.3f * rng.uniform());
        }
    }
    return c;
}

}  // namespace

TEST(EstimatorParity, GlslTwinMatchesCpp) {
    const int n = 8192;
    Cases cases = makeCases(n);
    // Medium 0 carries the analytic lattice grid, so volumeDensity(0, p) has a volume to read.
    Scene scene;
    Medium m;
    m.name = "lattice";
    m.density = std::make_shared<tyndall::test::LatticeTestGrid>(Bounds3{{-2, 0, -3}, {2, 2, 3}}, 7);
    scene.media.push_back(m);
    const DensityVolume& volume = static_cast<const tyndall::test::LatticeTestGrid&>(*m.density).volume();
    GlMediaTable table = buildMediaTable(scene, size_t(1) << 24);

    auto ctx = GlContext::create();
    const GlFunctions& gl = ctx->gl();
    GlProgram program(
        gl, "estimator parity",
        {{GL_COMPUTE_SHADER, {glsl("gl_layout.h"), glsl("beam_estimator.glsl"), glsl("media.glsl"), kParityShader}}});
    GlSplatFrame frame{};
    frame.freeFlightsPerRay = 4;
    frame.freeFlightsPerBeam = 4;
    frame.beamCount = n;
    GLuint buffers[10];
    gl.CreateBuffers(10, buffers);
    auto upload = [&](GLenum target, GLuint binding, GLuint buffer, const void* data, size_t bytes) {
        gl.NamedBufferData(buffer, GLsizeiptr(bytes), data, GL_STATIC_DRAW);
        gl.BindBufferBase(target, binding, buffer);
    };
    upload(GL_UNIFORM_BUFFER, kBindFrame, buffers[0], &frame, sizeof(frame));
    upload(GL_SHADER_STORAGE_BUFFER, kBindPrimaryRays, buffers[1], cases.rays.data(), n * sizeof(PrimaryRay));
    upload(GL_SHADER_STORAGE_BUFFER, kBindRayFreeFlights, buffers[2], cases.rayFreeFlights.data(), n * 16);
    upload(GL_SHADER_STORAGE_BUFFER, kBindBeams, buffers[3], cases.beams.data(), n * sizeof(PhotonBeam));
    upload(GL_SHADER_STORAGE_BUFFER, kBindBeamFreeFlights, buffers[4], cases.beamFreeFlights.data(), n * 16);
    upload(GL_SHADER_STORAGE_BUFFER, kBindMedia, buffers[5], table.media.data(), table.media.size() * sizeof(GlMedium));
    upload(GL_SHADER_STORAGE_BUFFER, kBindVolumes, buffers[6], table.volumes.data(),
           table.volumes.size() * sizeof(GlVolume));
    upload(GL_SHADER_STORAGE_BUFFER, kBindVoxels, buffers[7], table.voxels.data(), table.voxels.size() * sizeof(float));
    upload(GL_SHADER_STORAGE_BUFFER, 7, buffers[8], nullptr, size_t(n) * kOutputs * sizeof(float));
    upload(GL_SHADER_STORAGE_BUFFER, 8, buffers[9], cases.params.data(), cases.params.size() * sizeof(float));
    gl.UseProgram(program.id());
    gl.DispatchCompute(GLuint((n + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> out(size_t(n) * kOutputs);
    gl.GetNamedBufferSubData(buffers[8], 0, GLsizeiptr(out.size() * sizeof(float)), out.data());
    ASSERT_EQ(gl.GetError(), GLenum(GL_NO_ERROR));
    gl.DeleteBuffers(10, buffers);

    auto rel = [](float a, float b) { return std::abs(a - b) / std::max(std::abs(b), 1e-20f); };
    int hits = 0, clamped = 0, flagMismatch = 0;
    double worstRadiance = 0, worstKernel = 0, worstPhase = 0, worstDensity = 0;
    for (int i = 0; i < n; ++i) {
        const float* o = &out[size_t(i) * kOutputs];
        const float* p = &cases.params[size_t(i) * 8];
        const PrimaryRay& ray = cases.rays[i];
        const PhotonBeam& beam = cases.beams[i];
        BeamRayHit hit;
        bool ok = intersectBeamRay(ray.origin, ray.dir, ray.tMax, beam, &hit);
        if (ok != (o[0] == 1.0f)) {
            ++flagMismatch;
            continue;
        }
        if (ok) {
            ++hits;
            clamped += hit.invSinTheta == 1.0f / kMinSinTheta;
            EXPECT_NEAR(o[1], hit.u, 1e-6f * std::max(1.0f, hit.u)) << "case " << i;
            EXPECT_NEAR(o[2], hit.s, 1e-6f * std::max(1.0f, hit.s)) << "case " << i;
            EXPECT_NEAR(o[3], hit.t, 1e-6f * std::max(1.0f, hit.t)) << "case " << i;
            EXPECT_LE(rel(o[4], hit.invSinTheta), 1e-5f) << "case " << i;
            EXPECT_EQ(o[5], hit.cosTheta) << "case " << i;
            Rgb l = beamRadiance(hit, beam, Rgb(p[0], p[1], p[2]), p[3], Rgb(p[4]), Rgb(p[5]));
            for (int c = 0; c < 3; ++c) worstRadiance = std::max(worstRadiance, double(rel(o[6 + c], l[c])));
        }
        worstKernel = std::max(worstKernel, double(std::abs(o[9] - beamKernel(p[6], beam.radius)) * beam.radius));
        worstPhase = std::max(worstPhase, double(rel(o[10], hgPhase(p[7], p[3]))));
        float density = volume.sample(ray.origin + ray.dir * p[6]);
        worstDensity = std::max(worstDensity, double(std::abs(o[11] - density)));
        EXPECT_EQ(o[12], storedTransmittance(&cases.rayFreeFlights[size_t(i) * 4], 4, p[6])) << "case " << i;
        EXPECT_EQ(o[13], storedTransmittance(&cases.beamFreeFlights[size_t(i) * 4], 4, p[6])) << "case " << i;
    }
    std::printf(
        "%d cases, %d hits (%d at the 1/sin clamp), %d accept/reject mismatches; worst relative "
        "radiance %.2g, kernel*r %.2g, phase %.2g, absolute density %.2g\n",
        n, hits, clamped, flagMismatch, worstRadiance, worstKernel, worstPhase, worstDensity);
    EXPECT_GT(hits, n / 4);
    EXPECT_GT(clamped, 10);
    EXPECT_EQ(flagMismatch, 0) << "the GLSL and C++ accept/reject decisions must agree (precise arithmetic)";
    EXPECT_LT(worstRadiance, 1e-5);
    EXPECT_LT(worstKernel, 1e-5);
    EXPECT_LT(worstPhase, 1e-5);
    EXPECT_LT(worstDensity, 1e-5);
}
