// The signed solid angle a triangle subtends at a point (Van Oosterom & Strackee 1983), from the
// corners a, b, c taken relative to that point: positive when the triangle's normal (right-hand
// rule a → b → c) points away from the point; in (−2π, 2π]. Its sum over a closed surface is the
// winding number times 4π (geometry/point_in_solid.h, winding_number) and tells whether a direction
// leaves a vertex into the solid (geometry/vertex_cone.h). det_atan2 keeps it the same bits on
// every machine.
#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "util/det_math.h"

namespace offsetopt {

inline double triangle_solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double numerator = a.dot(b.cross(c));
  const double denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * det_atan2(numerator, denominator);
}

}  // namespace offsetopt
