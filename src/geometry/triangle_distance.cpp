#include "geometry/triangle_distance.h"

#include <algorithm>
#include <cmath>

#include "geometry/closest_point.h"
#include "geometry/triangle_triangle.h"

namespace offsetopt {

double segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                        const Eigen::Vector3d& b1) {
  // Minimise |a0 + s u − b0 − t v| over [0, 1]²: the unconstrained minimiser clamped one parameter
  // at a time, the other re-solved for the clamped one (the function is convex, so this finds the
  // minimum on the square).
  const Eigen::Vector3d u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double uu = u.squaredNorm(), vv = v.squaredNorm(), uv = u.dot(v), uw = u.dot(w), vw = v.dot(w);
  auto clamp01 = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  double s = 0.0, t = 0.0;
  if (uu <= 0.0 && vv <= 0.0) return w.norm();
  if (uu <= 0.0) {
    t = clamp01(vw / vv);
  } else if (vv <= 0.0) {
    s = clamp01(-uw / uu);
  } else {
    const double det = uu * vv - uv * uv;
    // Parallel (or nearly): any s will do for the interior; start from 0 and let the clamps work.
    s = det > 1e-14 * uu * vv ? clamp01((uv * vw - vv * uw) / det) : 0.0;
    t = (uv * s + vw) / vv;
    if (t < 0.0) {
      t = 0.0;
      s = clamp01(-uw / uu);
    } else if (t > 1.0) {
      t = 1.0;
      s = clamp01((uv - uw) / uu);
    }
  }
  return (w + s * u - t * v).norm();
}

double triangle_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                         const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2) {
  if (triangles_intersect(a0, a1, a2, b0, b1, b2)) return 0.0;
  const Eigen::Vector3d* a[3] = {&a0, &a1, &a2};
  const Eigen::Vector3d* b[3] = {&b0, &b1, &b2};
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, (closest_point_on_triangle(*a[i], b0, b1, b2) - *a[i]).norm());
    best = std::min(best, (closest_point_on_triangle(*b[i], a0, a1, a2) - *b[i]).norm());
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) best = std::min(best, segment_distance(*a[i], *a[(i + 1) % 3], *b[j], *b[(j + 1) % 3]));
  return best;
}

}  // namespace offsetopt
