#include "geometry/cylinder_prism.h"

#include <cmath>

#include <Eigen/Geometry>

#include "util/det_math.h"

namespace offsetopt {

Mesh cylinder_prism(const Eigen::Vector3d& bottom, const Eigen::Vector3d& top, double radius, int sides, double turn) {
  const Eigen::Vector3d axis = (top - bottom).normalized();
  // Any unit vector across the axis: the coordinate axis least aligned with it, made orthogonal.
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  const Eigen::Vector3d u = (Eigen::Vector3d::Unit(least) - axis(least) * axis).normalized();
  const Eigen::Vector3d v = axis.cross(u);
  const double kTwoPi = 6.283185307179586;
  Mesh m;
  m.V.resize(2 * sides + 2, 3);
  for (int i = 0; i < sides; ++i) {
    double s = 0.0, c = 0.0;
    det_sincos(turn + kTwoPi * i / sides, s, c);
    const Eigen::Vector3d offset = radius * (c * u + s * v);
    m.V.row(i) = (bottom + offset).transpose();
    m.V.row(sides + i) = (top + offset).transpose();
  }
  m.V.row(2 * sides) = bottom.transpose();
  m.V.row(2 * sides + 1) = top.transpose();
  m.F.resize(4 * sides, 3);
  for (int i = 0; i < sides; ++i) {
    const int j = (i + 1) % sides;
    // Counter-clockwise about the axis seen from the top: the sides' normals point away from it.
    m.F.row(4 * i) << i, j, sides + j;
    m.F.row(4 * i + 1) << i, sides + j, sides + i;
    m.F.row(4 * i + 2) << 2 * sides, j, i;                    // bottom cap, normal −axis
    m.F.row(4 * i + 3) << 2 * sides + 1, sides + i, sides + j;  // top cap, normal +axis
  }
  return m;
}

}  // namespace offsetopt
