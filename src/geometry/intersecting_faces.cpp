#include "geometry/intersecting_faces.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <iterator>

#include "geometry/exact_triangle_intersection.h"
#include "geometry/faces_intersect_exact.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

// The rule for two faces whose corners are known not to be collinear. Faces on exactly one
// common corner whose far edges both lie apart from the other face's box are faces_intersect_exact's
// first shortcut, taken here on the tree's packed corners and face boxes before anything is
// copied: most pairs a search meets are such neighbours.
bool planar_faces_intersect(const TriangleBvh& bvh, int f, int g) {
  const auto& F = bvh.faces();
  const int ids_f[3] = {F(f, 0), F(f, 1), F(f, 2)}, ids_g[3] = {F(g, 0), F(g, 1), F(g, 2)};
  int shared = 0, in_f = 0, in_g = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ids_f[i] == ids_g[j]) {
        ++shared;
        in_f = i;
        in_g = j;
      }
  if (shared == 1) {
    // The far edge of `face` (its corners other than corner `c`) apart from the box of `other`.
    auto far_edge_apart = [&bvh](int face, int c, int other) {
      return bvh.face_box(other).apart_from_segment(bvh.corner(face, c == 0 ? 1 : 0), bvh.corner(face, c == 2 ? 1 : 2));
    };
    if (far_edge_apart(g, in_g, f) && far_edge_apart(f, in_f, g)) return false;
  }
  const Eigen::Vector3d a[3] = {bvh.corner(f, 0), bvh.corner(f, 1), bvh.corner(f, 2)};
  const Eigen::Vector3d b[3] = {bvh.corner(g, 0), bvh.corner(g, 1), bvh.corner(g, 2)};
  return faces_intersect_exact(a, ids_f, b, ids_g);
}

bool collinear_face(const TriangleBvh& bvh, int f) { return collinear_exact(bvh.corner(f, 0), bvh.corner(f, 1), bvh.corner(f, 2)); }

}  // namespace

bool mesh_faces_intersect(const TriangleBvh& bvh, int f, int g) {
  if (collinear_face(bvh, f) || collinear_face(bvh, g)) return false;
  return planar_faces_intersect(bvh, f, g);
}

bool unrelated_faces_meet(const Eigen::Vector3d a[3], const Eigen::Vector3d b[3]) {
  const bool flat_a = collinear_exact(a[0], a[1], a[2]), flat_b = collinear_exact(b[0], b[1], b[2]);
  if (flat_a && flat_b) return false;  // neither has a plane: both are reported by themselves
  if (!flat_a && !flat_b) return triangles_meet_exact(a, b);
  // A collinear triangle is the union of its edges.
  const Eigen::Vector3d* line = flat_a ? a : b;
  const Eigen::Vector3d* face = flat_a ? b : a;
  for (int k = 0; k < 3; ++k)
    if (line[k] != line[(k + 1) % 3] && segment_meets_triangle_exact(line[k], line[(k + 1) % 3], face[0], face[1], face[2]))
      return true;
  return false;
}

namespace {

// Adds a pair; false (stop searching) once there are max_pairs.
bool record_pair(IntersectingFaces& out, int f, int g, std::size_t max_pairs) {
  out.pairs.emplace_back(f, g);
  if (out.pairs.size() < max_pairs) return true;
  out.truncated = true;
  return false;
}

IntersectingFaces self_intersections_from(const TriangleBvh& bvh, std::vector<std::pair<int, int>> start, std::size_t max_pairs,
                                          const std::vector<char>* known = nullptr) {
  IntersectingFaces out;
  // Collinearity once per face, on demand (each face meets about 15 candidates), unless known.
  std::vector<signed char> collinear(known ? 0 : static_cast<std::size_t>(bvh.faces().rows()), -1);
  auto flat = [&](int f) {
    if (known) return (*known)[static_cast<std::size_t>(f)] != 0;
    signed char& c = collinear[static_cast<std::size_t>(f)];
    if (c < 0) c = collinear_face(bvh, f) ? 1 : 0;
    return c == 1;
  };
  traverse_face_pairs(bvh, bvh, true, std::move(start), [&](int f, int g) {
    if (!bvh.face_box(f).overlaps(bvh.face_box(g)) || flat(f) || flat(g) || !planar_faces_intersect(bvh, f, g)) return true;
    return record_pair(out, std::min(f, g), std::max(f, g), max_pairs);
  }, true);
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

}  // namespace

IntersectingFaces self_intersections(const TriangleBvh& bvh, std::size_t max_pairs) {
  return self_intersections_from(bvh, {{0, 0}}, max_pairs);
}

IntersectingFaces self_intersections_part(const TriangleBvh& bvh, int part, std::size_t max_pairs,
                                          const std::vector<char>* collinear) {
  if (bvh.empty()) return {};
  const BvhNode& root = bvh.nodes().front();
  if (root.is_leaf()) return part == 0 ? self_intersections_from(bvh, {{0, 0}}, max_pairs, collinear) : IntersectingFaces{};
  // Popped last-in first-out, as self_intersections would descend from the root.
  if (part == 0) return self_intersections_from(bvh, {{root.left, root.right}, {root.left, root.left}}, max_pairs, collinear);
  return self_intersections_from(bvh, {{root.right, root.right}}, max_pairs, collinear);
}

IntersectingFaces merge_intersections(const IntersectingFaces& a, const IntersectingFaces& b, std::size_t max_pairs) {
  IntersectingFaces out;
  out.pairs.reserve(a.pairs.size() + b.pairs.size());
  std::merge(a.pairs.begin(), a.pairs.end(), b.pairs.begin(), b.pairs.end(), std::back_inserter(out.pairs));
  out.truncated = a.truncated || b.truncated;
  if (out.pairs.size() > max_pairs) {
    out.pairs.resize(max_pairs);
    out.truncated = true;
  }
  return out;
}

IntersectingFaces self_intersections_in_parts(const TriangleBvh& bvh, std::size_t max_pairs, int threads,
                                              const std::vector<char>* collinear) {
  IntersectingFaces parts[2];
  WorkerPool pool(std::min(std::max(threads, 1), 2));
  pool.run_parts(2, [&](int part) { parts[part] = self_intersections_part(bvh, part, max_pairs, collinear); });
  return merge_intersections(parts[0], parts[1], max_pairs);
}

namespace {

IntersectingFaces intersecting_faces_from(const TriangleBvh& a, const TriangleBvh& b, std::vector<std::pair<int, int>> start,
                                          std::size_t max_pairs) {
  IntersectingFaces out;
  traverse_face_pairs(a, b, false, std::move(start), [&](int f, int g) {
    if (!a.face_box(f).overlaps(b.face_box(g))) return true;
    const Eigen::Vector3d p[3] = {a.corner(f, 0), a.corner(f, 1), a.corner(f, 2)};
    const Eigen::Vector3d q[3] = {b.corner(g, 0), b.corner(g, 1), b.corner(g, 2)};
    if (!unrelated_faces_meet(p, q)) return true;
    return record_pair(out, f, g, max_pairs);
  }, true);
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

}  // namespace

IntersectingFaces intersecting_faces(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs) {
  return intersecting_faces_from(a, b, {{0, 0}}, max_pairs);
}

IntersectingFaces intersecting_faces_in_parts(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs, int threads) {
  if (a.empty() || b.empty()) return {};
  const BvhNode& root = a.nodes().front();
  if (root.is_leaf()) return intersecting_faces(a, b, max_pairs);
  IntersectingFaces parts[2];
  WorkerPool pool(std::min(std::max(threads, 1), 2));
  pool.run_parts(2, [&](int part) {
    parts[part] = intersecting_faces_from(a, b, {{part == 0 ? root.left : root.right, 0}}, max_pairs);
  });
  // Each part's pairs are sorted and the parts' faces of `a` disjoint: the merge is their union.
  return merge_intersections(parts[0], parts[1], max_pairs);
}

}  // namespace offsetopt
