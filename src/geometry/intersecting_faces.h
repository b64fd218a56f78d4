// Pairs of intersecting triangles found by a simultaneous traversal of two BVHs (or of one BVH
// with itself): self-intersections of an offset surface, crossings between an inner and an
// outer surface. Face tests are geometry/triangle_triangle.h.
//
// Within one mesh, faces that share vertices touch by construction and only count when they
// overlap beyond what they share: two faces on a common edge intersect when they are folded onto
// each other (normals opposite within 1e-9 rad); two faces on a common vertex intersect when the
// edge opposite that vertex in one meets the other. Faces sharing all three vertices (duplicates)
// are reported. Between two meshes, faces are unrelated and any contact counts.
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

// (face of a, face of b) pairs that intersect. Stops after `max_pairs` pairs.
IntersectingFaces intersecting_faces(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs = 1000);

// The rule above for two faces of one mesh, exposed for tests.
bool mesh_faces_intersect(const TriangleBvh& bvh, int f, int g);

}  // namespace offsetopt
