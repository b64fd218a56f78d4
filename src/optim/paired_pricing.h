// Aᵀ[y r] for a dense A (m × n, column-major, the bounded simplex's columns) and two m-vectors y, r:
// each of the 2n entries summed exactly as Eigen's matrix product Aᵀ * [y r] sums it (Eigen 3.4,
// SSE2, no FMA, two right-hand columns: one accumulator per entry over the rows in order, onto +0,
// then added to +0), so a dual simplex step that used the product sees the same numbers bit for
// bit. A is packed once (columns in pairs, row by row) where the product packs it at every call:
// a dual step on the reachability programme prices about 20,000 columns of about 15 rows.
//
// Only while the rows fit the product's one depth block and the product is not evaluated
// coefficient by coefficient: eligible(m, n) says when; otherwise use Eigen's own product.
// tests/optim/test_paired_pricing.cpp checks the bits against Eigen's product.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

class PairedPricing {
 public:
  static bool eligible(Eigen::Index m, Eigen::Index n) { return m >= 1 && m <= 64 && n + m + 2 >= 20; }

  explicit PairedPricing(const Eigen::MatrixXd& A);
  // priced (n × 2, resized) = Aᵀ [yr.col(0) yr.col(1)]; yr is m × 2.
  void price(const Eigen::MatrixXd& yr, Eigen::MatrixXd& priced);

 private:
  void store(Eigen::Index pair, const Eigen::Array2d& sy, const Eigen::Array2d& sr, Eigen::MatrixXd& priced) const;

  Eigen::Index m_ = 0, n_ = 0, pairs_ = 0;
  Eigen::Array<double, 2, Eigen::Dynamic> packed_, y_, r_;  // y_, r_: each entry in both lanes
};

}  // namespace offsetopt
