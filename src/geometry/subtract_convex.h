// A closed solid minus a small closed cutter (a convex prism: a drain hole, a channel, a box above
// a liquid level), as one closed, oriented, embedded triangle mesh: the boolean difference of
// Manifold's kind (exact signs, shared symbolic vertices), written for the case where the cutter
// is ours to move.
//
// Every topological decision is the sign of orient3d of input points (geometry/
// exact_triangle_intersection.h: exact), never a tolerance:
//   - a solid vertex inside the cutter: negative against the plane of every cutter triangle
//     (the cutter is convex);
//   - a solid edge crosses a cutter triangle, a cutter edge crosses a solid face: its ends on
//     opposite sides of the triangle's plane and the three orient3d(edge, triangle edge) of one sign;
//   - the intersection segment of a solid face f and a cutter triangle g runs along d = n_f × n_g;
//     which of its two ends comes first along d follows from the same signs (the edge of f where d
//     enters f is the one whose head is on g's positive side).
// A new vertex is a symbol, (solid edge, cutter triangle) or (cutter edge, solid face), created once
// and shared by every face that uses it, so the result is watertight whatever its coordinates
// (computed once from the symbol's lower-numbered end). The solid faces that are cut are
// re-triangulated (their part outside the cutter: geometry/triangulate_polygons.h, exact 2-D
// orientation), and the cutter's triangles keep their part inside the solid, reversed.
//
// General position is required, not assumed: any zero sign, an edge crossed more often than a
// convex cutter allows, crossings along a cutter edge closer than 1e-9 of it (ordered in floating
// point), an inconsistent inside/outside along an edge, or a face that cannot be triangulated gives
// status `degenerate`, and the caller moves its cutter (a tiny deterministic turn) and tries again.
#pragma once
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

enum class SubtractStatus { ok, degenerate, bad_input };

struct SubtractResult {
  SubtractStatus status = SubtractStatus::ok;
  std::string message;
  Mesh mesh;                       // solid minus cutter, unreferenced vertices removed
  // Per face of `mesh`: the solid face it copies unchanged, or -1 (a re-triangulated solid face or
  // a piece of the cutter).
  std::vector<int> source_face;
  int cut_solid_faces = 0;         // solid faces re-triangulated
  int removed_solid_faces = 0;     // solid faces wholly inside the cutter
  int cutter_faces_kept = 0;       // cutter triangles with a part inside the solid
  int new_vertices = 0;            // (edge, triangle) crossings
  bool touched = false;            // the cutter met the solid
};

// `solid`: closed, oriented (normals out of the material), possibly several shells (a cavity written
// reversed). `cutter`: a closed convex triangle mesh, normals out, far smaller than the solid.
SubtractResult subtract_convex(const Mesh& solid, const Mesh& cutter);

}  // namespace offsetopt
