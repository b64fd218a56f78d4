#include "geometry/cotan_laplacian.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace offsetopt {

std::string CotanOptions::check() const {
  if (!(sine_floor >= 0.0) || !(sine_floor < 1.0)) return "sine_floor must be in [0, 1)";
  if (!(mollify_margin >= 0.0) || !(mollify_margin <= 0.1)) return "mollify_margin must be in [0, 0.1]";
  return {};
}

namespace {

// The mollified matrix: every cotangent from the lengthened edge lengths alone.
void add_intrinsic_triplets(const Faces& F, const Eigen::Matrix<double, Eigen::Dynamic, 3>& lengths, double epsilon,
                            std::vector<Eigen::Triplet<double>>& triplets) {
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double l[3] = {lengths(f, 0) + epsilon, lengths(f, 1) + epsilon, lengths(f, 2) + epsilon};
    const double area = intrinsic_area(l[0], l[1], l[2]);
    if (!(area > 0.0)) continue;  // cannot happen after mollification; kept as a guard
    for (int corner = 0; corner < 3; ++corner) {
      const double a = l[(corner + 1) % 3], b = l[(corner + 2) % 3], c = l[corner];
      const double half_cot = (a * a + b * b - c * c) / (8.0 * area);
      const int i = F(f, (corner + 1) % 3), j = F(f, (corner + 2) % 3);
      triplets.emplace_back(i, j, -half_cot);
      triplets.emplace_back(j, i, -half_cot);
      triplets.emplace_back(i, i, half_cot);
      triplets.emplace_back(j, j, half_cot);
    }
  }
}

}  // namespace

Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F, const CotanOptions& options) {
  const Eigen::Index n = V.rows();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(F.rows()) * 12);
  const Eigen::Matrix<double, Eigen::Dynamic, 3> lengths = face_edge_lengths(V, F);
  const Mollification mollification = intrinsic_mollification(lengths, options.mollify_margin);
  if (mollification.epsilon > 0.0) {
    add_intrinsic_triplets(F, lengths, mollification.epsilon, triplets);
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(triplets.begin(), triplets.end());
    L.makeCompressed();
    return L;
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p[3] = {V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2))};
    // Edge k is opposite corner k.
    const Eigen::Vector3d edge[3] = {p[2] - p[1], p[0] - p[2], p[1] - p[0]};
    const double cross_norm = edge[2].cross(-edge[1]).norm();  // 2 * area
    double longest2 = 0.0;
    for (const auto& e : edge) longest2 = std::max(longest2, e.squaredNorm());
    const double denominator = std::max(cross_norm, options.sine_floor * longest2);
    if (denominator == 0.0) continue;  // every edge has zero length
    for (int corner = 0; corner < 3; ++corner) {
      // cot of the angle at `corner` = (a·b) / |a×b| with a, b the edges leaving the corner.
      const Eigen::Vector3d& to_next = edge[(corner + 2) % 3];   // p[corner+1] - p[corner]
      const Eigen::Vector3d& from_prev = edge[(corner + 1) % 3];  // p[corner] - p[corner+2]
      const double half_cot = 0.5 * (-to_next.dot(from_prev)) / denominator;
      const int i = F(f, (corner + 1) % 3), j = F(f, (corner + 2) % 3);
      triplets.emplace_back(i, j, -half_cot);
      triplets.emplace_back(j, i, -half_cot);
      triplets.emplace_back(i, i, half_cot);
      triplets.emplace_back(j, j, half_cot);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  L.makeCompressed();
  return L;
}

}  // namespace offsetopt
