#include "loading/mesh_builders.h"

#include <map>

#include "core/rng.h"
#include "core/sampling.h"

namespace tyndall {

TriangleMesh makeQuad(const std::string& name, const Vec3& corner, const Vec3& a, const Vec3& b, int material) {
    TriangleMesh m;
    m.name = name;
    m.material = material;
    m.positions = {corner, corner + a, corner + a + b, corner + b};
    m.texcoords[0] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // u along a, v along b
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

TriangleMesh makeBox(const std::string& name, const Vec3& lo, const Vec3& hi, int material, bool inward) {
    TriangleMesh m;
    m.name = name;
    m.material = material;
    for (int i = 0; i < 8; ++i)
        m.positions.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
    // Faces as quads (outward CCW).
    const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : quads) {
        if (!inward) {
            m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        } else {
            m.indices.insert(m.indices.end(), {q[0], q[2], q[1], q[0], q[3], q[2]});
        }
    }
    return m;
}

namespace {

/// Unit directions and faces of an icosahedron subdivided `subdivisions` times (outward CCW).
void geodesic(int subdivisions, std::vector<Vec3>* dirs, std::vector<uint32_t>* faces) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& p : v) p = normalize(p);
    std::vector<uint32_t> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(normalize(v[a] + v[b]));
            return mid[key] = uint32_t(v.size() - 1);
        };
        std::vector<uint32_t> next;
        for (size_t i = 0; i < f.size(); i += 3) {
            uint32_t a = f[i], b = f[i + 1], c = f[i + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        f.swap(next);
    }
    dirs->swap(v);
    faces->swap(f);
}

/// Appends triangle (a, b, c), reversed if needed so its normal has a positive component along `want`.
void pushFacing(TriangleMesh& m, uint32_t a, uint32_t b, uint32_t c, const Vec3& want) {
    Vec3 n = cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
    if (dot(n, want) >= 0)
        m.indices.insert(m.indices.end(), {a, b, c});
    else
        m.indices.insert(m.indices.end(), {a, c, b});
}

}  // namespace

TriangleMesh makeSphere(const std::string& name, const Vec3& center, float radius, int subdivisions, int material) {
    std::vector<Vec3> v;
    std::vector<uint32_t> f;
    geodesic(subdivisions, &v, &f);
    TriangleMesh m;
    m.name = name;
    m.material = material;
    m.normals = v;
    for (const Vec3& n : v) m.positions.push_back(center + n * radius);
    m.indices = f;
    return m;
}

TriangleMesh makeCylinder(const std::string& name, const Vec3& a, const Vec3& b, float radius, int segments,
                          int material) {
    TriangleMesh m;
    m.name = name;
    m.material = material;
    Frame frame(normalize(b - a));
    uint32_t n = uint32_t(segments);
    for (uint32_t i = 0; i < n; ++i) {
        float phi = 2.0f * kPi * float(i) / float(n);
        Vec3 off = (frame.s * std::cos(phi) + frame.t * std::sin(phi)) * radius;
        m.positions.push_back(a + off);
        m.positions.push_back(b + off);
    }
    uint32_t ca = uint32_t(m.positions.size()), cb = ca + 1;
    m.positions.push_back(a);
    m.positions.push_back(b);
    for (uint32_t i = 0; i < n; ++i) {
        uint32_t j = (i + 1) % n;
        uint32_t a0 = 2 * i, b0 = 2 * i + 1, a1 = 2 * j, b1 = 2 * j + 1;
        m.indices.insert(m.indices.end(), {a0, a1, b1, a0, b1, b0});  // side, outward
        m.indices.insert(m.indices.end(), {ca, a1, a0});              // cap at a, facing -axis
        m.indices.insert(m.indices.end(), {cb, b0, b1});              // cap at b, facing +axis
    }
    return m;
}

}  // namespace tyndall

namespace tyndall {

TriangleMesh makeBumpySphere(const std::string& name, const Vec3& center, float radius, int subdivisions,
                             float amplitude, float frequency, int bumps, uint32_t seed, int material) {
    std::vector<Vec3> dirs;
    std::vector<uint32_t> faces;
    geodesic(subdivisions, &dirs, &faces);
    Rng rng(seed, 0x6275u);
    std::vector<Vec3> waveDir(size_t(std::max(bumps, 0)));
    std::vector<float> wavePhase(waveDir.size());
    for (size_t k = 0; k < waveDir.size(); ++k) {
        waveDir[k] = sampleUniformSphere(rng.uniform(), rng.uniform());
        wavePhase[k] = 2.0f * kPi * rng.uniform();
    }
    float norm = bumps > 0 ? std::sqrt(2.0f / float(bumps)) : 0.0f;  // unit RMS for random phases
    TriangleMesh m;
    m.name = name;
    m.material = material;
    for (const Vec3& n : dirs) {
        float f = 0.0f;
        for (size_t k = 0; k < waveDir.size(); ++k) f += std::sin(frequency * dot(n, waveDir[k]) + wavePhase[k]);
        m.positions.push_back(center + n * (radius * (1.0f + amplitude * norm * f)));
    }
    m.indices = faces;
    computeVertexNormals(m);
    return m;
}

TriangleMesh makeWaterVolume(const std::string& name, const Vec3& top, float sizeX, float sizeZ, float depth, int resX,
                             int resZ, const std::vector<SurfaceWave>& waves, int material) {
    struct Wave {
        float a, k, dx, dz, phase;
    };
    std::vector<Wave> ws;
    for (const SurfaceWave& w : waves) {
        float len = std::sqrt(w.dirX * w.dirX + w.dirZ * w.dirZ);
        float dx = len > 0 ? w.dirX / len : 1.0f, dz = len > 0 ? w.dirZ / len : 0.0f;
        ws.push_back({w.amplitude, 2.0f * kPi / w.wavelength, dx, dz, w.phase});
    }
    auto height = [&](float x, float z, float* dhdx, float* dhdz) {
        float h = 0.0f;
        *dhdx = *dhdz = 0.0f;
        for (const Wave& w : ws) {
            float arg = w.k * (w.dx * x + w.dz * z) + w.phase;
            h += w.a * std::sin(arg);
            float d = w.a * w.k * std::cos(arg);
            *dhdx += d * w.dx;
            *dhdz += d * w.dz;
        }
        return h;
    };
    TriangleMesh m;
    m.name = name;
    m.material = material;
    const uint32_t nx = uint32_t(resX) + 1, nz = uint32_t(resZ) + 1;
    std::vector<Vec3> topGrid(size_t(nx) * nz), bottomGrid(size_t(nx) * nz);
    const float bottomY = top.y - depth;
    for (uint32_t j = 0; j < nz; ++j) {
        for (uint32_t i = 0; i < nx; ++i) {
            float lx = sizeX * (float(i) / float(resX) - 0.5f), lz = sizeZ * (float(j) / float(resZ) - 0.5f);
            float gx, gz;
            float h = height(lx, lz, &gx, &gz);
            topGrid[j * nx + i] = {top.x + lx, top.y + h, top.z + lz};
            bottomGrid[j * nx + i] = {top.x + lx, bottomY, top.z + lz};
            m.positions.push_back(topGrid[j * nx + i]);
            m.normals.push_back(normalize(Vec3(-gx, 1.0f, -gz)));
        }
    }
    for (uint32_t j = 0; j + 1 < nz; ++j) {
        for (uint32_t i = 0; i + 1 < nx; ++i) {
            uint32_t v00 = j * nx + i, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
            pushFacing(m, v00, v01, v11, {0, 1, 0});
            pushFacing(m, v00, v11, v10, {0, 1, 0});
        }
    }
    // Bottom and sides: flat, their own vertices (closedness welds by position).
    auto flat = [&](const Vec3& p, const Vec3& n) {
        m.positions.push_back(p);
        m.normals.push_back(n);
        return uint32_t(m.positions.size() - 1);
    };
    const Vec3 down{0, -1, 0};
    uint32_t bottomBase = uint32_t(m.positions.size());
    for (const Vec3& p : bottomGrid) flat(p, down);
    for (uint32_t j = 0; j + 1 < nz; ++j) {
        for (uint32_t i = 0; i + 1 < nx; ++i) {
            uint32_t v00 = bottomBase + j * nx + i, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
            pushFacing(m, v00, v11, v01, down);
            pushFacing(m, v00, v10, v11, down);
        }
    }
    auto side = [&](uint32_t a, uint32_t b, const Vec3& out) {  // grid indices of one border edge
        uint32_t t0 = flat(topGrid[a], out), t1 = flat(topGrid[b], out);
        uint32_t b1 = flat(bottomGrid[b], out), b0 = flat(bottomGrid[a], out);
        pushFacing(m, t0, t1, b1, out);
        pushFacing(m, t0, b1, b0, out);
    };
    for (uint32_t i = 0; i + 1 < nx; ++i) {
        side(i, i + 1, {0, 0, -1});
        side((nz - 1) * nx + i, (nz - 1) * nx + i + 1, {0, 0, 1});
    }
    for (uint32_t j = 0; j + 1 < nz; ++j) {
        side(j * nx, (j + 1) * nx, {-1, 0, 0});
        side(j * nx + nx - 1, (j + 1) * nx + nx - 1, {1, 0, 0});
    }
    return m;
}

TriangleMesh makeParaboloid(const std::string& name, const Vec3& apex, const Vec3& axis, float focalLength,
                            float innerRadius, float outerRadius, int rings, int segments, int material) {
    Frame frame(normalize(axis));
    TriangleMesh m;
    m.name = name;
    m.material = material;
    const uint32_t ns = uint32_t(segments);
    auto vertex = [&](float r, float phi) {
        Vec3 radial = frame.s * std::cos(phi) + frame.t * std::sin(phi);
        m.positions.push_back(apex + frame.n * (r * r / (4.0f * focalLength)) + radial * r);
        m.normals.push_back(normalize(frame.n - radial * (r / (2.0f * focalLength))));
    };
    const bool fan = innerRadius <= 0.0f;
    if (fan) {
        m.positions.push_back(apex);
        m.normals.push_back(frame.n);
    }
    const uint32_t firstRing = fan ? 1u : 0u;
    const uint32_t base = uint32_t(m.positions.size());
    for (uint32_t k = firstRing; k <= uint32_t(rings); ++k) {
        float r = innerRadius + (outerRadius - innerRadius) * float(k) / float(rings);
        for (uint32_t i = 0; i < ns; ++i) vertex(r, 2.0f * kPi * float(i) / float(ns));
    }
    auto at = [&](uint32_t k, uint32_t i) { return base + (k - firstRing) * ns + (i % ns); };
    for (uint32_t i = 0; i < ns && fan; ++i) pushFacing(m, 0, at(1, i), at(1, i + 1), frame.n);
    for (uint32_t k = firstRing; k < uint32_t(rings); ++k) {
        for (uint32_t i = 0; i < ns; ++i) {
            Vec3 want = m.normals[at(k, i)] + m.normals[at(k + 1, i + 1)];  // the concave side
            pushFacing(m, at(k, i), at(k + 1, i), at(k + 1, i + 1), want);
            pushFacing(m, at(k, i), at(k + 1, i + 1), at(k, i + 1), want);
        }
    }
    return m;
}

TriangleMesh makeLens(const std::string& name, const Vec3& center, const Vec3& axis, float radius, float thickness,
                      float curvatureRadius, int rings, int segments, int material) {
    Frame frame(normalize(axis));
    const float R = curvatureRadius;
    TriangleMesh m;
    m.name = name;
    m.material = material;
    const uint32_t ns = uint32_t(segments);
    // Cap `side` (+1 front, -1 back): apex at center + side * thickness/2 * axis; sphere centre
    // behind it at distance R; the normal is the outward sphere normal.
    auto cap = [&](float side) {
        Vec3 apexP = center + frame.n * (side * 0.5f * thickness);
        Vec3 sphereC = apexP - frame.n * (side * R);
        uint32_t apexI = uint32_t(m.positions.size());
        m.positions.push_back(apexP);
        m.normals.push_back(frame.n * side);
        std::vector<uint32_t> ring;
        for (uint32_t k = 1; k <= uint32_t(rings); ++k) {
            float r = radius * float(k) / float(rings);
            float z = R - std::sqrt(std::max(R * R - r * r, 0.0f));  // depth below the apex
            for (uint32_t i = 0; i < ns; ++i) {
                float phi = 2.0f * kPi * float(i) / float(ns);
                Vec3 p = apexP - frame.n * (side * z) + (frame.s * std::cos(phi) + frame.t * std::sin(phi)) * r;
                m.positions.push_back(p);
                m.normals.push_back(normalize(p - sphereC));
            }
        }
        auto at = [&](uint32_t k, uint32_t i) { return apexI + 1 + (k - 1) * ns + (i % ns); };
        for (uint32_t i = 0; i < ns; ++i) pushFacing(m, apexI, at(1, i), at(1, i + 1), frame.n * side);
        for (uint32_t k = 1; k < uint32_t(rings); ++k)
            for (uint32_t i = 0; i < ns; ++i) {
                Vec3 want = m.normals[at(k, i)];
                pushFacing(m, at(k, i), at(k + 1, i), at(k + 1, i + 1), want);
                pushFacing(m, at(k, i), at(k + 1, i + 1), at(k, i + 1), want);
            }
        for (uint32_t i = 0; i < ns; ++i) ring.push_back(at(uint32_t(rings), i));
        return ring;
    };
    std::vector<uint32_t> front = cap(1.0f), back = cap(-1.0f);
    for (uint32_t i = 0; i < ns; ++i) {
        uint32_t j = (i + 1) % ns;
        Vec3 out = m.positions[front[i]] + m.positions[front[j]] - center * 2.0f;
        out = out - frame.n * dot(out, frame.n);
        Vec3 a = m.positions[front[i]], b = m.positions[front[j]], c = m.positions[back[j]], d = m.positions[back[i]];
        uint32_t base = uint32_t(m.positions.size());
        for (const Vec3& p : {a, b, c, d}) {
            m.positions.push_back(p);
            m.normals.push_back(normalize(out));
        }
        pushFacing(m, base, base + 1, base + 2, out);
        pushFacing(m, base, base + 2, base + 3, out);
    }
    return m;
}

TriangleMesh makePerforatedSphere(const std::string& name, const Vec3& center, float radius, int subdivisions,
                                  int holes, float holeAngle, int material) {
    std::vector<Vec3> dirs;
    std::vector<uint32_t> faces;
    geodesic(subdivisions, &dirs, &faces);
    std::vector<Vec3> holeDirs;
    const float golden = kPi * (3.0f - std::sqrt(5.0f));
    for (int k = 0; k < holes; ++k) {
        float y = 1.0f - 2.0f * (float(k) + 0.5f) / float(holes);
        float r = safeSqrt(1.0f - y * y);
        holeDirs.push_back({r * std::cos(golden * float(k)), y, r * std::sin(golden * float(k))});
    }
    const float cosHole = std::cos(holeAngle);
    TriangleMesh m;
    m.name = name;
    m.material = material;
    for (const Vec3& d : dirs) m.positions.push_back(center + d * radius);
    for (size_t i = 0; i < faces.size(); i += 3) {
        Vec3 c = normalize(dirs[faces[i]] + dirs[faces[i + 1]] + dirs[faces[i + 2]]);
        bool open = false;
        for (const Vec3& h : holeDirs) open |= dot(c, h) > cosHole;
        if (!open) m.indices.insert(m.indices.end(), {faces[i], faces[i + 1], faces[i + 2]});
    }
    return m;
}

void transformMesh(TriangleMesh& mesh, const Affine& t) {
    for (Vec3& p : mesh.positions) p = t.point(p);
    for (Vec3& n : mesh.normals) {
        Vec3 tn = t.normal(n);
        float len = length(tn);
        n = len > 0 ? tn / len : n;
    }
    if (t.determinant() < 0)
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
}

void computeVertexNormals(TriangleMesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), Vec3(0.0f));
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
        Vec3 n = mesh.geometricNormal(t);  // length = 2 x area: area weighting for free
        for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[3 * t + k]] += n;
    }
    for (Vec3& n : mesh.normals) {
        float len = length(n);
        n = len > 0 ? n / len : Vec3(0, 1, 0);
    }
}

}  // namespace tyndall
