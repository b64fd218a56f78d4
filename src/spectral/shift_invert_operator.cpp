#include "spectral/shift_invert_operator.h"

#include <cmath>

#include "spectral/nested_dissection.h"

namespace offsetopt {

namespace {

// The triangular solves of LDLᵀ on a row-major block of width kWidth (0: the run-time `width`).
// `lower_*` is the strictly lower unit triangle by rows, `upper_*` the same triangle by columns.
template <int kWidth>
void solve_block(int n, int width, const int* lower_start, const int* lower_index, const double* lower_value,
                 const int* upper_start, const int* upper_index, const double* upper_value, const double* pivots,
                 double* x) {
  const int b = kWidth > 0 ? kWidth : width;
  double acc[kWidth > 0 ? kWidth : 64];
  // Forward: z_i = x_i - sum_{j<i} L_ij z_j.
  for (int i = 0; i < n; ++i) {
    double* xi = x + static_cast<std::ptrdiff_t>(i) * b;
    for (int c = 0; c < b; ++c) acc[c] = xi[c];
    for (int p = lower_start[i]; p < lower_start[i + 1]; ++p) {
      const double l = lower_value[p];
      const double* xj = x + static_cast<std::ptrdiff_t>(lower_index[p]) * b;
      for (int c = 0; c < b; ++c) acc[c] -= l * xj[c];
    }
    for (int c = 0; c < b; ++c) xi[c] = acc[c];
  }
  // Backward: w_j = z_j / d_j - sum_{i>j} L_ij w_i.
  for (int j = n - 1; j >= 0; --j) {
    double* xj = x + static_cast<std::ptrdiff_t>(j) * b;
    const double d = pivots[j];
    for (int c = 0; c < b; ++c) acc[c] = xj[c] / d;
    for (int p = upper_start[j]; p < upper_start[j + 1]; ++p) {
      const double l = upper_value[p];
      const double* xi = x + static_cast<std::ptrdiff_t>(upper_index[p]) * b;
      for (int c = 0; c < b; ++c) acc[c] -= l * xi[c];
    }
    for (int c = 0; c < b; ++c) xj[c] = acc[c];
  }
}

}  // namespace

ShiftInvertOperator::ShiftInvertOperator(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass,
                                         double shift, const Vertices* positions)
    : n_(L.rows()) {
  const int n = static_cast<int>(n_);
  if (positions) {
    order_ = nested_dissection(L, *positions);
  } else {
    // Eigen's AMD (as SimplicialLDLT uses it) returns P⁻¹ with indices()[new] = old.
    Eigen::AMDOrdering<int> amd;
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    amd(L, inverse);
    order_.assign(inverse.indices().data(), inverse.indices().data() + n);
  }
  std::vector<int> new_index(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) new_index[static_cast<std::size_t>(order_[i])] = i;

  scale_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) scale_[i] = mass.size() ? std::sqrt(mass(order_[i])) : 1.0;

  // Lower triangle of P (L + sM) Pᵀ.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(L.nonZeros() / 2 + n));
  for (int col = 0; col < n; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      const int r = new_index[static_cast<std::size_t>(it.row())], c = new_index[static_cast<std::size_t>(col)];
      if (r >= c) triplets.emplace_back(r, c, it.value());
    }
  }
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, shift * (mass.size() ? mass(order_[i]) : 1.0));
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(triplets.begin(), triplets.end());
  triplets = {};

  factor_.compute(K);
  if (factor_.info() != Eigen::Success) {
    status_ = Status::NotPositiveDefinite;
    return;
  }
  const Eigen::VectorXd& pivots = factor_.vectorD();
  pivot_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    if (!(pivots(i) > 0.0) || !std::isfinite(pivots(i))) {
      status_ = Status::NotPositiveDefinite;
      return;
    }
    pivot_[i] = pivots(i);
  }

  // The strictly lower triangle by rows (a transpose of Eigen's by-column storage).
  const Eigen::SparseMatrix<double>& lower = factor_.matrixL().nestedExpression();
  const int* col_start = lower.outerIndexPtr();
  const int* rows = lower.innerIndexPtr();
  const double* values = lower.valuePtr();
  row_start_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int p = col_start[j]; p < col_start[j + 1]; ++p) ++row_start_[static_cast<std::size_t>(rows[p]) + 1];
  for (int i = 0; i < n; ++i) row_start_[i + 1] += row_start_[i];
  row_columns_.resize(static_cast<std::size_t>(row_start_[n]));
  row_values_.resize(static_cast<std::size_t>(row_start_[n]));
  std::vector<int> fill(row_start_.begin(), row_start_.end() - 1);
  for (int j = 0; j < n; ++j) {
    for (int p = col_start[j]; p < col_start[j + 1]; ++p) {
      const int slot = fill[static_cast<std::size_t>(rows[p])]++;
      row_columns_[static_cast<std::size_t>(slot)] = j;
      row_values_[static_cast<std::size_t>(slot)] = values[p];
    }
  }
}

void ShiftInvertOperator::apply(const double* in, Eigen::Index in_stride, int b, RowMatrix& out) const {
  const int n = static_cast<int>(n_);
  work_.resize(n_, b);
  double* x = work_.data();
  for (int i = 0; i < n; ++i) {
    const double* src = in + static_cast<std::ptrdiff_t>(order_[i]) * in_stride;
    const double d = scale_[i];
    for (int c = 0; c < b; ++c) x[static_cast<std::ptrdiff_t>(i) * b + c] = d * src[c];
  }
  const Eigen::SparseMatrix<double>& lower = factor_.matrixL().nestedExpression();
  const int* ls = row_start_.data();
  const int* li = row_columns_.data();
  const double* lv = row_values_.data();
  const int* us = lower.outerIndexPtr();
  const int* ui = lower.innerIndexPtr();
  const double* uv = lower.valuePtr();
  const double* pv = pivot_.data();
  switch (b) {
    case 1: solve_block<1>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 2: solve_block<2>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 4: solve_block<4>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 6: solve_block<6>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 8: solve_block<8>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 12: solve_block<12>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    case 16: solve_block<16>(n, b, ls, li, lv, us, ui, uv, pv, x); break;
    default: {
      for (int c0 = 0; c0 < b; c0 += 64) {
        // Run-time widths above 64 are split (the accumulator is 64 wide); not a hot path.
        const int w = b - c0 < 64 ? b - c0 : 64;
        RowMatrix part = work_.middleCols(c0, w);
        solve_block<0>(n, w, ls, li, lv, us, ui, uv, pv, part.data());
        work_.middleCols(c0, w) = part;
      }
    }
  }
  out.resize(n_, b);
  for (int i = 0; i < n; ++i) {
    double* dst = out.data() + static_cast<std::ptrdiff_t>(order_[i]) * b;
    const double d = scale_[i];
    for (int c = 0; c < b; ++c) dst[c] = d * x[static_cast<std::ptrdiff_t>(i) * b + c];
  }
}

}  // namespace offsetopt
