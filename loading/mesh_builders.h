#pragma once
// Procedural meshes for the built-in scenes and tests. All are counter-clockwise seen from the
// side their normal points to.
#include <vector>

#include "core/scene.h"
#include "core/transform.h"

namespace tyndall {

/// Parallelogram corner + a, corner + b; normal along cross(a, b).
TriangleMesh makeQuad(const std::string& name, const Vec3& corner, const Vec3& a, const Vec3& b, int material);
/// Axis-aligned box, closed; normals point out (`inward` = false) or in.
TriangleMesh makeBox(const std::string& name, const Vec3& lo, const Vec3& hi, int material, bool inward = false);
/// Geodesic sphere from a subdivided icosahedron (20 * 4^subdivisions triangles), closed,
/// outward, with exact per-vertex normals for smooth shading.
TriangleMesh makeSphere(const std::string& name, const Vec3& center, float radius, int subdivisions, int material);
/// Closed cylinder around the segment a -> b with `segments` sides, outward, flat-capped.
TriangleMesh makeCylinder(const std::string& name, const Vec3& a, const Vec3& b, float radius, int segments,
                          int material);

/// Geodesic sphere (as makeSphere) whose radius is modulated by a smooth random bump field:
/// r(n) = radius * (1 + amplitude * sum of `bumps` sinusoidal plane waves of angular frequency
/// `frequency` over the unit direction n, normalised to unit RMS). Deterministic in `seed`.
/// Closed, outward, with area-weighted vertex normals.
TriangleMesh makeBumpySphere(const std::string& name, const Vec3& center, float radius, int subdivisions,
                             float amplitude, float frequency, int bumps, uint32_t seed, int material);

/// One sinusoidal surface wave: height amplitude * sin(2 pi / wavelength * dot(direction, (x, z)) + phase).
struct SurfaceWave {
    float amplitude = 0;       ///< scene units
    float wavelength = 1;      ///< scene units, > 0
    float dirX = 1, dirZ = 0;  ///< horizontal travel direction (normalised by the builder)
    float phase = 0;           ///< radians
};
/// A closed water volume: the top is the height field y = top.y + sum of `waves` over the
/// rectangle centred on `top` with extents sizeX x sizeZ, sampled on a resX x resZ grid of quads;
/// sides and a flat bottom at top.y - depth close it. Outward; smooth analytic normals on the
/// top, flat elsewhere.
TriangleMesh makeWaterVolume(const std::string& name, const Vec3& top, float sizeX, float sizeZ, float depth, int resX,
                             int resZ, const std::vector<SurfaceWave>& waves, int material);

/// Open paraboloid reflector around `axis` (opening direction) with its apex at `apex`:
/// height along the axis h(r) = r^2 / (4 focalLength) for innerRadius <= r <= outerRadius
/// (innerRadius > 0 leaves a hole at the apex for a lamp). The focus lies at apex + axis * focalLength.
/// `rings` x `segments` quads; normals face the concave (focus) side.
TriangleMesh makeParaboloid(const std::string& name, const Vec3& apex, const Vec3& axis, float focalLength,
                            float innerRadius, float outerRadius, int rings, int segments, int material);

/// Symmetric biconvex lens centred at `center` with optical axis `axis`: two spherical caps of
/// curvature radius `curvatureRadius` over an aperture of radius `radius`, `thickness` apart on the
/// axis, joined by a cylindrical rim. Closed, outward, smooth normals on the caps. Requires
/// curvatureRadius >= radius and an edge thickness (thickness - 2 sagitta) >= 0.
TriangleMesh makeLens(const std::string& name, const Vec3& center, const Vec3& axis, float radius, float thickness,
                      float curvatureRadius, int rings, int segments, int material);

/// Faceted geodesic sphere (flat shading, 20 * 4^subdivisions facets) with `holes` round openings
/// of angular radius `holeAngle` (radians) centred on a Fibonacci spiral of directions: the
/// facets whose centre lies inside a hole are left out. Open when holes > 0; normals outward.
TriangleMesh makePerforatedSphere(const std::string& name, const Vec3& center, float radius, int subdivisions,
                                  int holes, float holeAngle, int material);

/// Applies `t` to positions and normals; reverses the winding when t mirrors (det < 0) so the
/// exterior side stays the side the normals point to.
void transformMesh(TriangleMesh& mesh, const Affine& t);
/// Area-weighted vertex normals from the triangles (for smooth shading of displaced surfaces).
void computeVertexNormals(TriangleMesh& mesh);

}  // namespace tyndall
