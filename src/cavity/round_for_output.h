// The surfaces of a result as they will read back from the files written (docs/design.md
// "Verification": verify the bytes written). OBJ, PLY and 3MF keep every double; STL stores
// float32 (meshio/write_mesh.h, stored_precision), and rounding a vertex by up to half a float
// ulp (6e-8 of its largest coordinate) can make nearly coplanar faces of a CAD part cross, or
// put a cavity vertex a hair closer to the outer surface than the wall.
//
// So the meshes are rounded here, before the final verification, and the rounding is repaired
// where it creates a defect the unrounded mesh did not have: a face pair that intersects by the
// exact rule (geometry/intersecting_faces.h) but did not before, or a face whose corners became
// collinear. Each vertex of such a face is moved to another float32 point near its own (up to
// kRoundingSearchUlps ulps per coordinate, the fewest ulps first), keeping the choice that leaves
// the fewest new defects around it; at most kRoundingRepairRounds passes. What cannot be
// repaired is counted, and the verification refuses it (cavity/verify_offsets.h).
//
// Lengths in input units; the meshes keep their connectivity and vertex order.
#pragma once
#include <memory>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "mesh/mesh.h"
#include "meshio/write_mesh.h"

namespace offsetopt {

constexpr int kRoundingSearchUlps = 2;
constexpr int kRoundingRepairRounds = 4;
constexpr std::size_t kRoundingPairCap = 100000;

struct RoundedForOutput {
  Mesh outer, inner;                  // as they read back
  long long outer_new_pairs = 0;      // defects the rounding made and the repair could not undo:
  long long inner_new_pairs = 0;      // new intersecting face pairs, new collinear faces
  int vertices_moved = 0;             // vertices not at their nearest float32 point
  int repair_rounds = 0;
  // The self-intersecting face pairs of `inner` as it is now (geometry/intersecting_faces.h's
  // search, capped at kRoundingPairCap), kept so the verification need not search it again: the
  // repair's last search was of this very mesh (geometry/intersecting_faces.h's
  // self_intersections_in_parts). Not searched with StoredPrecision::exact.
  bool inner_searched = false;
  IntersectingFaces inner_pairs;
  std::shared_ptr<const TriangleBvh> inner_tree;  // the tree of that search (default leaf size)
  std::shared_ptr<const TriangleBvh> outer_tree;  // the tree of `outer` as it is now (default leaf size)
};

// `shared` (empty, or one flag per vertex when outer and inner share connectivity) marks inner
// vertices that are the outer vertex of the same index (an opening): they take its rounding.
// With StoredPrecision::exact the meshes come back unchanged. `threads` (>= 1): the searches in
// two parts on two threads when > 1; the result is the same for any count.
RoundedForOutput round_for_output(const Mesh& outer, const Mesh& inner, const std::vector<char>& shared,
                                  StoredPrecision precision, int threads = 2);

// How far rounding (repairs included) can move the distance between a cavity vertex and the
// outer surface: twice the largest vertex displacement, for coordinates below `largest_coordinate`
// in magnitude. The contour keeps this much more than the wall, so the wall survives the rounding.
double rounding_wall_margin(double largest_coordinate, StoredPrecision precision);

}  // namespace offsetopt
