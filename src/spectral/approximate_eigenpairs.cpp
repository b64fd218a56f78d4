#include "spectral/approximate_eigenpairs.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace offsetopt {

namespace {

// LU with partial pivoting of the tridiagonal T - μI (diagonal d, off-diagonal e), kept for
// repeated solves. The eliminated row always has two entries (columns i, i+1); the pivot row
// has up to three (u0, u1, u2 at columns i, i+1, i+2).
class ShiftedTridiagonalLu {
 public:
  ShiftedTridiagonalLu(const Eigen::VectorXd& d, const Eigen::VectorXd& e, double mu, double tiny)
      : n_(d.size()), u0_(n_), u1_(n_, 0.0), u2_(n_, 0.0), multiplier_(n_, 0.0), swapped_(n_, false) {
    double c0 = d(0) - mu, c1 = n_ > 1 ? e(0) : 0.0;
    for (Eigen::Index i = 0; i + 1 < n_; ++i) {
      const double below = e(i), next_diagonal = d(i + 1) - mu, next_upper = i + 2 < n_ ? e(i + 1) : 0.0;
      if (std::abs(c0) >= std::abs(below)) {
        if (c0 == 0.0) c0 = tiny;  // both zero: the column is already eliminated
        u0_[i] = c0;
        u1_[i] = c1;
        multiplier_[i] = below / c0;
        c0 = next_diagonal - multiplier_[i] * c1;
        c1 = next_upper;
      } else {
        u0_[i] = below;
        u1_[i] = next_diagonal;
        u2_[i] = next_upper;
        multiplier_[i] = c0 / below;
        swapped_[i] = true;
        const double old_c1 = c1;
        c0 = old_c1 - multiplier_[i] * next_diagonal;
        c1 = -multiplier_[i] * next_upper;
      }
    }
    u0_[n_ - 1] = std::abs(c0) < tiny ? (c0 < 0.0 ? -tiny : tiny) : c0;
    for (Eigen::Index i = 0; i + 1 < n_; ++i)
      if (std::abs(u0_[i]) < tiny) u0_[i] = u0_[i] < 0.0 ? -tiny : tiny;
  }

  // x ← (T - μI)⁻¹ x.
  void solve(Eigen::VectorXd& x) const {
    for (Eigen::Index i = 0; i + 1 < n_; ++i) {
      if (swapped_[i]) std::swap(x(i), x(i + 1));
      x(i + 1) -= multiplier_[i] * x(i);
    }
    for (Eigen::Index i = n_ - 1; i >= 0; --i) {
      double v = x(i);
      if (i + 1 < n_) v -= u1_[i] * x(i + 1);
      if (i + 2 < n_) v -= u2_[i] * x(i + 2);
      x(i) = v / u0_[i];
    }
  }

 private:
  Eigen::Index n_;
  std::vector<double> u0_, u1_, u2_, multiplier_;
  std::vector<bool> swapped_;
};

// Columns spanning the eigenvectors of the tridiagonal for eigenvalues near μ, by three block
// inverse iterations (orthonormalised after each) from a fixed start with no special structure.
Eigen::MatrixXd tridiagonal_eigenvectors(const Eigen::VectorXd& d, const Eigen::VectorXd& e, double mu, double tiny,
                                         int count) {
  const Eigen::Index n = d.size();
  const ShiftedTridiagonalLu lu(d, e, mu, tiny);
  Eigen::MatrixXd X(n, count);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < count; ++c) X(i, c) = 1.0 + 0.125 * static_cast<double>((i * (5 + 2 * c) + 3 * c * c) % 8);
  for (int iteration = 0; iteration < 3; ++iteration) {
    for (int c = 0; c < count; ++c) {
      Eigen::VectorXd x = X.col(c);
      lu.solve(x);
      X.col(c) = x;
    }
    if (!X.allFinite()) break;
    X = Eigen::HouseholderQR<Eigen::MatrixXd>(X).householderQ() * Eigen::MatrixXd::Identity(n, count);
  }
  return X;
}

}  // namespace

ApproximateEigenpairs::ApproximateEigenpairs(const Eigen::MatrixXd& H) : H_(H) {
  const Eigen::Index n = H.rows();
  slack_ = 4.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon() * H.norm();
  if (n == 1) {
    values_ = H.diagonal();
    ok_ = true;
    return;
  }
  // Exactly the steps of SelfAdjointEigenSolver::compute before its QR sweeps.
  reduced_ = H.triangularView<Eigen::Lower>();
  double scale = reduced_.cwiseAbs().maxCoeff();
  if (scale == 0.0) scale = 1.0;
  reduced_.triangularView<Eigen::Lower>() /= scale;
  diagonal_.resize(n);
  off_diagonal_.resize(n - 1);
  householder_.resize(n - 1);
  Eigen::internal::tridiagonalization_inplace(reduced_, diagonal_, off_diagonal_, householder_, false);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> sweeps;
  sweeps.computeFromTridiagonal(diagonal_, off_diagonal_, Eigen::EigenvaluesOnly);
  if (sweeps.info() != Eigen::Success) return;
  scaled_values_ = sweeps.eigenvalues();
  const Eigen::VectorXd ascending = scaled_values_ * scale;  // as compute() scales back
  values_ = ascending.reverse();
  tiny_ = std::numeric_limits<double>::epsilon() * std::max(1.0, off_diagonal_.cwiseAbs().maxCoeff());
  ok_ = true;
}

double ApproximateEigenpairs::vector(int i, Eigen::VectorXd& z) const {
  Eigen::MatrixXd V;
  const double bound = subspace(i, 1, V);
  z = V.col(0);
  return bound;
}

double ApproximateEigenpairs::subspace(int first, int count, Eigen::MatrixXd& V) const {
  const Eigen::Index n = H_.rows();
  const double infinity = std::numeric_limits<double>::infinity();
  if (n == 1) {
    V = Eigen::MatrixXd::Ones(1, 1);
    return 0.0;
  }
  const double mu = scaled_values_.segment(n - first - count, count).mean();
  V = tridiagonal_eigenvectors(diagonal_, off_diagonal_, mu, tiny_, count);
  // V ← Q V with Q = H_0 H_1 ⋯ H_{n-2}, H_k = I - τ_k v_k v_kᵀ acting on rows k+1.., v_k = (1,
  // the column of `reduced_` below its subdiagonal): one reflection at a time (Eigen's blocked
  // application costs more for a few columns).
  for (Eigen::Index k = n - 2; k >= 0; --k) {
    const double tau = householder_(k);
    if (tau == 0.0) continue;
    const Eigen::Index length = n - k - 2;
    const auto essential = reduced_.col(k).segment(k + 2, length);
    for (int c = 0; c < count; ++c) {
      auto column = V.col(c);
      const double w = tau * (column(k + 1) + essential.dot(column.segment(k + 2, length)));
      column(k + 1) -= w;
      column.segment(k + 2, length) -= w * essential;
    }
  }
  if (!V.allFinite()) return infinity;
  V = Eigen::HouseholderQR<Eigen::MatrixXd>(V).householderQ() * Eigen::MatrixXd::Identity(n, count);
  // The bound, from H itself: whatever went wrong above shows in the residual.
  const Eigen::MatrixXd HV = H_ * V;
  const Eigen::MatrixXd projected = V.transpose() * HV;
  const double residual = (HV - V * projected).norm();
  const Eigen::VectorXd inside =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(0.5 * (projected + projected.transpose()), Eigen::EigenvaluesOnly)
          .eigenvalues();
  const double lo = inside.minCoeff(), hi = inside.maxCoeff();
  double gap = infinity;
  for (Eigen::Index m = 0; m < n; ++m)
    if (m < first || m >= first + count) gap = std::min(gap, std::max(lo - values_(m), values_(m) - hi));
  const double root_count = std::sqrt(static_cast<double>(count));
  gap -= slack_ * root_count;
  const double bound = std::sqrt(2.0) * (residual + 2.0 * slack_ * root_count) / gap;
  return gap > 0.0 && std::isfinite(bound) ? bound : infinity;
}

}  // namespace offsetopt
