// Triangulation of planar polygons with holes by ear clipping (Meisters 1975, "Polygons have
// ears") after joining each hole to its enclosing boundary by a bridge to a visible vertex
// (Eberly 2002, "Triangulation by Ear Clipping"), on the exact orientation predicate of
// geometry/convex_hull_2d.h, then Lawson edge flips (Lawson 1977) against slivers. No point is
// added: every triangle corner is an input point.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace offsetopt {

enum class TriangulationStatus { ok, degenerate_loop, unenclosed_hole, no_ear, too_many_steps };

struct PolygonTriangulation {
  TriangulationStatus status = TriangulationStatus::ok;
  std::string message;
  // Counter-clockwise triangles over global point indices: loop 0's points first, then loop 1's...
  std::vector<std::array<int, 3>> triangles;
  int outer_loops = 0;
  int holes = 0;
};

// `loops` are closed, pairwise disjoint, simple polygons (last point joined to the first):
// counter-clockwise ones are outer boundaries, clockwise ones holes, each hole inside the
// smallest outer boundary around it (islands inside holes are outer boundaries again).
// Collinear points are kept and used.
PolygonTriangulation triangulate_polygons(const std::vector<std::vector<Eigen::Vector2d>>& loops);

// Twice the signed area (shoelace formula), positive for counter-clockwise.
double twice_signed_area(const std::vector<Eigen::Vector2d>& loop);

}  // namespace offsetopt
