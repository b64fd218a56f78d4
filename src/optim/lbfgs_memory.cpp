#include "optim/lbfgs_memory.h"

#include <cmath>

namespace offsetopt {

LbfgsMemory::LbfgsMemory(int n, int capacity)
    : n_(n), capacity_(capacity), s_(n, capacity), y_(n, capacity) {
  reset();
}

void LbfgsMemory::reset() {
  count_ = 0;
  theta_ = 1.0;
  sty_.resize(0, 0);
  sts_.resize(0, 0);
  w_.resize(n_, 0);
  m_.resize(0, 0);
}

bool LbfgsMemory::add(const Eigen::VectorXd& s, const Eigen::VectorXd& y) {
  if (count_ == capacity_) {
    // Drop the oldest pair; columns move one to the left in increasing order (no aliasing).
    for (int j = 0; j + 1 < capacity_; ++j) {
      s_.col(j) = s_.col(j + 1);
      y_.col(j) = y_.col(j + 1);
    }
    --count_;
  }
  s_.col(count_) = s;
  y_.col(count_) = y;
  ++count_;
  theta_ = y.dot(y) / s.dot(y);
  if (!refactor()) {
    reset();
    return false;
  }
  return true;
}

bool LbfgsMemory::refactor() {
  const int p = count_;
  const auto S = s_.leftCols(p);
  const auto Y = y_.leftCols(p);
  sty_ = S.transpose() * Y;
  sts_ = S.transpose() * S;
  w_.resize(n_, 2 * p);
  w_.leftCols(p) = Y;
  w_.rightCols(p) = theta_ * S;
  if (!std::isfinite(theta_) || !(theta_ > 0.0)) return false;
  for (int i = 0; i < p; ++i) {
    if (!(sty_(i, i) > 0.0) || !std::isfinite(sty_(i, i))) return false;
  }
  // J J^T = θ S^T S + L D^{-1} L^T.
  Eigen::MatrixXd t = theta_ * sts_;
  for (int i = 0; i < p; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (int k = 0; k < std::min(i, j); ++k) sum += sty_(i, k) * sty_(j, k) / sty_(k, k);
      t(i, j) += sum;
      if (j != i) t(j, i) = t(i, j);
    }
  }
  j_factor_.compute(t);
  if (j_factor_.info() != Eigen::Success) return false;
  const Eigen::VectorXd jdiag = j_factor_.matrixL().toDenseMatrix().diagonal();
  for (int i = 0; i < p; ++i) {
    if (!(jdiag(i) > 0.0) || !std::isfinite(jdiag(i))) return false;
  }
  // Explicit M, column by column, symmetrised.
  m_.resize(2 * p, 2 * p);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(2 * p);
  for (int j = 0; j < 2 * p; ++j) {
    e(j) = 1.0;
    m_.col(j) = apply_m(e);
    e(j) = 0.0;
  }
  const Eigen::MatrixXd sym = 0.5 * (m_ + m_.transpose());
  m_ = sym;
  return m_.allFinite();
}

Eigen::MatrixXd LbfgsMemory::middle_inverse() const {
  const int p = count_;
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(2 * p, 2 * p);
  for (int i = 0; i < p; ++i) {
    k(i, i) = -sty_(i, i);
    for (int j = 0; j < i; ++j) {
      k(p + i, j) = sty_(i, j);  // L
      k(j, p + i) = sty_(i, j);  // L^T
    }
  }
  k.bottomRightCorner(p, p) = theta_ * sts_;
  return k;
}

Eigen::VectorXd LbfgsMemory::apply_m(const Eigen::VectorXd& v) const {
  const int p = count_;
  Eigen::VectorXd out(2 * p);
  if (p == 0) return out;
  const Eigen::VectorXd v1 = v.head(p);
  // J a2 = v2 + L D^{-1} v1.
  Eigen::VectorXd rhs = v.tail(p);
  for (int i = 0; i < p; ++i) {
    double sum = 0.0;
    for (int k = 0; k < i; ++k) sum += sty_(i, k) * (v1(k) / sty_(k, k));
    rhs(i) += sum;
  }
  // p2 = J^{-T} J^{-1} rhs.
  const Eigen::VectorXd p2 = j_factor_.solve(rhs);
  // p1 = −D^{-1} v1 + D^{-1} L^T p2.
  for (int i = 0; i < p; ++i) {
    double sum = 0.0;
    for (int k = i + 1; k < p; ++k) sum += sty_(k, i) * p2(k);
    out(i) = (-v1(i) + sum) / sty_(i, i);
  }
  out.tail(p) = p2;
  return out;
}

Eigen::MatrixXd LbfgsMemory::dense_b() const {
  Eigen::MatrixXd b = -(w_ * m_ * w_.transpose());
  b.diagonal().array() += theta_;
  return b;
}

}  // namespace offsetopt
