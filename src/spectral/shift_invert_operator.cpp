#include "spectral/shift_invert_operator.h"

#include <emmintrin.h>  // SSE2: part of the x86-64 baseline

#include <algorithm>
#include <cmath>

#include "sparse/fill_reducing_ordering.h"

namespace offsetopt {

namespace {

// Supernodes wider than this are split, so a supernode's rows of the block stay in L1.
constexpr int kMaxSupernodeWidth = 96;

struct SolveData {
  int n;
  const int* rows;
  const double* values;
  const double* pivots;
};

// Forward (L z = x), scaling (z / d) and backward (Lᵀ w = z / d) on a row-major block of width
// kWidth (0: the run-time `width`, at most 64). Every sum runs in a fixed order: entry by entry
// the terms are subtracted in increasing column (forward) or row (backward) order.
template <int kWidth, class Supernodes>
void solve_block(const SolveData& data, const Supernodes& supernodes, int width, double* x) {
  const int b = kWidth > 0 ? kWidth : width;
  double acc[kWidth > 0 ? kWidth : 64];
  std::vector<double> buffer(static_cast<std::size_t>(kMaxSupernodeWidth) * static_cast<std::size_t>(b));
  for (const auto& s : supernodes) {
    double* xs = x + static_cast<std::ptrdiff_t>(s.first) * b;
    const double* triangle = data.values + s.triangle;
    for (int i = 1; i < s.width; ++i) {
      const double* l = triangle + static_cast<std::ptrdiff_t>(i) * (i - 1) / 2;
      for (int c = 0; c < b; ++c) acc[c] = xs[i * b + c];
      for (int j = 0; j < i; ++j)
        for (int c = 0; c < b; ++c) acc[c] -= l[j] * xs[j * b + c];
      for (int c = 0; c < b; ++c) xs[i * b + c] = acc[c];
    }
    const double* below = data.values + s.below;
    const int* rows = data.rows + s.row_begin;
    int r = 0;
    if constexpr (kWidth > 1) {
      // Two rows at a time: independent chains, shared loads of the supernode's rows. Column
      // pairs in SSE registers, an odd last column in scalars: the same operations per entry.
      constexpr int H = kWidth / 2;
      constexpr bool kOdd = kWidth % 2 == 1;
      for (; r + 1 < s.row_count; r += 2) {
        double* x0 = x + static_cast<std::ptrdiff_t>(rows[r]) * b;
        double* x1 = x + static_cast<std::ptrdiff_t>(rows[r + 1]) * b;
        const double* l0 = below + static_cast<std::ptrdiff_t>(r) * s.width;
        const double* l1 = l0 + s.width;
        __m128d a0[H], a1[H];
        double t0 = kOdd ? x0[kWidth - 1] : 0.0, t1 = kOdd ? x1[kWidth - 1] : 0.0;
        for (int h = 0; h < H; ++h) {
          a0[h] = _mm_loadu_pd(x0 + 2 * h);
          a1[h] = _mm_loadu_pd(x1 + 2 * h);
        }
        for (int j = 0; j < s.width; ++j) {
          const __m128d f0 = _mm_set1_pd(l0[j]), f1 = _mm_set1_pd(l1[j]);
          const double* xj = xs + j * kWidth;
          for (int h = 0; h < H; ++h) {
            const __m128d v = _mm_loadu_pd(xj + 2 * h);
            a0[h] = _mm_sub_pd(a0[h], _mm_mul_pd(f0, v));
            a1[h] = _mm_sub_pd(a1[h], _mm_mul_pd(f1, v));
          }
          if (kOdd) {
            t0 -= l0[j] * xj[kWidth - 1];
            t1 -= l1[j] * xj[kWidth - 1];
          }
        }
        for (int h = 0; h < H; ++h) {
          _mm_storeu_pd(x0 + 2 * h, a0[h]);
          _mm_storeu_pd(x1 + 2 * h, a1[h]);
        }
        if (kOdd) {
          x0[kWidth - 1] = t0;
          x1[kWidth - 1] = t1;
        }
      }
    }
    for (; r < s.row_count; ++r) {
      double* xr = x + static_cast<std::ptrdiff_t>(rows[r]) * b;
      const double* l = below + static_cast<std::ptrdiff_t>(r) * s.width;
      for (int c = 0; c < b; ++c) acc[c] = xr[c];
      for (int j = 0; j < s.width; ++j)
        for (int c = 0; c < b; ++c) acc[c] -= l[j] * xs[j * b + c];
      for (int c = 0; c < b; ++c) xr[c] = acc[c];
    }
  }
  for (int i = 0; i < data.n; ++i) {
    const double d = data.pivots[i];
    for (int c = 0; c < b; ++c) x[static_cast<std::ptrdiff_t>(i) * b + c] /= d;
  }
  for (auto it = supernodes.rbegin(); it != supernodes.rend(); ++it) {
    const auto& s = *it;
    double* xs = x + static_cast<std::ptrdiff_t>(s.first) * b;
    double* a = buffer.data();
    std::copy(xs, xs + static_cast<std::ptrdiff_t>(s.width) * b, a);
    const double* below = data.values + s.below;
    const int* rows = data.rows + s.row_begin;
    int r = 0;
    if constexpr (kWidth > 1) {
      // Two rows at a time: each a[j] loaded and stored once per pair, terms still in row order.
      constexpr int H = kWidth / 2;
      constexpr bool kOdd = kWidth % 2 == 1;
      for (; r + 1 < s.row_count; r += 2) {
        const double* x0 = x + static_cast<std::ptrdiff_t>(rows[r]) * b;
        const double* x1 = x + static_cast<std::ptrdiff_t>(rows[r + 1]) * b;
        const double* l0 = below + static_cast<std::ptrdiff_t>(r) * s.width;
        const double* l1 = l0 + s.width;
        __m128d v0[H], v1[H];
        for (int h = 0; h < H; ++h) {
          v0[h] = _mm_loadu_pd(x0 + 2 * h);
          v1[h] = _mm_loadu_pd(x1 + 2 * h);
        }
        for (int j = 0; j < s.width; ++j) {
          const __m128d f0 = _mm_set1_pd(l0[j]), f1 = _mm_set1_pd(l1[j]);
          double* aj = a + j * kWidth;
          for (int h = 0; h < H; ++h) {
            __m128d t = _mm_sub_pd(_mm_loadu_pd(aj + 2 * h), _mm_mul_pd(f0, v0[h]));
            _mm_storeu_pd(aj + 2 * h, _mm_sub_pd(t, _mm_mul_pd(f1, v1[h])));
          }
          if (kOdd) {
            const double t = aj[kWidth - 1] - l0[j] * x0[kWidth - 1];
            aj[kWidth - 1] = t - l1[j] * x1[kWidth - 1];
          }
        }
      }
    }
    for (; r < s.row_count; ++r) {
      const double* xr = x + static_cast<std::ptrdiff_t>(rows[r]) * b;
      const double* l = below + static_cast<std::ptrdiff_t>(r) * s.width;
      for (int j = 0; j < s.width; ++j)
        for (int c = 0; c < b; ++c) a[j * b + c] -= l[j] * xr[c];
    }
    // The triangle by rows, last first: row i is final when it is read (contiguous reads of the
    // packed rows; each a[j] receives its terms in decreasing i).
    const double* triangle = data.values + s.triangle;
    for (int i = s.width - 1; i >= 1; --i) {
      const double* l = triangle + static_cast<std::ptrdiff_t>(i) * (i - 1) / 2;
      const double* ai = a + i * b;
      for (int j = 0; j < i; ++j)
        for (int c = 0; c < b; ++c) a[j * b + c] -= l[j] * ai[c];
    }
    std::copy(a, a + static_cast<std::ptrdiff_t>(s.width) * b, xs);
  }
}

}  // namespace

ShiftInvertOperator::ShiftInvertOperator(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass,
                                         double shift, const Vertices* positions, WorkerPool* pool)
    : n_(L.rows()) {
  const int n = static_cast<int>(n_);
  const int threads = pool ? pool->size() : 1;
  const FillReducingOrdering ordering =
      positions ? fill_reducing_ordering(L, *positions, L, 1, threads > 1) : fill_reducing_ordering(L, Vertices(), L, 0, false);
  std::vector<int> new_index(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) new_index[static_cast<std::size_t>(ordering.new_to_old[static_cast<std::size_t>(i)])] = i;

  // K = P (L + sM) Pᵀ, both triangles (the factorisation reads each pair where it needs it).
  BlockLdlt factor;
  {
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<std::size_t>(L.nonZeros() + n));
    for (int col = 0; col < n; ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it)
        triplets.emplace_back(new_index[static_cast<std::size_t>(it.row())], new_index[static_cast<std::size_t>(col)], it.value());
    for (int i = 0; i < n; ++i) {
      const int old = ordering.new_to_old[static_cast<std::size_t>(i)];
      triplets.emplace_back(i, i, shift * (mass.size() ? mass(old) : 1.0));
    }
    Eigen::SparseMatrix<double> K(n, n);
    K.setFromTriplets(triplets.begin(), triplets.end());
    triplets = {};
    SupernodalCholesky cholesky;
    cholesky.set_thread_count(threads);
    cholesky.analyze(K);
    if (!cholesky.factorize(K)) {
      status_ = Status::not_positive_definite;
      return;
    }
    factor_ = cholesky.block_ldlt(kMaxSupernodeWidth);
  }
  factor_nonzeros_ = static_cast<Eigen::Index>(ordering.counts.nonzeros) - n_;
  order_.resize(static_cast<std::size_t>(n));
  scale_.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    order_[static_cast<std::size_t>(i)] = ordering.new_to_old[static_cast<std::size_t>(factor_.order[static_cast<std::size_t>(i)])];
    scale_[static_cast<std::size_t>(i)] = mass.size() ? std::sqrt(mass(order_[static_cast<std::size_t>(i)])) : 1.0;
  }
  for (double pivot : factor_.pivots)
    if (!(pivot > 0.0) || !std::isfinite(pivot)) {
      status_ = Status::not_positive_definite;
      return;
    }
}

void ShiftInvertOperator::apply(const double* in, Eigen::Index in_stride, int b, RowMatrix& out,
                                WorkerPool* pool) const {
  out.resize(n_, b);
  const int parts = pool ? std::min(pool->size(), b) : 1;
  if (static_cast<int>(work_.size()) < parts) work_.resize(static_cast<std::size_t>(parts));
  // Columns are independent: each part solves its own columns with its own buffer.
  const auto solve_columns = [&](int part) {
    const int c0 = static_cast<int>(split_point(b, parts, part));
    const int c1 = static_cast<int>(split_point(b, parts, part + 1));
    if (c1 > c0) solve_columns_into(in + c0, in_stride, c1 - c0, out.data() + c0, b, work_[part]);
  };
  if (parts == 1)
    solve_columns(0);
  else
    pool->run([&](int part) {
      if (part < parts) solve_columns(part);
    });
}

void ShiftInvertOperator::solve_columns_into(const double* in, Eigen::Index in_stride, int w, double* out,
                                             Eigen::Index out_stride, RowMatrix& work) const {
  const int n = static_cast<int>(n_);
  work.resize(n_, w);
  double* x = work.data();
  for (int i = 0; i < n; ++i) {
    const double* src = in + static_cast<std::ptrdiff_t>(order_[i]) * in_stride;
    const double d = scale_[i];
    for (int c = 0; c < w; ++c) x[static_cast<std::ptrdiff_t>(i) * w + c] = d * src[c];
  }
  const SolveData data{n, factor_.rows.data(), factor_.values.data(), factor_.pivots.data()};
  switch (w) {
    case 1: solve_block<1>(data, factor_.supernodes, w, x); break;
    case 2: solve_block<2>(data, factor_.supernodes, w, x); break;
    case 3: solve_block<3>(data, factor_.supernodes, w, x); break;
    case 4: solve_block<4>(data, factor_.supernodes, w, x); break;
    case 5: solve_block<5>(data, factor_.supernodes, w, x); break;
    case 6: solve_block<6>(data, factor_.supernodes, w, x); break;
    case 8: solve_block<8>(data, factor_.supernodes, w, x); break;
    default: {
      // Other widths in slices of at most 64 columns (each column is solved independently).
      for (int c0 = 0; c0 < w; c0 += 64) {
        const int slice = std::min(64, w - c0);
        RowMatrix part = work.middleCols(c0, slice);
        solve_block<0>(data, factor_.supernodes, slice, part.data());
        work.middleCols(c0, slice) = part;
      }
    }
  }
  for (int i = 0; i < n; ++i) {
    double* dst = out + static_cast<std::ptrdiff_t>(order_[i]) * out_stride;
    const double d = scale_[i];
    for (int c = 0; c < w; ++c) dst[c] = d * x[static_cast<std::ptrdiff_t>(i) * w + c];
  }
}

}  // namespace offsetopt
