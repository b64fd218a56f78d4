#include "geometry/ray_cast.h"

#include <algorithm>
#include <cmath>

#include "geometry/ray_triangle.h"

namespace offsetopt {

std::string RayCastOptions::check() const {
  if (std::isnan(t_min) || std::isnan(t_max) || !(t_min <= t_max)) return "RayCastOptions: need t_min <= t_max";
  if (!(tolerance >= 0.0) || !std::isfinite(tolerance)) return "RayCastOptions::tolerance must be finite and >= 0";
  for (int face : ignored_faces)
    if (face < 0) return "RayCastOptions::ignored_faces must hold face numbers >= 0";
  return std::string();
}

RayCastHit ray_cast_closest(const TriangleBvh& bvh, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            const RayCastOptions& options) {
  RayCastHit best;
  if (bvh.empty()) return best;
  const Eigen::Vector3d inverse = direction.cwiseInverse();
  double t_limit = options.t_max;
  const auto& ignored = options.ignored_faces;
  const auto& nodes = bvh.nodes();
  // Depth first, nearer child first, so the first hits shrink t_limit and prune the rest. The
  // result does not depend on the order (ties in t go to the lowest face index).
  struct Entry {
    int node;
    double t_enter;
  };
  Entry stack[128];
  int top = 0;
  double t0, t1;
  if (!ray_box_interval(origin, inverse, nodes[0].box, options.t_min, t_limit, t0, t1)) return best;
  stack[top++] = {0, t0};
  while (top > 0) {
    const Entry entry = stack[--top];
    if (entry.t_enter > t_limit) continue;
    const BvhNode& node = nodes[static_cast<std::size_t>(entry.node)];
    if (node.is_leaf()) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const int face = bvh.leaf_faces()[static_cast<std::size_t>(k)];
        if (!ignored.empty() && std::find(ignored.begin(), ignored.end(), face) != ignored.end()) continue;
        const RayTriangleHit h =
            ray_triangle(origin, direction, bvh.corner(face, 0), bvh.corner(face, 1), bvh.corner(face, 2), options.tolerance);
        if (!h.hit || !(h.t > options.t_min) || h.t > t_limit) continue;
        if (h.t < best.t || (h.t == best.t && face < best.face)) {
          best.hit = true;
          best.face = face;
          best.t = h.t;
          best.u = h.u;
          best.v = h.v;
          best.exiting = h.orientation > 0.0;
          t_limit = h.t;
        }
      }
      continue;
    }
    double left_enter, left_exit, right_enter, right_exit;
    const bool left = ray_box_interval(origin, inverse, nodes[static_cast<std::size_t>(node.left)].box, options.t_min, t_limit, left_enter, left_exit);
    const bool right = ray_box_interval(origin, inverse, nodes[static_cast<std::size_t>(node.right)].box, options.t_min, t_limit, right_enter, right_exit);
    if (left && right) {
      if (left_enter <= right_enter) {
        stack[top++] = {node.right, right_enter};
        stack[top++] = {node.left, left_enter};
      } else {
        stack[top++] = {node.left, left_enter};
        stack[top++] = {node.right, right_enter};
      }
    } else if (left) {
      stack[top++] = {node.left, left_enter};
    } else if (right) {
      stack[top++] = {node.right, right_enter};
    }
  }
  return best;
}

bool segment_hits_mesh(const TriangleBvh& bvh, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                       const std::vector<int>& ignored_faces) {
  RayCastOptions options;
  options.t_min = -1e-12;  // the endpoint p itself counts
  options.t_max = 1.0 + 1e-12;
  options.ignored_faces = ignored_faces;
  return ray_cast_closest(bvh, p, q - p, options).hit;
}

}  // namespace offsetopt
