#include "core/medium_nesting.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.h"

namespace tyndall {

namespace {

// Double precision throughout: winding numbers and crossings near touching surfaces.
struct D3 {
    double x = 0, y = 0, z = 0;
};
D3 d3(const Vec3& v) { return {v.x, v.y, v.z}; }
D3 operator+(const D3& a, const D3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(const D3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(const D3& a, const D3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double len(const D3& a) { return std::sqrt(dot(a, a)); }

struct Box {
    D3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    void extend(const D3& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    bool overlaps(const Box& b, double eps) const {
        return lo.x <= b.hi.x + eps && b.lo.x <= hi.x + eps && lo.y <= b.hi.y + eps && b.lo.y <= hi.y + eps &&
               lo.z <= b.hi.z + eps && b.lo.z <= hi.z + eps;
    }
    bool contains(const D3& p, double eps) const {
        return p.x >= lo.x - eps && p.x <= hi.x + eps && p.y >= lo.y - eps && p.y <= hi.y + eps &&
               p.z >= lo.z - eps && p.z <= hi.z + eps;
    }
    double diagonal() const { return hi.x >= lo.x ? len(hi - lo) : 0.0; }
};

/// A mesh's triangles in double precision with a uniform grid over them, for the queries below.
class MeshGeometry {
public:
    explicit MeshGeometry(const TriangleMesh& mesh) {
        const size_t n = mesh.triangleCount();
        m_tris.reserve(n);
        for (size_t t = 0; t < n; ++t) {
            Tri tri{d3(mesh.vertex(t, 0)), d3(mesh.vertex(t, 1)), d3(mesh.vertex(t, 2))};
            m_tris.push_back(tri);
            for (const D3& v : {tri.a, tri.b, tri.c}) m_box.extend(v);
        }
        m_res = std::clamp(int(std::ceil(std::cbrt(double(n)))), 1, 48);
        for (int k = 0; k < 3; ++k) {
            double extent = k == 0 ? m_box.hi.x - m_box.lo.x : k == 1 ? m_box.hi.y - m_box.lo.y : m_box.hi.z - m_box.lo.z;
            m_cell[k] = std::max(extent / m_res, 1e-30);
        }
        // Counting sort of triangles into the cells their bounds overlap.
        std::vector<std::vector<uint32_t>> cells(size_t(m_res) * m_res * m_res);
        for (uint32_t t = 0; t < m_tris.size(); ++t) {
            Box b;
            for (const D3& v : {m_tris[t].a, m_tris[t].b, m_tris[t].c}) b.extend(v);
            forCells(b, [&](size_t c) { cells[c].push_back(t); });
        }
        m_start.push_back(0);
        for (const auto& c : cells) {
            m_items.insert(m_items.end(), c.begin(), c.end());
            m_start.push_back(uint32_t(m_items.size()));
        }
    }

    struct Tri {
        D3 a, b, c;
    };
    const std::vector<Tri>& triangles() const { return m_tris; }
    const Box& box() const { return m_box; }

    /// Calls f(triangle) for every triangle in a grid cell that `b` overlaps (repeats possible);
    /// stops and returns true as soon as f returns true.
    template <typename F>
    bool anyNear(const Box& b, F f) const {
        bool found = false;
        forCells(b, [&](size_t c) {
            for (uint32_t i = m_start[c]; i < m_start[c + 1] && !found; ++i) found = f(m_tris[m_items[i]]);
        });
        return found;
    }

private:
    template <typename F>
    void forCells(const Box& b, F f) const {
        if (!b.overlaps(m_box, 0.0)) return;
        int lo[3], hi[3];
        const double blo[3] = {b.lo.x, b.lo.y, b.lo.z}, bhi[3] = {b.hi.x, b.hi.y, b.hi.z};
        const double glo[3] = {m_box.lo.x, m_box.lo.y, m_box.lo.z};
        auto cell = [&](double v, int k) { return int(std::clamp(std::floor((v - glo[k]) / m_cell[k]), 0.0, m_res - 1.0)); };
        for (int k = 0; k < 3; ++k) lo[k] = cell(blo[k], k), hi[k] = cell(bhi[k], k);
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) f((size_t(z) * m_res + y) * m_res + x);
    }

    std::vector<Tri> m_tris;
    Box m_box;
    int m_res = 1;
    double m_cell[3] = {1, 1, 1};
    std::vector<uint32_t> m_start, m_items;
};

double windingNumber(const MeshGeometry& g, const D3& p) {
    // Van Oosterom and Strackee's solid angle of each triangle seen from p.
    double sum = 0;
    for (const MeshGeometry::Tri& t : g.triangles()) {
        D3 a = t.a - p, b = t.b - p, c = t.c - p;
        double la = len(a), lb = len(b), lc = len(c);
        double det = dot(a, cross(b, c));
        double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
        sum += 2.0 * std::atan2(det, den);
    }
    return sum / (4.0 * M_PI);
}

/// Distance from p to triangle t (Ericson, Real-Time Collision Detection, 5.1.5).
double distanceToTriangle(const D3& p, const MeshGeometry::Tri& t) {
    D3 ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
    double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return len(ap);
    D3 bp = p - t.b;
    double d3v = dot(ab, bp), d4 = dot(ac, bp);
    if (d3v >= 0 && d4 <= d3v) return len(bp);
    double vc = d1 * d4 - d3v * d2;
    if (vc <= 0 && d1 >= 0 && d3v <= 0) return len(p - (t.a + ab * (d1 / (d1 - d3v))));
    D3 cp = p - t.c;
    double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return len(cp);
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return len(p - (t.a + ac * (d2 / (d2 - d6))));
    double va = d3v * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3v) >= 0 && (d5 - d6) >= 0)
        return len(p - (t.b + (t.c - t.b) * ((d4 - d3v) / ((d4 - d3v) + (d5 - d6)))));
    double denom = 1.0 / (va + vb + vc);
    return len(p - (t.a + ab * (vb * denom) + ac * (vc * denom)));
}

bool onSurface(const MeshGeometry& g, const D3& p, double eps) {
    Box b;
    b.extend(p - D3{eps, eps, eps});
    b.extend(p + D3{eps, eps, eps});
    return g.anyNear(b, [&](const MeshGeometry::Tri& t) { return distanceToTriangle(p, t) <= eps; });
}

/// True when segment [p, q] passes through the inside of triangle t: its ends more than eps on
/// opposite sides of the plane, the crossing point more than eps inside every edge.
bool crossesTriangle(const D3& p, const D3& q, const MeshGeometry::Tri& t, double eps) {
    D3 n = cross(t.b - t.a, t.c - t.a);
    double nl = len(n);
    if (!(nl > 0)) return false;
    double sp = dot(n, p - t.a) / nl, sq = dot(n, q - t.a) / nl;
    if (!((sp > eps && sq < -eps) || (sp < -eps && sq > eps))) return false;
    D3 x = p + (q - p) * (sp / (sp - sq));
    const D3* v[3] = {&t.a, &t.b, &t.c};
    for (int k = 0; k < 3; ++k) {
        D3 e = *v[(k + 1) % 3] - *v[k];
        double el = len(e);
        if (!(el > 0) || dot(cross(e, x - *v[k]), n) / (nl * el) <= eps) return false;
    }
    return true;
}

/// Does any triangle edge of `a` cross a triangle of `b`?
bool edgesCross(const MeshGeometry& a, const MeshGeometry& b, double eps) {
    for (const MeshGeometry::Tri& t : a.triangles()) {
        const D3* v[3] = {&t.a, &t.b, &t.c};
        for (int k = 0; k < 3; ++k) {
            const D3 &p = *v[k], &q = *v[(k + 1) % 3];
            Box e;
            e.extend(p);
            e.extend(q);
            if (!e.overlaps(b.box(), eps)) continue;
            if (b.anyNear(e, [&](const MeshGeometry::Tri& s) { return crossesTriangle(p, q, s, eps); })) return true;
        }
    }
    return false;
}

Containment classify(const TriangleMesh& innerMesh, const MeshGeometry& inner, const MeshGeometry& outer,
                     size_t maxSamples) {
    Box both = inner.box();
    both.extend(outer.box().lo);
    both.extend(outer.box().hi);
    const double eps = 1e-6 * both.diagonal();
    if (!inner.box().overlaps(outer.box(), eps)) return Containment::Outside;
    bool in = false, out = false;
    const std::vector<Vec3>& pos = innerMesh.positions;
    for (const Vec3& v : pos) out |= !outer.box().contains(d3(v), eps);
    const size_t stride = std::max<size_t>(1, (pos.size() + maxSamples - 1) / maxSamples);
    auto sample = [&](const D3& p) {
        if (!outer.box().contains(p, eps) || onSurface(outer, p, eps)) return;
        (std::abs(windingNumber(outer, p)) > 0.5 ? in : out) = true;
    };
    for (size_t i = 0; i < pos.size(); i += stride) sample(d3(pos[i]));
    if (!in && !out) {
        // Every sampled vertex on the container's surface (a liquid filling the bottom of a glass):
        // the triangles' centres decide.
        const auto& tris = inner.triangles();
        const size_t step = std::max<size_t>(1, (tris.size() + maxSamples - 1) / maxSamples);
        for (size_t t = 0; t < tris.size(); t += step) sample((tris[t].a + tris[t].b + tris[t].c) * (1.0 / 3.0));
    }
    if (in && out) return Containment::Straddles;
    if (edgesCross(inner, outer, eps) || edgesCross(outer, inner, eps)) return Containment::Straddles;
    return in ? Containment::Inside : Containment::Outside;
}

std::string sceneLabel(const Scene& s) { return "scene '" + s.name + "' (" + s.source + ")"; }
std::string meshName(const Scene& s, size_t i) {
    return "mesh '" + s.meshes[i].name + "' (index " + std::to_string(i) + ")";
}

double signedVolume(const TriangleMesh& m) {
    double v = 0;
    for (size_t t = 0; t < m.triangleCount(); ++t) v += dot(d3(m.vertex(t, 0)), cross(d3(m.vertex(t, 1)), d3(m.vertex(t, 2))));
    return v / 6.0;
}

}  // namespace

double windingNumber(const TriangleMesh& mesh, const Vec3& p) { return windingNumber(MeshGeometry(mesh), d3(p)); }

Containment containment(const TriangleMesh& inner, const TriangleMesh& outer) {
    return classify(inner, MeshGeometry(inner), MeshGeometry(outer), 64);
}

void resolveNestedMedia(Scene& scene) {
    const size_t n = scene.meshes.size();
    auto material = [&](size_t m) -> const Material* {
        int i = scene.meshes[m].material;
        return i >= 0 && i < int(scene.materials.size()) ? &scene.materials[size_t(i)] : nullptr;
    };
    auto transmissive = [&](size_t m) { return material(m) && material(m)->isTransmissive(); };
    // An interior of its own: given explicitly and not just the exterior again.
    auto ownInterior = [&](size_t m) {
        const TriangleMesh& mesh = scene.meshes[m];
        return mesh.interiorMedium != kInheritMedium && mesh.interiorMedium != mesh.exteriorMedium;
    };

    // Malformed meshes (validate() reports them) take part as empty ones.
    auto wellFormed = [&](size_t m) {
        const TriangleMesh& mesh = scene.meshes[m];
        if (mesh.indices.size() % 3 != 0 || mesh.positions.empty()) return false;
        for (uint32_t i : mesh.indices)
            if (i >= mesh.positions.size()) return false;
        for (const Vec3& p : mesh.positions)
            if (!isFinite(p)) return false;
        return true;
    };

    std::vector<char> container(n, 0), outward(n, 1), matters(n, 0), valid(n, 0);
    std::vector<size_t> containers;
    for (size_t m = 0; m < n; ++m) {
        valid[m] = wellFormed(m);
        if (!valid[m]) continue;
        if ((transmissive(m) || ownInterior(m)) && scene.meshes[m].isClosed()) {
            container[m] = 1;
            outward[m] = signedVolume(scene.meshes[m]) >= 0;
            containers.push_back(m);
        }
        matters[m] = container[m] || transmissive(m) || ownInterior(m) || (material(m) && material(m)->isEmissive());
    }

    std::vector<std::unique_ptr<MeshGeometry>> geometry(n);
    auto geom = [&](size_t m) -> const MeshGeometry& {
        if (!geometry[m]) geometry[m] = std::make_unique<MeshGeometry>(scene.meshes[m]);
        return *geometry[m];
    };
    // Containers of each mesh. Meshes whose media do not matter are placed by one vertex.
    std::vector<std::vector<size_t>> inside(n);
    std::vector<std::pair<size_t, size_t>> straddles;  // (mesh, container), judged once media are known
    for (size_t b = 0; b < n && !containers.empty(); ++b) {
        if (!valid[b]) continue;
        for (size_t a : containers) {
            if (a == b) continue;
            Containment c;
            if (matters[b]) {
                c = classify(scene.meshes[b], geom(b), geom(a), 64);
            } else {
                const D3 p = d3(scene.meshes[b].positions[0]);
                c = geom(a).box().contains(p, 0.0) && std::abs(windingNumber(geom(a), p)) > 0.5 ? Containment::Inside
                                                                                               : Containment::Outside;
            }
            if (c == Containment::Straddles) straddles.push_back({b, a});
            if (c == Containment::Inside) inside[b].push_back(a);
        }
    }

    // Outer meshes first: a container's inside medium is resolved before the meshes it holds.
    std::vector<size_t> order(n);
    for (size_t m = 0; m < n; ++m) order[m] = m;
    std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) { return inside[x].size() < inside[y].size(); });
    for (size_t b : order) {
        int innermost = -1;
        for (size_t a : inside[b]) {
            if (innermost >= 0 && inside[a].size() == inside[size_t(innermost)].size())
                throw Error(sceneLabel(scene) + ": " + meshName(scene, b) + " lies inside both " +
                            meshName(scene, size_t(innermost)) + " and " + meshName(scene, a) +
                            ", and neither contains the other: closed meshes that bound media must not overlap");
            if (innermost < 0 || inside[a].size() > inside[size_t(innermost)].size()) innermost = int(a);
        }
        MediumId around = scene.globalMedium;
        if (innermost >= 0) {
            const TriangleMesh& c = scene.meshes[size_t(innermost)];
            around = outward[size_t(innermost)] ? c.interiorMedium : c.exteriorMedium;
        }
        TriangleMesh& mesh = scene.meshes[b];
        if (mesh.exteriorMedium == kInheritMedium) mesh.exteriorMedium = around;
        if (mesh.interiorMedium == kInheritMedium) {
            if (container[b] && !outward[b] && innermost >= 0)
                mesh.interiorMedium = around;
            else
                mesh.interiorMedium = transmissive(b) && mesh.isClosed() ? kVacuum : mesh.exteriorMedium;
        }
    }
    // Straddling a container matters only where its two sides hold different media (two glass
    // objects that intersect in vacuum are fine; in fog they are not: glass holds no fog).
    for (const auto& [b, a] : straddles) {
        const TriangleMesh& c = scene.meshes[a];
        if (c.interiorMedium == c.exteriorMedium) continue;
        throw Error(sceneLabel(scene) + ": " + meshName(scene, b) + " lies partly inside and partly outside " +
                    meshName(scene, a) +
                    ", which bounds a medium: a mesh that bounds a medium, lets light through or emits it must lie "
                    "wholly inside or wholly outside every medium-bounding mesh (move it, or split it at the boundary)");
    }
}

}  // namespace tyndall
