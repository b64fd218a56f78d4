#include "geometry/inscribed_ball.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "geometry/closest_point.h"
#include "geometry/ray_cast.h"

namespace offsetopt {

InscribedBall inscribed_ball(const TriangleBvh& bvh, const Eigen::Vector3d& x, const Eigen::Vector3d& d,
                             double initial_radius, const std::vector<int>& ignored_faces, int max_iterations,
                             double relative_tolerance) {
  InscribedBall out;
  double r = initial_radius;
  for (int iteration = 0; iteration < max_iterations && r > 0.0; ++iteration) {
    out.iterations = iteration + 1;
    const Eigen::Vector3d centre = x + r * d;
    // A point counts as inside only when clearly so, so rounding on a surface tangent to the ball
    // (a flat region around x) cannot shrink it, and a faceted sphere converges in a few steps.
    const ClosestPoint q = closest_point(bvh, centre, r * (1.0 - relative_tolerance), ignored_faces);
    if (!q.found) break;
    const Eigen::Vector3d offset = q.point - x;
    const double along = offset.dot(d);
    if (!(along > 0.0)) break;  // cannot happen for a point inside the ball; guards rounding
    const double shrunk = offset.squaredNorm() / (2.0 * along);
    if (!(shrunk < r * (1.0 - relative_tolerance))) break;
    r = shrunk;
  }
  out.radius = r;
  return out;
}

double inscribed_radius_by_rays(const TriangleBvh& bvh, const Eigen::Vector3d& x, const Eigen::Vector3d& d, double max_radius,
                                const std::vector<int>& ignored_faces, double stop_below) {
  // cos and sin of 20, 40, 60 degrees and of the eight azimuths (literal constants: no libm).
  static const double cone_cos[3] = {0.93969262078590838, 0.76604444311897804, 0.5};
  static const double cone_sin[3] = {0.34202014332566873, 0.64278760968653933, 0.86602540378443865};
  static const double azimuth_cos[8] = {1.0, 0.70710678118654752, 0.0, -0.70710678118654752, -1.0, -0.70710678118654752, 0.0, 0.70710678118654752};
  static const double azimuth_sin[8] = {0.0, 0.70710678118654752, 1.0, 0.70710678118654752, 0.0, -0.70710678118654752, -1.0, -0.70710678118654752};
  // An orthonormal frame around d: the axis least aligned with d, made orthogonal.
  const Eigen::Vector3d a = d.cwiseAbs();
  const Eigen::Vector3d axis = a.x() <= a.y() && a.x() <= a.z() ? Eigen::Vector3d::UnitX()
                               : (a.y() <= a.z() ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d e1 = (axis - axis.dot(d) * d).normalized();
  const Eigen::Vector3d e2 = d.cross(e1);
  double radius = max_radius;
  RayCastOptions ray;
  ray.ignored_faces = ignored_faces;
  auto probe = [&](const Eigen::Vector3d& u, double cosine) {
    ray.t_max = 2.0 * radius * cosine;  // a farther hit cannot lower the radius
    const RayCastHit hit = ray_cast_closest(bvh, x, u, ray);
    if (hit.hit) radius = std::min(radius, hit.t / (2.0 * cosine));
  };
  probe(d, 1.0);
  for (int c = 0; c < 3 && radius > stop_below; ++c)
    for (int k = 0; k < 8 && radius > stop_below; ++k)
      probe(cone_cos[c] * d + cone_sin[c] * (azimuth_cos[k] * e1 + azimuth_sin[k] * e2), cone_cos[c]);
  return radius;
}

}  // namespace offsetopt
