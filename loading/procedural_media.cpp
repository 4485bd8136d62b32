#include "loading/procedural_media.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.h"

namespace tyndall {

namespace {
float lattice(int x, int y, int z, uint32_t seed) {
    uint64_t h = splitMix64((uint64_t(uint32_t(x)) << 32) ^ (uint64_t(uint32_t(y)) << 16) ^ uint64_t(uint32_t(z)) ^
                            (uint64_t(seed) << 48));
    h = splitMix64(h ^ uint64_t(uint32_t(z)) * 0x9E3779B97F4A7C15ull);
    return float(h >> 40) * 0x1p-24f;
}

float smooth(float t) {
    return t * t * (3.0f - 2.0f * t);
}

/// Value noise in [0, 1): smoothed trilinear blend of hashed lattice values.
float valueNoise(const Vec3& p, uint32_t seed) {
    int ix = int(std::floor(p.x)), iy = int(std::floor(p.y)), iz = int(std::floor(p.z));
    float fx = smooth(p.x - float(ix)), fy = smooth(p.y - float(iy)), fz = smooth(p.z - float(iz));
    float v[2][2];
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy) {
            float a = lattice(ix, iy + dy, iz + dz, seed), b = lattice(ix + 1, iy + dy, iz + dz, seed);
            v[dz][dy] = a + (b - a) * fx;
        }
    float y0 = v[0][0] + (v[0][1] - v[0][0]) * fy, y1 = v[1][0] + (v[1][1] - v[1][0]) * fy;
    return y0 + (y1 - y0) * fz;
}

float fbm(Vec3 p, uint32_t seed) {
    float sum = 0, amp = 0.5f, norm = 0;
    for (int octave = 0; octave < 4; ++octave) {
        sum += amp * valueNoise(p, seed + uint32_t(octave));
        norm += amp;
        amp *= 0.5f;
        p = p * 2.03f + Vec3(17.1f, 3.7f, 9.2f);
    }
    return sum / norm;
}

float smoothstep(float e0, float e1, float x) {
    return smooth(clampValue((x - e0) / (e1 - e0), 0.0f, 1.0f));
}
}  // namespace

namespace {
constexpr float kWobble = 0.25f;  // lateral drift of the smoke column's axis

float smokeReach(const ProceduralSmoke& s) {
    return s.topRadius + kWobble + 2.0f * s.voxelSize;
}

void smokeDims(const ProceduralSmoke& s, int64_t dims[3]) {
    const double reach = smokeReach(s);
    dims[0] = dims[2] = int64_t(std::ceil(2.0 * reach / s.voxelSize)) + 1;
    dims[1] = int64_t(std::ceil(double(s.height) / s.voxelSize)) + 1;
}

void fogDims(const RollingFog& f, int64_t dims[3]) {
    for (int a = 0; a < 3; ++a) dims[a] = int64_t(std::ceil(double(f.hi[a] - f.lo[a]) / f.voxelSize)) + 1;
}

/// The product of the dimensions a grid would have, in doubles so that hostile parameters (a box
/// of 1e30, an infinite extent) saturate at UINT64_MAX instead of overflowing an integer.
uint64_t saturatingVoxelCount(double nx, double ny, double nz) {
    double n = nx * ny * nz;
    return n >= 1.8e19 || !(n == n) ? UINT64_MAX : uint64_t(n);
}
}  // namespace

uint64_t voxelCount(const ProceduralSmoke& s) {
    const double side = std::ceil(2.0 * smokeReach(s) / s.voxelSize) + 1;
    return saturatingVoxelCount(side, std::ceil(double(s.height) / s.voxelSize) + 1, side);
}

namespace {
constexpr float kFireSmokeSpread = 1.6f;  // the smoke column's radius at the top, in flame radii
constexpr float kFireWobble = 0.15f;      // lateral drift of the column's axis, in flame radii

void fireDims(const ProceduralFire& f, int64_t dims[3]) {
    const double reach = double(f.radius) * (kFireSmokeSpread + kFireWobble) + 2.0 * f.voxelSize;
    dims[0] = dims[2] = int64_t(std::ceil(2.0 * reach / f.voxelSize)) + 1;
    dims[1] = int64_t(std::ceil(double(f.height) / f.voxelSize)) + 1;
}
}  // namespace

uint64_t voxelCount(const ProceduralFire& f) {
    const double side = std::ceil(2.0 * (double(f.radius) * (kFireSmokeSpread + kFireWobble) + 2.0 * f.voxelSize) /
                                  f.voxelSize) + 1;  // as fireDims
    const uint64_t one = saturatingVoxelCount(side, std::ceil(double(f.height) / f.voxelSize) + 1, side);
    return one > UINT64_MAX / 2 ? UINT64_MAX : 2 * one;
}

uint64_t voxelCount(const RollingFog& f) {
    double n[3];
    for (int a = 0; a < 3; ++a) n[a] = std::ceil(double(f.hi[a] - f.lo[a]) / f.voxelSize) + 1;  // as fogDims
    return saturatingVoxelCount(n[0], n[1], n[2]);
}

std::shared_ptr<const VdbDensityGrid> makeProceduralSmoke(const ProceduralSmoke& s) {
    const float wobble = kWobble;
    const float reach = smokeReach(s);
    const Vec3 lo = s.base + Vec3(-reach, 0.0f, -reach);
    int64_t d64[3];
    smokeDims(s, d64);
    const int dims[3] = {int(d64[0]), int(d64[1]), int(d64[2])};
    std::vector<float> values(size_t(dims[0]) * dims[1] * dims[2], 0.0f);
    for (int k = 0; k < dims[2]; ++k)
        for (int j = 0; j < dims[1]; ++j) {
            const float y = float(j) * s.voxelSize;  // height above the foot
            const float h = y / s.height;
            const float radius = s.baseRadius + (s.topRadius - s.baseRadius) * std::sqrt(h);
            const Vec3 axis = s.base + Vec3(wobble * std::sin(2.3f * y + 0.5f), y, wobble * 0.6f * std::sin(1.7f * y));
            const float vertical = smoothstep(0.0f, 0.12f, h) * (1.0f - smoothstep(0.55f, 1.0f, h));
            for (int i = 0; i < dims[0]; ++i) {
                Vec3 p = lo + Vec3(float(i) * s.voxelSize, y, float(k) * s.voxelSize);
                float r = std::hypot(p.x - axis.x, p.z - axis.z);
                // Noise advected upward and swirled with height so the column breaks into billows.
                Vec3 q = Vec3(p.x + 0.3f * std::sin(1.3f * y), p.y * 0.8f, p.z + 0.3f * std::cos(1.1f * y));
                float n = fbm(q * s.noiseFrequency, s.seed);
                float edge = radius * (0.7f + 0.6f * n);
                float profile = 1.0f - smoothstep(0.45f * edge, edge, r);
                float d = vertical * profile * smoothstep(0.32f, 0.62f, n) * s.densityScale;
                values[(size_t(k) * dims[1] + j) * dims[0] + i] = d > 1e-3f * s.densityScale ? d : 0.0f;
            }
        }
    Affine3 indexToWorld = Affine3::scaleTranslate(Vec3(s.voxelSize), lo);
    return VdbDensityGrid::fromDense(dims, values, indexToWorld, "procedural smoke");
}

std::shared_ptr<const VdbDensityGrid> makeRollingFog(const RollingFog& f) {
    int64_t d64[3];
    fogDims(f, d64);
    const int dims[3] = {int(d64[0]), int(d64[1]), int(d64[2])};
    std::vector<float> values(size_t(dims[0]) * dims[1] * dims[2], 0.0f);
    const float inv = 1.0f / f.bankSize;
    for (int k = 0; k < dims[2]; ++k)
        for (int i = 0; i < dims[0]; ++i) {
            const float x = f.lo.x + float(i) * f.voxelSize, z = f.lo.z + float(k) * f.voxelSize;
            // The layer's local top rolls between 0.4x and 1.6x the mean thickness, in long banks.
            float banks = fbm(Vec3(x * inv, 0.37f, z * inv * 0.6f), f.seed);
            float top = f.layerHeight * (0.4f + 1.2f * smoothstep(0.3f, 0.7f, banks));
            for (int j = 0; j < dims[1]; ++j) {
                const float y = float(j) * f.voxelSize;
                // Densest on the ground, thinning with height and fading out over the top 40% of
                // the layer, with wisps: finer noise stretched along the banks.
                float profile = std::exp(-1.5f * y / top) * (1.0f - smoothstep(0.6f * top, top, y));
                if (profile <= 0) break;
                float wisps = fbm(Vec3(x * 2.5f * inv, y * 3.0f / f.layerHeight, z * 1.5f * inv), f.seed + 101);
                float d = profile * (0.35f + 0.65f * smoothstep(0.35f, 0.75f, wisps));
                values[(size_t(k) * dims[1] + j) * dims[0] + i] = d > 1e-3f ? d * f.densityScale : 0.0f;
            }
        }
    Affine3 indexToWorld = Affine3::scaleTranslate(Vec3(f.voxelSize), f.lo);
    return VdbDensityGrid::fromDense(dims, values, indexToWorld, "procedural rolling fog");
}

FireGrids makeProceduralFire(const ProceduralFire& f) {
    int64_t d64[3];
    fireDims(f, d64);
    const int dims[3] = {int(d64[0]), int(d64[1]), int(d64[2])};
    const float reach = float(d64[0] - 1) * 0.5f * f.voxelSize;
    const Vec3 lo = f.base + Vec3(-reach, 0.0f, -reach);
    const size_t n = size_t(dims[0]) * dims[1] * dims[2];
    std::vector<float> density(n, 0.0f), temperature(n, 0.0f);
    const float R = f.radius, top = std::max(f.flameHeight, 1e-3f);
    for (int j = 0; j < dims[1]; ++j) {
        const float y = float(j) * f.voxelSize;  // height above the foot
        const float hf = y / top, h = y / f.height;
        const Vec3 axis =
            f.base + Vec3(kFireWobble * R * std::sin(2.1f * y + 0.4f), y, kFireWobble * R * 0.7f * std::sin(1.6f * y));
        // Flames: a cone tapering to the tips; smoke: a column widening above them.
        const float flameRadius = R * std::pow(std::max(0.0f, 1.0f - 0.85f * hf), 0.7f);
        const float smokeRadius = R * (0.5f + (kFireSmokeSpread - 0.5f) * std::sqrt(clampValue(h, 0.0f, 1.0f)));
        const float cooling = 1.0f - 0.45f * clampValue(hf, 0.0f, 1.0f);  // the core cools as it rises
        const float smokeRise = smoothstep(0.5f * top, 1.1f * top, y) * (1.0f - smoothstep(0.6f * f.height, f.height, y));
        for (int k = 0; k < dims[2]; ++k)
            for (int i = 0; i < dims[0]; ++i) {
                const Vec3 p = lo + Vec3(float(i) * f.voxelSize, y, float(k) * f.voxelSize);
                const float r = std::hypot(p.x - axis.x, p.z - axis.z);
                // Noise advected upward (stretched vertically) so the flames break into tongues.
                const Vec3 q(p.x + 0.2f * std::sin(4.0f * y), p.y * 0.4f - 0.3f, p.z + 0.2f * std::cos(3.3f * y));
                const float n = fbm(q * f.noiseFrequency, f.seed);
                const float edge = flameRadius * (0.3f + 1.4f * n);
                const float flame = edge > 0 ? (1.0f - smoothstep(0.35f * edge, edge, r)) *
                                                   smoothstep(0.25f, 0.55f, n + 0.3f * (1.0f - hf))
                                             : 0.0f;
                const float core = std::exp(-(r * r) / (0.35f * R * R + 1e-12f));
                float t = f.temperature * flame * cooling * (0.75f + 0.25f * core);
                // The smoke above the flames: warm at first (dim red at most), cooling as it rises.
                const float m = fbm(q * (0.7f * f.noiseFrequency) + Vec3(5.3f, 1.1f, 2.9f), f.seed + 17);
                const float smokeEdge = smokeRadius * (0.7f + 0.6f * m);
                const float smoke = smokeRise * (1.0f - smoothstep(0.45f * smokeEdge, smokeEdge, r)) * smoothstep(0.3f, 0.6f, m);
                const float warm = 0.5f * f.temperature * std::exp(-3.0f * std::max(0.0f, y - top) / std::max(f.height - top, 1e-3f));
                t = std::max(t, smoke * warm);
                const float d = std::max(0.4f * flame, smoke) * f.densityScale;
                const size_t at = (size_t(k) * dims[1] + j) * dims[0] + i;
                density[at] = d > 1e-3f * f.densityScale ? d : 0.0f;
                temperature[at] = t > 0.01f * f.temperature ? t : 0.0f;
            }
    }
    const Affine3 indexToWorld = Affine3::scaleTranslate(Vec3(f.voxelSize), lo);
    FireGrids g;
    g.density = VdbDensityGrid::fromDense(dims, density, indexToWorld, "procedural fire (density)");
    g.temperature = VdbDensityGrid::fromDense(dims, temperature, indexToWorld, "procedural fire (temperature)");
    return g;
}

}  // namespace tyndall
