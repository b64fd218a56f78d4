#include "spectral/mass_matrix.h"

#include <Eigen/Geometry>

namespace offsetopt {

Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F) {
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double third_area = (b - a).cross(c - a).norm() / 6.0;
    for (int corner = 0; corner < 3; ++corner) mass(F(f, corner)) += third_area;
  }
  return mass;
}

}  // namespace offsetopt
