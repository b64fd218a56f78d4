#include "geometry/ray_triangle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace offsetopt {

RayTriangleHit ray_triangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tolerance) {
  RayTriangleHit out;
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);  // = -direction . (e1 x e2)
  out.orientation = -det;
  // |det| = |direction| |e1 x e2| |sine of the angle between the ray and the plane|.
  const double scale = direction.norm() * e1.cross(e2).norm();
  if (!(std::abs(det) > 1e-12 * scale)) {
    // Parallel: only a ray lying in the plane could touch the triangle, and then no count is safe.
    const Eigen::Vector3d normal = e1.cross(e2);
    const double longest_edge = std::sqrt(std::max({e1.squaredNorm(), e2.squaredNorm(), (c - b).squaredNorm()}));
    out.ambiguous = std::abs((origin - a).dot(normal)) <= 1e-9 * normal.norm() * longest_edge;
    return out;
  }
  const double inverse_det = 1.0 / det;
  const Eigen::Vector3d s = origin - a;
  const double u = s.dot(p) * inverse_det;
  if (u < -tolerance || u > 1.0 + tolerance) return out;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = direction.dot(q) * inverse_det;
  if (v < -tolerance || u + v > 1.0 + tolerance) return out;
  out.hit = true;
  out.t = e2.dot(q) * inverse_det;
  out.u = u;
  out.v = v;
  out.ambiguous = u < tolerance || v < tolerance || u + v > 1.0 - tolerance;
  return out;
}

}  // namespace offsetopt
