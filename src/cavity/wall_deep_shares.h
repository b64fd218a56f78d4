// How much of each generous cell can lie a wall deep (docs/reachability.md "Cells a wall deep in
// part"): per cell of CarvableCells::outer, an upper bound of the share of its cube whose points
// are at least `wall` from the surface, in [0, 1].
//
// The generous reading counts a whole cell wherever the cell may hold a point a wall deep, so it
// reaches up to half a cell diagonal nearer the surface than the wall, and a goal just past what
// any void reaches can stay undecided (a sphere's largest void, 1.5% short of a target, was
// not proved). A point within `wall` of a point of the surface is less than a wall deep, so a
// cell near the wall keeps only what the balls of radius `wall` about the surface's closest points
// to its 8 corners leave, and the ball about the centre's closest point on those corners' faces
// (any surface point will do): counted on sub-cubes of side h / 2^levels, a sub-cube
// dropped when one ball holds it whole (its farthest corner lies within the radius; a ball is
// convex), kept when no ball reaches into it, split otherwise, and kept at the last level. Cells
// whose centre lies at least wall + half a diagonal deep keep 1 without a query.
//
// Not for the --outer reading, whose generous cells keep the wall from material added outside.
// The same result for any `threads` (>= 1).
#pragma once
#include <vector>

#include "cavity/carvable_cells.h"
#include "geometry/bvh.h"

namespace offsetopt {

struct WallDeepShares {
  std::vector<double> share;      // per cells.outer
  std::int64_t shell_cells = 0;   // cells that needed the balls
  std::int64_t queries = 0;       // distance queries (the shell's corners, and the band count's)
};

WallDeepShares wall_deep_shares(const CarvableCells& cells, const TriangleBvh& surface, double wall, int levels, int threads);

}  // namespace offsetopt
