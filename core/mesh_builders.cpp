#include "core/mesh_builders.h"

#include <map>

namespace tyndall {

TriangleMesh makeQuad(const std::string& name, const Vec3& corner, const Vec3& a, const Vec3& b, int material) {
    TriangleMesh m;
    m.name = name;
    m.material = material;
    m.positions = {corner, corner + a, corner + a + b, corner + b};
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

TriangleMesh makeSphere(const std::string& name, const Vec3& center, float radius, int subdivisions, int material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (Vec3& p : v) p = normalize(p);
    std::vector<uint32_t> f = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,
                               11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8,
                               3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
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
    TriangleMesh m;
    m.name = name;
    m.material = material;
    m.normals = v;
    for (const Vec3& n : v) m.positions.push_back(center + n * radius);
    m.indices = f;
    return m;
}

TriangleMesh makeCylinder(const std::string& name, const Vec3& a, const Vec3& b, float radius, int segments, int material) {
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
