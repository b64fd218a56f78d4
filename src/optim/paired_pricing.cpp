#include "optim/paired_pricing.h"

namespace offsetopt {

PairedPricing::PairedPricing(const Eigen::MatrixXd& A) : m_(A.rows()), n_(A.cols()), pairs_((A.cols() + 1) / 2) {
  packed_.resize(2, pairs_ * m_);
  // Pair p holds, row by row, (A(k, 2p), A(k, 2p + 1)); the last pair's missing column is 0.
  for (Eigen::Index p = 0; p < pairs_; ++p) {
    const double* first = A.data() + 2 * p * m_;
    const double* second = 2 * p + 1 < n_ ? first + m_ : nullptr;
    double* to = packed_.data() + 2 * p * m_;
    for (Eigen::Index k = 0; k < m_; ++k) {
      to[2 * k] = first[k];
      to[2 * k + 1] = second ? second[k] : 0.0;
    }
  }
  y_.resize(2, m_);
  r_.resize(2, m_);
}

void PairedPricing::store(Eigen::Index p, const Eigen::Array2d& sy, const Eigen::Array2d& sr, Eigen::MatrixXd& priced) const {
  const Eigen::Array2d y = 0.0 + sy, r = 0.0 + sr;  // the product adds its sums to a zeroed result: -0 becomes +0
  priced(2 * p, 0) = y[0];
  priced(2 * p, 1) = r[0];
  if (2 * p + 1 < n_) {
    priced(2 * p + 1, 0) = y[1];
    priced(2 * p + 1, 1) = r[1];
  }
}

void PairedPricing::price(const Eigen::MatrixXd& yr, Eigen::MatrixXd& priced) {
  priced.resize(n_, 2);
  for (Eigen::Index k = 0; k < m_; ++k) {
    y_.col(k).setConstant(yr(k, 0));
    r_.col(k).setConstant(yr(k, 1));
  }
  // Two pairs (four columns) at a time, one per lane: each lane's sums are the product's, in its
  // order; the rows' loop is shared.
  Eigen::Index p = 0;
  for (; p + 1 < pairs_; p += 2) {
    Eigen::Array2d sy0 = Eigen::Array2d::Zero(), sr0 = Eigen::Array2d::Zero();
    Eigen::Array2d sy1 = Eigen::Array2d::Zero(), sr1 = Eigen::Array2d::Zero();
    const Eigen::Index base0 = p * m_, base1 = base0 + m_;
    for (Eigen::Index k = 0; k < m_; ++k) {
      const Eigen::Array2d a0 = packed_.col(base0 + k), a1 = packed_.col(base1 + k);
      sy0 += a0 * y_.col(k);
      sr0 += a0 * r_.col(k);
      sy1 += a1 * y_.col(k);
      sr1 += a1 * r_.col(k);
    }
    store(p, sy0, sr0, priced);
    store(p + 1, sy1, sr1, priced);
  }
  for (; p < pairs_; ++p) {
    Eigen::Array2d sy = Eigen::Array2d::Zero(), sr = Eigen::Array2d::Zero();
    const Eigen::Index base = p * m_;
    for (Eigen::Index k = 0; k < m_; ++k) {
      const Eigen::Array2d a = packed_.col(base + k);
      sy += a * y_.col(k);
      sr += a * r_.col(k);
    }
    store(p, sy, sr, priced);
  }
}

}  // namespace offsetopt
