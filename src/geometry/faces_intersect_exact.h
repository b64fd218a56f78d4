// The pair rule of a self-intersection search, shared by `check` (geometry/mesh_defects.h) and
// the optimiser's verification (geometry/intersecting_faces.h): whether two faces of one mesh
// meet other than where the mesh joins them, with CGAL's semantics
// (Polygon_mesh_processing::self_intersections on exact predicates), decided exactly
// (geometry/exact_triangle_intersection.h):
//   - no shared corner: the closed triangles meet (touching counts);
//   - one shared corner: the edge opposite it in either face meets the other face;
//   - two shared corners (a common edge): the four corners are coplanar and the two third
//     corners lie on the same side of the common edge (the faces are folded onto each other);
//     coplanar neighbours on opposite sides merely continue one flat surface;
//   - three (a duplicate face): always.
// Both faces must have a plane (collinear_exact false): CGAL reports a collinear face by itself
// and tests it against nothing. Corners are compared by id; pass ids that are equal exactly when
// the positions are (a reader that merges duplicate points, as CGAL's, sees one vertex there).
#pragma once
#include <Eigen/Core>

namespace offsetopt {

bool faces_intersect_exact(const Eigen::Vector3d f[3], const int f_ids[3], const Eigen::Vector3d g[3], const int g_ids[3]);

}  // namespace offsetopt
