#include "geometry/intersecting_faces.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <iterator>

#include "geometry/triangle_triangle.h"

namespace offsetopt {

bool mesh_faces_intersect(const TriangleBvh& bvh, int f, int g) {
  const auto& F = bvh.faces();
  std::array<int, 3> shared_in_f{}, shared_in_g{};
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (F(f, i) == F(g, j)) {
        shared_in_f[static_cast<std::size_t>(shared)] = i;
        shared_in_g[static_cast<std::size_t>(shared)] = j;
        ++shared;
      }
  const Eigen::Vector3d p1 = bvh.corner(f, 0), q1 = bvh.corner(f, 1), r1 = bvh.corner(f, 2);
  const Eigen::Vector3d p2 = bvh.corner(g, 0), q2 = bvh.corner(g, 1), r2 = bvh.corner(g, 2);
  if (shared == 0) return triangles_intersect(p1, q1, r1, p2, q2, r2);
  if (shared >= 3) return true;
  if (shared == 2) {
    const Eigen::Vector3d nf = (q1 - p1).cross(r1 - p1), ng = (q2 - p2).cross(r2 - p2);
    const double sine = nf.cross(ng).norm(), scale = nf.norm() * ng.norm();
    return nf.dot(ng) < 0.0 && sine <= 1e-9 * scale;
  }
  // One shared vertex: test the opposite edge of each face against the other face.
  const int sf = shared_in_f[0], sg = shared_in_g[0];
  const Eigen::Vector3d fa = bvh.corner(f, (sf + 1) % 3), fb = bvh.corner(f, (sf + 2) % 3);
  const Eigen::Vector3d ga = bvh.corner(g, (sg + 1) % 3), gb = bvh.corner(g, (sg + 2) % 3);
  return segment_intersects_triangle(fa, fb, p2, q2, r2) || segment_intersects_triangle(ga, gb, p1, q1, r1);
}

namespace {

// Adds a pair; false (stop searching) once there are max_pairs.
bool record_pair(IntersectingFaces& out, int f, int g, std::size_t max_pairs) {
  out.pairs.emplace_back(f, g);
  if (out.pairs.size() < max_pairs) return true;
  out.truncated = true;
  return false;
}

IntersectingFaces self_intersections_from(const TriangleBvh& bvh, std::vector<std::pair<int, int>> start, std::size_t max_pairs) {
  IntersectingFaces out;
  traverse_face_pairs(bvh, bvh, true, std::move(start), [&](int f, int g) {
    if (!bvh.face_box(f).overlaps(bvh.face_box(g)) || !mesh_faces_intersect(bvh, f, g)) return true;
    return record_pair(out, std::min(f, g), std::max(f, g), max_pairs);
  });
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

}  // namespace

IntersectingFaces self_intersections(const TriangleBvh& bvh, std::size_t max_pairs) {
  return self_intersections_from(bvh, {{0, 0}}, max_pairs);
}

IntersectingFaces self_intersections_part(const TriangleBvh& bvh, int part, std::size_t max_pairs) {
  if (bvh.empty()) return {};
  const BvhNode& root = bvh.nodes().front();
  if (root.is_leaf()) return part == 0 ? self_intersections(bvh, max_pairs) : IntersectingFaces{};
  // Popped last-in first-out, as self_intersections would descend from the root.
  if (part == 0) return self_intersections_from(bvh, {{root.left, root.right}, {root.left, root.left}}, max_pairs);
  return self_intersections_from(bvh, {{root.right, root.right}}, max_pairs);
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

IntersectingFaces intersecting_faces(const TriangleBvh& a, const TriangleBvh& b, std::size_t max_pairs) {
  IntersectingFaces out;
  traverse_face_pairs(a, b, false, {{0, 0}}, [&](int f, int g) {
    if (!a.face_box(f).overlaps(b.face_box(g)) ||
        !triangles_intersect(a.corner(f, 0), a.corner(f, 1), a.corner(f, 2), b.corner(g, 0), b.corner(g, 1), b.corner(g, 2)))
      return true;
    return record_pair(out, f, g, max_pairs);
  });
  std::sort(out.pairs.begin(), out.pairs.end());
  return out;
}

}  // namespace offsetopt
