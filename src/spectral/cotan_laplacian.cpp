#include "spectral/cotan_laplacian.h"

#include <Eigen/Geometry>
#include <vector>

namespace offsetopt {

namespace {

// Cotangent of the angle between u and w, with |sin| floored by `sine_floor`.
double guarded_cotangent(const Eigen::Vector3d& u, const Eigen::Vector3d& w, double sine_floor) {
  const double cross_norm = u.cross(w).norm();
  const double floor = sine_floor * u.norm() * w.norm();
  const double denominator = cross_norm > floor ? cross_norm : floor;
  if (denominator == 0.0) return 0.0;  // a zero-length edge contributes nothing
  return u.dot(w) / denominator;
}

}  // namespace

Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F, const CotanOptions& options) {
  const Eigen::Index n = V.rows();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(F.rows()) * 12);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int corner = 0; corner < 3; ++corner) {
      // The angle at `corner` is opposite the edge (i, j).
      const int k = F(f, corner), i = F(f, (corner + 1) % 3), j = F(f, (corner + 2) % 3);
      const Eigen::Vector3d pk = V.row(k), pi = V.row(i), pj = V.row(j);
      const double half_cot = 0.5 * guarded_cotangent(pi - pk, pj - pk, options.sine_floor);
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
