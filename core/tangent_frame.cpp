#include "core/tangent_frame.h"

#include <cmath>

namespace tyndall {

namespace {
Vec3 anyPerpendicular(const Vec3& n) { return Frame(n).s; }

Vec3 orthogonalTo(const Vec3& n, const Vec3& t) {
    Vec3 p = t - n * dot(n, t);
    float len = length(p);
    return len > 1e-12f && std::isfinite(len) ? p / len : anyPerpendicular(n);
}

float angleAt(const Vec3& a, const Vec3& b, const Vec3& c) {  // at a, between b - a and c - a
    Vec3 u = b - a, v = c - a;
    float lu = length(u), lv = length(v);
    if (!(lu > 0 && lv > 0)) return 0.0f;
    return std::acos(std::max(-1.0f, std::min(1.0f, dot(u, v) / (lu * lv))));
}
}  // namespace

bool triangleUvDerivatives(const TriangleMesh& mesh, int set, uint32_t tri, Vec3* dpdu, Vec3* dpdv) {
    const std::vector<Vec2>& uv = mesh.texcoords[set];
    if (uv.empty()) return false;
    const uint32_t* idx = &mesh.indices[3 * size_t(tri)];
    Vec3 e1 = mesh.positions[idx[1]] - mesh.positions[idx[0]], e2 = mesh.positions[idx[2]] - mesh.positions[idx[0]];
    float du1 = uv[idx[1]].x - uv[idx[0]].x, dv1 = uv[idx[1]].y - uv[idx[0]].y;
    float du2 = uv[idx[2]].x - uv[idx[0]].x, dv2 = uv[idx[2]].y - uv[idx[0]].y;
    float det = du1 * dv2 - du2 * dv1;
    if (!(std::abs(det) > 1e-20f)) return false;
    float inv = 1.0f / det;
    *dpdu = (e1 * dv2 - e2 * dv1) * inv;
    *dpdv = (e2 * du1 - e1 * du2) * inv;
    return std::isfinite(length(*dpdu)) && std::isfinite(length(*dpdv));
}

void generateTangents(TriangleMesh& mesh, int set) {
    const size_t nv = mesh.positions.size();
    if (mesh.normals.size() != nv || mesh.texcoords[set].size() != nv) return;
    std::vector<Vec3> tAcc(nv), bAcc(nv);
    for (uint32_t tri = 0; tri < mesh.triangleCount(); ++tri) {
        Vec3 dpdu, dpdv;
        if (!triangleUvDerivatives(mesh, set, tri, &dpdu, &dpdv)) continue;
        for (int k = 0; k < 3; ++k) {
            uint32_t v = mesh.indices[3 * size_t(tri) + k];
            float w = angleAt(mesh.vertex(tri, k), mesh.vertex(tri, (k + 1) % 3), mesh.vertex(tri, (k + 2) % 3));
            tAcc[v] += dpdu * w;
            bAcc[v] += dpdv * w;
        }
    }
    mesh.tangents.resize(nv);
    mesh.tangentSigns.resize(nv);
    for (size_t v = 0; v < nv; ++v) {
        const Vec3& n = mesh.normals[v];
        mesh.tangents[v] = orthogonalTo(n, tAcc[v]);
        // glTF's v grows downward: a right-handed (w = +1) frame has dP/dv along -cross(N, T).
        mesh.tangentSigns[v] = dot(cross(n, mesh.tangents[v]), bAcc[v]) > 0 ? -1.0f : 1.0f;
    }
}

TangentFrame normalMapFrame(const TriangleMesh& mesh, int set, uint32_t tri, float b1, float b2, const Vec3& ng) {
    const uint32_t* idx = &mesh.indices[3 * size_t(tri)];
    const float b0 = 1.0f - b1 - b2;
    TangentFrame f;
    f.n = ng;
    if (!mesh.normals.empty()) {
        Vec3 n = mesh.normals[idx[0]] * b0 + mesh.normals[idx[1]] * b1 + mesh.normals[idx[2]] * b2;
        float len = length(n);
        if (len > 0 && std::isfinite(len)) f.n = dot(n, ng) < 0 ? -n / len : n / len;
    }
    float w = 1.0f;
    Vec3 t;
    if (!mesh.tangents.empty()) {
        t = mesh.tangents[idx[0]] * b0 + mesh.tangents[idx[1]] * b1 + mesh.tangents[idx[2]] * b2;
        float s = mesh.tangentSigns[idx[0]] * b0 + mesh.tangentSigns[idx[1]] * b1 + mesh.tangentSigns[idx[2]] * b2;
        w = s < 0 ? -1.0f : 1.0f;
    } else {
        Vec3 dpdu, dpdv;
        if (triangleUvDerivatives(mesh, set, tri, &dpdu, &dpdv)) {
            t = dpdu;
            w = dot(cross(f.n, dpdu), dpdv) > 0 ? -1.0f : 1.0f;
        }
    }
    f.t = orthogonalTo(f.n, t);
    f.b = cross(f.n, f.t) * w;
    return f;
}

Vec3 perturbedNormal(const TangentFrame& frame, const Vec3& m, const Vec3& ng) {
    if (m.x == 0.0f && m.y == 0.0f && m.z > 0.0f) return frame.n;
    Vec3 n = frame.t * m.x + frame.b * m.y + frame.n * m.z;
    float len = length(n);
    if (!(len > 0 && std::isfinite(len))) return frame.n;
    n = n / len;
    float c = dot(n, ng);
    if (c < kMinHorizonCos) n = normalize(n + ng * (kMinHorizonCos - c) * 1.01f);
    return n;
}

}  // namespace tyndall
