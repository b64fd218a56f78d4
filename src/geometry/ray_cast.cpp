#include "geometry/ray_cast.h"

#include <algorithm>

#include "geometry/ray_triangle.h"

namespace offsetopt {

RayCastHit ray_cast_closest(const TriangleBvh& bvh, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            const RayCastOptions& options) {
  RayCastHit best;
  if (bvh.empty()) return best;
  const Eigen::Vector3d inverse = direction.cwiseInverse();
  double t_limit = options.t_max;
  const auto& ignored = options.ignored_faces;
  bvh.traverse(
      [&](const Aabb& box) {
        double t0, t1;
        return ray_box_interval(origin, inverse, box, options.t_min, t_limit, t0, t1);
      },
      [&](int face) {
        if (!ignored.empty() && std::find(ignored.begin(), ignored.end(), face) != ignored.end()) return true;
        const RayTriangleHit h =
            ray_triangle(origin, direction, bvh.corner(face, 0), bvh.corner(face, 1), bvh.corner(face, 2), options.tolerance);
        if (!h.hit || !(h.t > options.t_min) || h.t > t_limit) return true;
        if (h.t < best.t || (h.t == best.t && face < best.face)) {
          best.hit = true;
          best.face = face;
          best.t = h.t;
          best.u = h.u;
          best.v = h.v;
          best.exiting = h.orientation > 0.0;
          t_limit = h.t;
        }
        return true;
      });
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
