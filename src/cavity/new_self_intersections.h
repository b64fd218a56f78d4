// Self-intersections of a moved surface that its source did not have: the check that an outer
// offset surface (the input's connectivity, its vertices moved by the thickening) adds no crossing
// to the solid. Face pairs (f, g), f < g, numbered as rows of surface.F, found by
// geometry/intersecting_faces.h's rule (one search of the whole surface through its BVH); a pair
// listed in `own_pairs` (the source's pairs, found by the same rule on the source) is the
// source's own and is not counted. Matching pairs, not counts: a thickening that removes one of
// the input's crossings and adds another is reported.
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

struct NewSelfIntersections {
  long long pairs = 0;         // pairs not in own_pairs, at most the cap
  long long own_pairs_kept = 0;  // pairs that are the source's own
  bool truncated = false;      // the search stopped at its cap: there may be more
  int first_face = -1, second_face = -1;  // the smallest new pair, or -1
  std::vector<std::pair<int, int>> new_pairs;  // sorted, `pairs` of them
};

// `own_pairs` sorted (as IntersectingFaces::pairs are). `threads` (>= 1): the search in two parts
// on two threads when > 1; the result is the same for any count.
NewSelfIntersections new_self_intersections(const Mesh& surface, const std::vector<std::pair<int, int>>& own_pairs,
                                            std::size_t cap = 100000, int threads = 2);

}  // namespace offsetopt
