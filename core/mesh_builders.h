#pragma once
// Procedural meshes for the built-in scenes and tests. All are counter-clockwise seen from the
// side their normal points to.
#include "core/scene.h"

namespace tyndall {

/// Parallelogram corner + a, corner + b; normal along cross(a, b).
TriangleMesh makeQuad(const std::string& name, const Vec3& corner, const Vec3& a, const Vec3& b, int material);
/// Axis-aligned box, closed; normals point out (`inward` = false) or in.
TriangleMesh makeBox(const std::string& name, const Vec3& lo, const Vec3& hi, int material, bool inward = false);
/// Geodesic sphere from a subdivided icosahedron (20 * 4^subdivisions triangles), closed,
/// outward, with exact per-vertex normals for smooth shading.
TriangleMesh makeSphere(const std::string& name, const Vec3& center, float radius, int subdivisions, int material);
/// Closed cylinder around the segment a -> b with `segments` sides, outward, flat-capped.
TriangleMesh makeCylinder(const std::string& name, const Vec3& a, const Vec3& b, float radius, int segments, int material);

}  // namespace tyndall
