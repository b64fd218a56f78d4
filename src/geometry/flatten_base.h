// A flat base for a solid that touches the ground in a point or a line (issue 13): cut the
// closed surface with the horizontal plane H above its lowest point, drop everything below and
// close the cut with planar cap polygons (holes included) facing −z, as slicers' "cut" does.
// Cap polygons are triangulated by ear clipping after bridging holes (triangulate_polygons.h).
//
// Exactness: no vertex is ever on the plane. The plane's height is z = zmin + H rounded to a
// double; while some vertex has exactly that z it is moved down to the next double (a vertex
// on the plane counts as above it, and stays). Then every cut edge has one end strictly below
// and one strictly above, its crossing point gets z equal to the plane's height exactly, and x,
// y interpolated from the lower end (so both faces of the edge share one point).
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

struct FlattenSettings {
  double height = 0.0;  // H above the lowest vertex, mesh units, > 0 and below the top
  std::string check() const;
};

enum class FlattenStatus { ok, bad_settings, cuts_everything, cap_failed };

struct FlattenResult {
  FlattenStatus status = FlattenStatus::ok;
  std::string message;
  Mesh mesh;                   // the kept part and the cap, closed and outward-oriented
  double plane_z = 0.0;        // the cut plane's height
  int removed_vertices = 0;    // input vertices below the plane
  int cut_edges = 0;           // edges crossing it (= points on the cut polygons)
  int cap_loops = 0;           // cut polygons: outer boundaries + holes
  int cap_holes = 0;
  int cap_faces = 0;           // the last cap_faces faces of mesh are the cap
  // The cut polygons, counter-clockwise seen from above for outer boundaries, clockwise for holes.
  std::vector<std::vector<Eigen::Vector2d>> loops;
};

// `mesh` must be closed, edge-manifold and outward-oriented (as load_mesh returns it).
FlattenResult flatten_base(const Mesh& mesh, const FlattenSettings& settings);

}  // namespace offsetopt
