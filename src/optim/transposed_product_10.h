// out = Cᵀ x for C of 10 rows (m columns, column-major) and x of 10 entries: each of the m entries
// summed exactly as Eigen's row-major matrix-vector product Cᵀ * x sums it (Eigen 3.4, SSE2, no
// FMA: the even and the odd terms apart, in order, onto +0, then the two added, then added to +0),
// so a caller that used the product gets the same bits without a dynamic product per call (the
// reachability programme builds tens of thousands of 10-term columns a pass).
//
// For m >= 2 (Eigen takes a single row as a dot product, summed another way).
// tests/optim/test_paired_pricing.cpp checks the bits against Eigen's product.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

void transposed_product_10(const Eigen::Matrix<double, 10, Eigen::Dynamic>& C, const Eigen::Matrix<double, 10, 1>& x, double* out);

}  // namespace offsetopt
