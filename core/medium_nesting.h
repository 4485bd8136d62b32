#pragma once
// Nested media: which medium surrounds each mesh, found once at load time (Scene::finalize) from
// how the meshes lie inside one another, so that smoke in a glass jar in fog, a lamp in a foggy
// lantern and a liquid in a glass in a room need no per-mesh bookkeeping.
//
// A *container* is a closed mesh a path can enter: a transmissive material (dielectric,
// interface), or any closed mesh given an interior medium of its own. Its *inside medium* is the
// medium on its geometric inside: the interior of an outward-facing mesh, the exterior of an
// inward-facing one (the cavity of a hollow object, `"inward": true`). A mesh lies inside a
// container when its vertices have winding number +-1 with respect to it and its surface does not
// cross the container's; vertices on the container's surface (within 1e-6 of the pair's size)
// count neither way, so a mesh resting on a container's surface from outside is outside it. The
// *innermost* container of a mesh is the one that lies inside all its other containers.
//
// Medium slots still kInheritMedium are resolved as follows (explicit slots are kept as given):
//   - exterior: the inside medium of the innermost container; the global medium when there is none;
//   - interior of an inward-facing mesh inside a container: the same medium (the space between the
//     two holds the container's medium);
//   - interior otherwise: vacuum for a closed transmissive mesh (a glass ball in fog holds no fog),
//     else the exterior (an open sheet has the same medium on both sides; an opaque mesh is never
//     entered).
// Refused, with an Error naming both meshes and the scene: a mesh whose media matter (a container,
// a transmissive or emissive mesh, or one given an interior medium) that lies partly inside and
// partly outside a container whose two sides hold different media (two glass balls that intersect
// in vacuum are fine, in fog they are not); a mesh inside two containers neither of which contains
// the other (coincident containers). Opaque, non-emissive meshes may cross containers freely (a
// floor running through a fog box): no path takes its medium from them.
#include <string>

#include "core/scene.h"

namespace tyndall {

/// How a mesh lies with respect to a closed mesh.
enum class Containment { Outside, Inside, Straddles };

/// Generalised winding number of the closed mesh `mesh` at `p`: the signed solid angle of its
/// triangles seen from p over 4 pi, in double precision. +1 inside an outward-facing (counter-
/// clockwise seen from outside) mesh, -1 inside an inward-facing one, 0 outside; fractional on the
/// surface.
double windingNumber(const TriangleMesh& mesh, const Vec3& p);

/// Where `inner` lies with respect to the closed mesh `outer` (see the file comment): Straddles
/// when its sampled vertices fall on both sides or a triangle edge of either mesh crosses a
/// triangle of the other (touching is not crossing). Up to 64 vertices of `inner` are sampled.
Containment containment(const TriangleMesh& inner, const TriangleMesh& outer);

/// Resolves the inherited medium slots of every mesh of `scene` by containment (file comment);
/// throws Error for the refused cases. Needs materials and media in place; called by
/// Scene::finalize() before anything reads a mesh's media.
void resolveNestedMedia(Scene& scene);

}  // namespace tyndall
