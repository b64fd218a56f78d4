// A flat base for a solid that touches the ground in a point or a line (issue 13): cut the
// closed surface with the horizontal plane H above its lowest point, drop everything below and
// close the cut with planar cap polygons (holes included) facing −z, as slicers' "cut" does.
// Cap polygons are triangulated by ear clipping after bridging holes (triangulate_polygons.h).
//
// Exactness: the plane is z = zmin + H rounded to a double. Vertices within 1e-6 of the diagonal
// of it are first moved onto it (z only; FlattenOptions::snap). A vertex exactly on it counts as
// above and stays (the limit of a plane slightly below it): an edge from below to it is cut at
// the vertex itself, and pieces of faces that shrink to a point or a segment vanish. Every other
// cut edge has one end strictly on each side; its crossing point gets z equal to the plane's
// height exactly and x, y interpolated from the lower end, once per edge, so both faces share
// it. The cap's boundary is the kept surface's boundary, all of it in the plane.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

struct FlattenOptions {
  double height = 0.0;  // H above the lowest vertex, mesh units, > 0 and below the top
  // Vertices closer to the plane than this fraction of the bounding-box diagonal are moved onto
  // it (z only) before the cut, so no sliver of a near-zero height is left next to the cap.
  double snap = 1e-6;
  std::string check() const;
};

enum class FlattenStatus { ok, bad_options, cuts_everything, cap_failed };

struct FlattenResult {
  FlattenStatus status = FlattenStatus::ok;
  std::string message;
  Mesh mesh;                   // the kept part and the cap, closed and outward-oriented
  double plane_z = 0.0;        // the cut plane's height
  int removed_vertices = 0;    // input vertices below the plane
  int snapped_vertices = 0;    // vertices moved onto the plane (by at most snap x diagonal)
  int cut_edges = 0;           // points on the cut polygons (edge crossings, vertices on the plane)
  int cap_loops = 0;           // cut polygons: outer boundaries + holes
  int cap_holes = 0;
  int cap_faces = 0;           // the last cap_faces faces of mesh are the cap
  // The cut polygons, counter-clockwise seen from above for outer boundaries, clockwise for holes.
  std::vector<std::vector<Eigen::Vector2d>> loops;
};

// `mesh` must be closed, edge-manifold and outward-oriented (as load_mesh returns it).
FlattenResult flatten_base(const Mesh& mesh, const FlattenOptions& settings);

}  // namespace offsetopt
