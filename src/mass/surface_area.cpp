#include "mass/surface_area.h"

#include <Eigen/Geometry>

#include "util/neumaier_sum.h"

namespace offsetopt {

double surface_area(const Mesh& mesh) {
  NeumaierSum sum;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0));
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1));
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2));
    sum.add(0.5 * (b - a).cross(c - a).norm());
  }
  return sum.value();
}

}  // namespace offsetopt
