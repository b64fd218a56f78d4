// PairedPricing and transposed_product_10 against the Eigen products they stand in for, bit for
// bit: random entries of mixed magnitudes and signs, exact zeros (products of ±0), odd and even
// column counts, every row count they accept.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include <Eigen/Dense>

#include "optim/paired_pricing.h"
#include "optim/transposed_product_10.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

// Mostly O(1) values over several decades, some exact zeros (so that ±0 products occur).
double entry(Rng& rng) {
  const double r = rng.uniform(0.0, 1.0);
  if (r < 0.1) return 0.0;
  return rng.uniform(-1.0, 1.0) * std::pow(10.0, std::floor(rng.uniform(-6.0, 6.0)));
}

bool same_bits(const double* a, const double* b, Eigen::Index count) {
  return std::memcmp(a, b, sizeof(double) * static_cast<std::size_t>(count)) == 0;
}

}  // namespace

TEST_CASE("PairedPricing: A^T [y r] as Eigen's product sums it") {
  Rng rng(20261126);
  for (const int m : {1, 2, 3, 6, 15, 18, 33, 64})
    for (const int n : {19, 20, 21, 101, 1000}) {
      if (!PairedPricing::eligible(m, n)) continue;
      Eigen::MatrixXd A(m, n), yr(m, 2);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < m; ++i) A(i, j) = entry(rng);
      A.col(n / 2).setZero();  // a column of zeros: every product ±0, the sum +0
      for (int i = 0; i < m; ++i) {
        yr(i, 0) = entry(rng);
        yr(i, 1) = -entry(rng);
      }
      Eigen::MatrixXd expected;
      expected.noalias() = A.transpose() * yr;
      PairedPricing pricing(A);
      Eigen::MatrixXd priced;
      pricing.price(yr, priced);
      CHECK(priced.rows() == n);
      CHECK(same_bits(priced.data(), expected.data(), 2 * n));
      // A second call with other duals on the same packing.
      yr = -yr;
      expected.noalias() = A.transpose() * yr;
      pricing.price(yr, priced);
      CHECK(same_bits(priced.data(), expected.data(), 2 * n));
    }
  CHECK_FALSE(PairedPricing::eligible(0, 100));
  CHECK_FALSE(PairedPricing::eligible(65, 100));
  CHECK_FALSE(PairedPricing::eligible(6, 11));
}

TEST_CASE("transposed_product_10: C^T x as Eigen's row-major product sums it") {
  Rng rng(7);
  for (int m = 2; m <= 40; ++m)
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::Matrix<double, 10, Eigen::Dynamic> C(10, m);
      Eigen::Matrix<double, 10, 1> x;
      for (int k = 0; k < m; ++k)
        for (int i = 0; i < 10; ++i) C(i, k) = entry(rng);
      for (int i = 0; i < 10; ++i) x(i) = entry(rng);
      if (trial == 0) C.col(0).setZero();
      Eigen::VectorXd expected(m);
      expected.noalias() = C.transpose() * x;
      Eigen::VectorXd out(m);
      transposed_product_10(C, x, out.data());
      CHECK(same_bits(out.data(), expected.data(), m));
    }
}

TEST_CASE("transposed_product_10: a row of 10 weights times 10 rows, and the sum of two, as Eigen sums them") {
  // The reduced problem's chain rule (shape/reduced_problem.cpp) had g.head(k) = w_in * A and
  // g.tail(k) = w_out * B + w_in * C with fixed 1 x 10 weights; it now sums them with this function.
  Rng rng(11);
  for (int k = 2; k <= 40; ++k)
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::Matrix<double, 10, Eigen::Dynamic> A(10, k), B(10, k), C(10, k);
      Eigen::Matrix<double, 1, 10> w_in, w_out;
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < 10; ++i) {
          A(i, j) = entry(rng);
          B(i, j) = entry(rng);
          C(i, j) = entry(rng);
        }
      for (int i = 0; i < 10; ++i) {
        w_in(i) = entry(rng);
        w_out(i) = entry(rng);
      }
      if (trial == 0) w_out.setZero();
      if (trial == 1) B.col(0).setZero();
      Eigen::RowVectorXd expected(2 * k);
      expected.head(k) = w_in * A;
      expected.tail(k) = w_out * B + w_in * C;
      Eigen::RowVectorXd head(k), outer_part(k), inner_part(k);
      transposed_product_10(A, w_in.transpose(), head.data());
      transposed_product_10(B, w_out.transpose(), outer_part.data());
      transposed_product_10(C, w_in.transpose(), inner_part.data());
      const Eigen::RowVectorXd tail = outer_part + inner_part;
      CHECK(same_bits(head.data(), expected.data(), k));
      CHECK(same_bits(tail.data(), expected.data() + k, k));
    }
}
