#pragma once
// Tangent frames for normal maps (glTF normalTexture).
//
// glTF's convention: TANGENT = (T, w) per vertex, the bitangent is B = w cross(N, T), and a normal
// map texel (r, g, b) is the normal (2r - 1, 2g - 1, 2b - 1) in the frame (T, B, N), +x along T
// (+u), +y along B ("up" in the image: glTF's v grows downward, so B ~ -dP/dv when w = +1).
//
// When a normal-mapped mesh has no TANGENT, glTF asks for MikkTSpace tangents. Debian ships no
// MikkTSpace library, so generateTangents() does what MikkTSpace does in the common case: per
// triangle, dP/du and dP/dv from the texture coordinates; accumulated per vertex weighted by the
// triangle's angle at that vertex; T made perpendicular to the vertex normal (Gram-Schmidt); the
// sign w from whether the accumulated dP/dv agrees with cross(N, T) (mirrored uv gives w = -1).
// Differences from MikkTSpace (documented in docs/algorithm.md): vertices are not split where the
// tangent frames of neighbouring triangles disagree (mirrored-uv seams within one shared vertex, or
// opposite handedness meeting at a vertex), and dP/du and dP/dv are not normalised per triangle
// before accumulation (MikkTSpace's "magnitude" handling differs there). Models with such seams
// should carry TANGENT, which exporters write by default.
#include <cstdint>

#include "core/scene.h"

namespace tyndall {

/// Fills mesh.tangents / tangentSigns from mesh.normals and TEXCOORD_`set`. Needs per-vertex normals
/// and that set of texture coordinates (does nothing without them: the hit then builds a flat frame
/// per triangle, normalMapFrame). Vertices whose triangles have degenerate uv get an arbitrary
/// tangent perpendicular to the normal.
void generateTangents(TriangleMesh& mesh, int set);

/// The unnormalised dP/du and dP/dv of triangle `tri` in TEXCOORD_`set` (glTF uv); false when the
/// uv triangle is degenerate or the set is absent.
bool triangleUvDerivatives(const TriangleMesh& mesh, int set, uint32_t tri, Vec3* dpdu, Vec3* dpdv);

/// The tangent frame at (tri, b1, b2): N the interpolated vertex normal (or `ng`, the unit
/// geometric normal, for meshes without normals), on ng's side; T unit, perpendicular to N; B =
/// w cross(N, T). From the mesh's tangents when present, else from the triangle's uv derivatives.
struct TangentFrame {
    Vec3 t, b, n;
};
TangentFrame normalMapFrame(const TriangleMesh& mesh, int set, uint32_t tri, float b1, float b2, const Vec3& ng);

/// The shading normal for a tangent-space normal `m` (already scaled, not necessarily unit) in
/// `frame`, kept at least kMinHorizonCos above the geometric surface `ng` (a normal map can tilt the
/// normal below the geometric horizon; it is then bent back toward ng, as Cycles and pbrt do, so
/// that reflection never sends a path through the surface). m = (0, 0, 1) returns frame.n exactly.
Vec3 perturbedNormal(const TangentFrame& frame, const Vec3& m, const Vec3& ng);
inline constexpr float kMinHorizonCos = 0.02f;

}  // namespace tyndall
