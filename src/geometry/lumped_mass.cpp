#include "geometry/lumped_mass.h"

#include <Eigen/Geometry>

namespace offsetopt {

Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F, double mollify_margin) {
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(V.rows());
  const Eigen::Matrix<double, Eigen::Dynamic, 3> lengths = face_edge_lengths(V, F);
  const Mollification mollification = intrinsic_mollification(lengths, mollify_margin);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    double third_area = 0.0;
    if (mollification.epsilon > 0.0) {
      const double e = mollification.epsilon;
      third_area = intrinsic_area(lengths(f, 0) + e, lengths(f, 1) + e, lengths(f, 2) + e) / 3.0;
    } else {
      const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      third_area = (b - a).cross(c - a).norm() / 6.0;
    }
    for (int corner = 0; corner < 3; ++corner) mass(F(f, corner)) += third_area;
  }
  return mass;
}

}  // namespace offsetopt
