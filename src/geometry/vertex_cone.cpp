#include "geometry/vertex_cone.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/triangle_solid_angle.h"

namespace offsetopt {

bool direction_enters_solid(const Vertices& V, const Faces& F, const std::vector<int>& fan, int vertex,
                            const Eigen::Vector3d& direction) {
  const Eigen::Vector3d x = V.row(vertex).transpose();
  double shortest = std::numeric_limits<double>::infinity();
  for (int f : fan)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) != vertex) shortest = std::min(shortest, (V.row(F(f, k)).transpose() - x).norm());
  const double length = direction.norm();
  if (fan.empty() || !(shortest > 0.0) || !std::isfinite(shortest) || !(length > 0.0)) return false;
  const Eigen::Vector3d p = x + (1e-4 * shortest / length) * direction;
  double solid_angle = 0.0;
  for (int f : fan) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose() - p;
    const Eigen::Vector3d b = V.row(F(f, 1)).transpose() - p;
    const Eigen::Vector3d c = V.row(F(f, 2)).transpose() - p;
    solid_angle += triangle_solid_angle(a, b, c);
  }
  return solid_angle > 0.0;
}

VertexFaces vertex_faces(Eigen::Index vertex_count, const Faces& F) {
  VertexFaces out;
  out.offsets.assign(static_cast<std::size_t>(vertex_count) + 1, 0);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++out.offsets[static_cast<std::size_t>(F(f, k)) + 1];
  for (std::size_t i = 1; i < out.offsets.size(); ++i) out.offsets[i] += out.offsets[i - 1];
  out.faces.resize(static_cast<std::size_t>(out.offsets.back()));
  std::vector<int> cursor(out.offsets.begin(), out.offsets.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) out.faces[static_cast<std::size_t>(cursor[static_cast<std::size_t>(F(f, k))]++)] = static_cast<int>(f);
  return out;
}

}  // namespace offsetopt
