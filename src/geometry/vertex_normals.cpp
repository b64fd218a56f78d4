#include "geometry/vertex_normals.h"

#include <Eigen/Geometry>

namespace offsetopt {

Vertices vertex_normals(const Vertices& V, const Faces& F) {
  Vertices N = Vertices::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const double length = N.row(i).norm();
    if (length > 0.0) N.row(i) /= length;
  }
  return N;
}

}  // namespace offsetopt
