// Pairs of intersecting triangles found by a simultaneous traversal of two BVHs (or of one BVH
// with itself): self-intersections of an offset surface or a cavity, crossings between an inner
// and an outer surface. Every decision is exact (geometry/exact_triangle_intersection.h).
//
// Within one mesh the rule is geometry/faces_intersect_exact.h's (CGAL's self_intersections
// semantics) with corners compared by vertex index: faces on a common edge count only when
// coplanar and folded onto each other, faces on a common vertex when the edge opposite it in one
// meets the other, duplicates always; faces with collinear corners are not tested (a caller that
// must refuse them counts them itself). Between two meshes, faces are unrelated and any contact
// counts; a collinear face is tested as its edges.
#pragma once
#include <utility>
#include <vector>

#include "geometry/bvh.h"

namespace offsetopt {

struct IntersectingFaces {
  std::vector<std::pair<int, int>> pairs;  // sorted; within one mesh first < second
  bool truncated = false;                  // stopped at max_pairs
};

// Faces of one mesh that intersect each other. Stops after `max_pairs` pairs.
IntersectingFaces self_intersections(const TriangleBvh& bvh, std::size_t max_pairs = 1000);

// Part `part` (0 or 1) of self_intersections, to run the two on two threads: part 0 the pairs
// within the root's left subtree and across its two subtrees, part 1 those within the right
// subtree. Merged by merge_intersections they are self_intersections' pairs, unless truncated.
// `collinear`, when given, holds collinear_exact of each face's corners (1 or 0, one per face of
// the tree's mesh), which the search would otherwise decide itself.
IntersectingFaces self_intersections_part(const TriangleBvh& bvh, int part, std::size_t max_pairs = 1000,
                                          const std::vector<char>* collinear = nullptr);

// The sorted union of two disjoint results, at most `max_pairs` of them (truncated if either was).
IntersectingFaces merge_intersections(const IntersectingFaces& a, const IntersectingFaces& b, std::size_t max_pairs);

// self_intersections' pairs as its two parts merged, the parts on two threads when `threads` > 1:
// the same result for any count (and self_intersections' own unless truncated, when the two
// stop at different pairs). `collinear` as for self_intersections_part.
IntersectingFaces self_intersections_in_parts(const TriangleBvh& bvh, std::size_t max_pairs, int threads,
                                              const std::vector<char>* collinear = nullptr);

// (face of a, face of b) pairs that intersect. Stops after `max_pairs` pairs.
IntersectingFaces intersecting_faces(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs = 1000);

// intersecting_faces' pairs in two parts (below the root of `a` left and right, `a` not a
// single leaf), the parts on two threads when `threads` > 1: the same result for any count, and
// intersecting_faces' own unless truncated.
IntersectingFaces intersecting_faces_in_parts(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs, int threads);

// The rule above for two faces of one mesh, exposed for tests.
bool mesh_faces_intersect(const TriangleBvh& bvh, int f, int g);

// The rule above for two faces of different meshes.
bool unrelated_faces_meet(const Eigen::Vector3d a[3], const Eigen::Vector3d b[3]);

}  // namespace offsetopt
