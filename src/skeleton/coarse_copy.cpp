#include "skeleton/coarse_copy.h"

#include <algorithm>

#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "util/parallel.h"

namespace offsetopt {

CoarseCopy coarse_copy(const Vertices& V, const Faces& F, int target_vertices, int threads) {
  CoarseCopy copy;
  copy.decimated = decimate_mesh(V, F, target_vertices);
  const Mesh& coarse = copy.decimated.mesh;
  const Eigen::Index n = V.rows();
  copy.corners.assign(static_cast<std::size_t>(n), {0, 0, 0});
  copy.weights.assign(static_cast<std::size_t>(n), {1.0, 0.0, 0.0});
  const TriangleBvh bvh(coarse.V, coarse.F);
  for_ranges(n, threads, 4096, [&](Eigen::Index begin, Eigen::Index end) {
    for (Eigen::Index i = begin; i < end; ++i) {
      const std::size_t u = static_cast<std::size_t>(i);
      const int kept = copy.decimated.coarse_vertex[u];
      if (kept >= 0) {
        copy.corners[u] = {kept, kept, kept};
        continue;
      }
      const ClosestPoint nearest = closest_point(bvh, V.row(i).transpose());
      if (!nearest.found) continue;
      const Eigen::Index face = nearest.face;
      const std::array<int, 3> corner = {coarse.F(face, 0), coarse.F(face, 1), coarse.F(face, 2)};
      const Eigen::Vector3d a = coarse.V.row(corner[0]), b = coarse.V.row(corner[1]), c = coarse.V.row(corner[2]);
      // Barycentric coordinates of the closest point (on the triangle, so in [0, 1]).
      const Eigen::Vector3d e0 = b - a, e1 = c - a, d = nearest.point - a;
      const double d00 = e0.dot(e0), d01 = e0.dot(e1), d11 = e1.dot(e1), d20 = d.dot(e0), d21 = d.dot(e1);
      const double denominator = d00 * d11 - d01 * d01;
      double wb = 0.0, wc = 0.0;
      if (denominator > 0.0) {
        wb = std::clamp((d11 * d20 - d01 * d21) / denominator, 0.0, 1.0);
        wc = std::clamp((d00 * d21 - d01 * d20) / denominator, 0.0, 1.0 - wb);
      }
      copy.corners[u] = corner;
      copy.weights[u] = {1.0 - wb - wc, wb, wc};
    }
  });
  return copy;
}

Eigen::MatrixXd carry_to_input(const CoarseCopy& copy, const Eigen::MatrixXd& coarse_values) {
  const Eigen::Index n = static_cast<Eigen::Index>(copy.corners.size());
  Eigen::MatrixXd out(n, coarse_values.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& corner = copy.corners[static_cast<std::size_t>(i)];
    const auto& weight = copy.weights[static_cast<std::size_t>(i)];
    if (corner[0] == corner[1] && corner[1] == corner[2]) {
      out.row(i) = coarse_values.row(corner[0]);
      continue;
    }
    out.row(i) = weight[0] * coarse_values.row(corner[0]) + weight[1] * coarse_values.row(corner[1]) +
                 weight[2] * coarse_values.row(corner[2]);
  }
  return out;
}

}  // namespace offsetopt
