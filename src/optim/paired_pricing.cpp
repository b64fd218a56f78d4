#include "optim/paired_pricing.h"

namespace offsetopt {

PairedPricing::PairedPricing(const Eigen::MatrixXd& A) : m_(A.rows()), n_(A.cols()), pairs_((A.cols() + 1) / 2) {
  packed_.resize(2, pairs_ * m_);
  if (n_ % 2 == 1) packed_.row(1).tail(m_).setZero();  // the last pair's missing column
  for (Eigen::Index j = 0; j < n_; ++j)
    for (Eigen::Index k = 0; k < m_; ++k) packed_(j % 2, (j / 2) * m_ + k) = A(k, j);
  y_.resize(2, m_);
  r_.resize(2, m_);
}

void PairedPricing::price(const Eigen::MatrixXd& yr, Eigen::MatrixXd& priced) {
  priced.resize(n_, 2);
  for (Eigen::Index k = 0; k < m_; ++k) {
    y_.col(k).setConstant(yr(k, 0));
    r_.col(k).setConstant(yr(k, 1));
  }
  for (Eigen::Index p = 0; p < pairs_; ++p) {
    // Two columns side by side, one per lane: each lane's sums are the product's, in its order.
    Eigen::Array2d sy = Eigen::Array2d::Zero(), sr = Eigen::Array2d::Zero();
    const Eigen::Index base = p * m_;
    for (Eigen::Index k = 0; k < m_; ++k) {
      const Eigen::Array2d a = packed_.col(base + k);
      sy += a * y_.col(k);
      sr += a * r_.col(k);
    }
    sy = 0.0 + sy;  // the product adds its sums to a zeroed result: -0 becomes +0
    sr = 0.0 + sr;
    priced(2 * p, 0) = sy[0];
    priced(2 * p, 1) = sr[0];
    if (2 * p + 1 < n_) {
      priced(2 * p + 1, 0) = sy[1];
      priced(2 * p + 1, 1) = sr[1];
    }
  }
}

}  // namespace offsetopt
