#include "spectral/shift_invert_operator.h"

#include <emmintrin.h>  // SSE2: part of the x86-64 baseline

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <memory>

#include "sparse/nested_dissection.h"

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

namespace {

using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>>;

// The factorisation is split at the first dissection level when the separator is small enough
// for a dense factor and the matrix large enough to gain from it.
constexpr int kMaxDenseSeparator = 2500;
constexpr int kMinSplitSize = 20000;
// A column of the dense separator factor is computed on the pool's threads from this many
// multiply-adds ((rows below) x (columns left of it)) on.
constexpr double kMinParallelColumnWork = 200001;

// Lower triangle (column-major) of D = Lr diag(d) Lrᵀ for a dense unit lower Lr stored by rows
// (row i holds columns 0..i-1 at i(i-1)/2): T(i, j) = sum_{k <= j} Lr(i, k) d_k Lr(j, k).
// Rows of T are split among the pool's threads; each entry sums k in increasing order.
void lower_times_transpose(const std::vector<double>& rows, const std::vector<double>& d, int m,
                           std::vector<double>& T, WorkerPool* pool) {
  T.assign(static_cast<std::size_t>(m) * m, 0.0);
  auto entry = [&](int i, int j) {  // i >= j
    const double* li = rows.data() + static_cast<std::ptrdiff_t>(i) * (i - 1) / 2;
    const double* lj = rows.data() + static_cast<std::ptrdiff_t>(j) * (j - 1) / 2;
    double sum = 0.0;
    for (int k = 0; k < j; ++k) sum += li[k] * d[k] * lj[k];
    return sum + (i == j ? d[j] : li[j] * d[j]);  // k = j: Lr(j, j) = 1
  };
  auto band = [&](int part, int parts) {
    for (int i = static_cast<int>(split_point(m, parts, part)); i < split_point(m, parts, part + 1); ++i)
      for (int j = 0; j <= i; ++j) T[static_cast<std::size_t>(j) * m + i] = entry(i, j);
  };
  if (pool && pool->size() > 1)
    pool->run([&](int part) { band(part, pool->size()); });
  else
    band(0, 1);
}

// Dense LDLᵀ of the symmetric matrix whose lower triangle is S (column-major, m by m): L by
// rows (packed as above), pivots in d. False when a pivot is not positive.
bool dense_ldlt(const std::vector<double>& S, int m, std::vector<double>& rows, std::vector<double>& d,
                WorkerPool* pool) {
  rows.assign(static_cast<std::size_t>(m) * (m > 0 ? m - 1 : 0) / 2, 0.0);
  d.assign(static_cast<std::size_t>(m), 0.0);
  std::vector<double> weighted(static_cast<std::size_t>(m));  // L(j, k) d_k for the current j
  for (int j = 0; j < m; ++j) {
    const double* lj = rows.data() + static_cast<std::ptrdiff_t>(j) * (j - 1) / 2;
    double pivot = S[static_cast<std::size_t>(j) * m + j];
    for (int k = 0; k < j; ++k) {
      weighted[static_cast<std::size_t>(k)] = lj[k] * d[k];
      pivot -= lj[k] * weighted[static_cast<std::size_t>(k)];
    }
    if (!(pivot > 0.0) || !std::isfinite(pivot)) return false;
    d[j] = pivot;
    // Column j below the diagonal; rows split among threads, each a fixed-order dot product.
    auto column = [&](int part, int parts) {
      const int count = m - j - 1;
      for (int t = static_cast<int>(split_point(count, parts, part)); t < split_point(count, parts, part + 1); ++t) {
        const int i = j + 1 + t;
        double* li = rows.data() + static_cast<std::ptrdiff_t>(i) * (i - 1) / 2;
        double sum = S[static_cast<std::size_t>(j) * m + i];
        for (int k = 0; k < j; ++k) sum -= li[k] * weighted[static_cast<std::size_t>(k)];
        li[j] = sum / pivot;
      }
    };
    if (execution_policy(pool, static_cast<double>(m - j) * j, kMinParallelColumnWork) == ExecutionPolicy::parallel)
      pool->run([&](int part) { column(part, pool->size()); });
    else
      column(0, 1);
  }
  return true;
}

}  // namespace

void ShiftInvertOperator::add_supernodes(const int* start, const int* index, const double* value, int columns,
                                         int column_offset, const std::vector<int>& row_map) {
  // Column c joins the run when column c-1's pattern is {c} followed by column c's.
  auto continues = [&](int c) {
    const int previous = start[c] - start[c - 1];
    if (previous < 1 || index[start[c - 1]] != c || previous - 1 != start[c + 1] - start[c]) return false;
    return std::equal(index + start[c - 1] + 1, index + start[c], index + start[c]);
  };
  for (int first = 0; first < columns;) {
    int width = 1;
    while (first + width < columns && width < kMaxSupernodeWidth && continues(first + width)) ++width;
    Supernode s;
    s.first = column_offset + first;
    s.width = width;
    const int last = first + width - 1;
    s.row_begin = static_cast<int>(rows_.size());
    s.row_count = start[last + 1] - start[last];
    for (int p = start[last]; p < start[last + 1]; ++p) rows_.push_back(row_map[static_cast<std::size_t>(index[p])]);
    s.triangle = values_.size();
    for (int i = 1; i < width; ++i)
      for (int j = 0; j < i; ++j) values_.push_back(value[start[first + j] + (i - j - 1)]);
    s.below = values_.size();
    for (int r = 0; r < s.row_count; ++r)
      for (int j = 0; j < width; ++j) values_.push_back(value[start[first + j] + (width - 1 - j) + r]);
    supernodes_.push_back(s);
    first += width;
  }
}

ShiftInvertOperator::ShiftInvertOperator(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass,
                                         double shift, const Vertices* positions, WorkerPool* pool)
    : n_(L.rows()) {
  const int n = static_cast<int>(n_);
  DissectionSplit split;
  if (positions) {
    order_ = nested_dissection(L, *positions, {}, &split);
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

  // Lower triangle of K = P (L + sM) Pᵀ, as triplets.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(static_cast<std::size_t>(L.nonZeros() / 2 + n));
  for (int col = 0; col < n; ++col) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, col); it; ++it) {
      const int r = new_index[static_cast<std::size_t>(it.row())], c = new_index[static_cast<std::size_t>(col)];
      if (r >= c) triplets.emplace_back(r, c, it.value());
    }
  }
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, shift * (mass.size() ? mass(order_[i]) : 1.0));

  const int nA = split.first, nB = split.second, nS = split.separator;
  const bool two_parts = positions && n >= kMinSplitSize && nA > 0 && nB > 0 && nS <= kMaxDenseSeparator &&
                         nA + nB + nS == n;
  if (!two_parts) {
    Factor factor;
    {
      Eigen::SparseMatrix<double> K(n, n);
      K.setFromTriplets(triplets.begin(), triplets.end());
      triplets = {};
      factor.compute(K);
    }
    if (factor.info() != Eigen::Success) {
      status_ = Status::NotPositiveDefinite;
      return;
    }
    const Eigen::VectorXd pivots = factor.vectorD();  // returned by value
    pivot_.assign(pivots.data(), pivots.data() + n);
    const Eigen::SparseMatrix<double>& lower = factor.matrixL().nestedExpression();
    factor_nonzeros_ = lower.nonZeros();
    values_.reserve(static_cast<std::size_t>(factor_nonzeros_));
    std::vector<int> identity(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) identity[static_cast<std::size_t>(i)] = i;
    add_supernodes(lower.outerIndexPtr(), lower.innerIndexPtr(), lower.valuePtr(), n, 0, identity);
  } else {
    // Order [A, B, S]: no entry couples A and B. Eigen factors K[A∪S] and K[B∪S] (in parallel
    // when there are threads); their trailing blocks are the Schur complements
    // T_A = K_SS - K_SA K_AA⁻¹ K_AS and T_B alike, so the separator's Schur complement is
    // T_A + T_B - K_SS, factored densely. The result is the LDLᵀ of K in the same order.
    const int sBegin = nA + nB;
    std::vector<Eigen::Triplet<double>> part[2];
    std::vector<double> separator(static_cast<std::size_t>(nS) * nS, 0.0);  // K_SS lower, column-major
    for (const auto& t : triplets) {
      const int r = t.row(), c = t.col();
      const bool rS = r >= sBegin, cS = c >= sBegin;
      const int rp = r < nA ? 0 : (r < sBegin ? 1 : 2), cp = c < nA ? 0 : (c < sBegin ? 1 : 2);
      if (rS && cS) {
        separator[static_cast<std::size_t>(c - sBegin) * nS + (r - sBegin)] += t.value();
        part[0].emplace_back(r - nB, c - nB, t.value());
        part[1].emplace_back(r - nA, c - nA, t.value());
      } else if ((rp == 0 || rS) && cp == 0) {
        part[0].emplace_back(rS ? r - nB : r, c, t.value());
      } else if ((rp == 1 || rS) && cp == 1) {
        part[1].emplace_back(r - nA, c - nA, t.value());
      } else {
        status_ = Status::NotPositiveDefinite;  // cannot happen with a valid dissection
        return;
      }
    }
    triplets = {};
    std::unique_ptr<Factor> factors[2] = {std::make_unique<Factor>(), std::make_unique<Factor>()};
    std::vector<double> schur[2];
    bool ok[2] = {false, false};
    const int sizes[2] = {nA, nB};
    auto factor_part = [&](int p) {
      const int m = sizes[p] + nS;
      {
        Eigen::SparseMatrix<double> K(m, m);
        K.setFromTriplets(part[p].begin(), part[p].end());
        part[p] = {};
        factors[p]->compute(K);
      }
      if (factors[p]->info() != Eigen::Success) return;
      // The trailing block: dense unit lower rows and pivots of the separator.
      const Eigen::SparseMatrix<double>& lower = factors[p]->matrixL().nestedExpression();
      const int* st = lower.outerIndexPtr();
      const int* ix = lower.innerIndexPtr();
      const double* va = lower.valuePtr();
      std::vector<double> rows(static_cast<std::size_t>(nS) * (nS > 0 ? nS - 1 : 0) / 2, 0.0), d(static_cast<std::size_t>(nS));
      const Eigen::VectorXd pivots = factors[p]->vectorD();  // returned by value
      for (int j = 0; j < nS; ++j) {
        const int col = sizes[p] + j;
        d[static_cast<std::size_t>(j)] = pivots(col);
        for (int q = st[col]; q < st[col + 1]; ++q) {
          const int i = ix[q] - sizes[p];
          rows[static_cast<std::size_t>(i) * (i - 1) / 2 + j] = va[q];
        }
      }
      lower_times_transpose(rows, d, nS, schur[p], nullptr);
      ok[p] = true;
    };
    if (pool && pool->size() > 1)
      pool->run([&](int p) {
        for (int q = p; q < 2; q += pool->size()) factor_part(q);
      });
    else
      for (int q = 0; q < 2; ++q) factor_part(q);
    if (!ok[0] || !ok[1]) {
      status_ = Status::NotPositiveDefinite;
      return;
    }
    for (std::size_t e = 0; e < separator.size(); ++e) separator[e] = schur[0][e] + schur[1][e] - separator[e];
    std::vector<double> separator_rows, separator_pivots;
    if (!dense_ldlt(separator, nS, separator_rows, separator_pivots, pool)) {
      status_ = Status::NotPositiveDefinite;
      return;
    }
    pivot_.resize(static_cast<std::size_t>(n));
    for (int p = 0; p < 2; ++p) {
      const int offset = p == 0 ? 0 : nA;
      const Eigen::VectorXd pivots = factors[p]->vectorD();
      for (int i = 0; i < sizes[p]; ++i) pivot_[static_cast<std::size_t>(offset + i)] = pivots(i);
    }
    for (int i = 0; i < nS; ++i) pivot_[static_cast<std::size_t>(sBegin + i)] = separator_pivots[static_cast<std::size_t>(i)];
    // Supernodes of A and B (rows of the separator mapped to their global index), then the
    // dense separator.
    for (int p = 0; p < 2; ++p) {
      const int offset = p == 0 ? 0 : nA;
      std::vector<int> row_map(static_cast<std::size_t>(sizes[p] + nS));
      for (int i = 0; i < sizes[p]; ++i) row_map[static_cast<std::size_t>(i)] = offset + i;
      for (int i = 0; i < nS; ++i) row_map[static_cast<std::size_t>(sizes[p] + i)] = sBegin + i;
      const Eigen::SparseMatrix<double>& lower = factors[p]->matrixL().nestedExpression();
      add_supernodes(lower.outerIndexPtr(), lower.innerIndexPtr(), lower.valuePtr(), sizes[p], offset, row_map);
      factor_nonzeros_ += lower.outerIndexPtr()[sizes[p]];
      factors[p].reset();  // free it before the next one is copied
    }
    for (int first = 0; first < nS; first += kMaxSupernodeWidth) {
      Supernode s;
      s.first = sBegin + first;
      s.width = std::min(kMaxSupernodeWidth, nS - first);
      s.row_begin = static_cast<int>(rows_.size());
      s.row_count = nS - first - s.width;
      for (int r = first + s.width; r < nS; ++r) rows_.push_back(sBegin + r);
      auto l = [&](int i, int j) { return separator_rows[static_cast<std::size_t>(i) * (i - 1) / 2 + j]; };
      s.triangle = values_.size();
      for (int i = 1; i < s.width; ++i)
        for (int j = 0; j < i; ++j) values_.push_back(l(first + i, first + j));
      s.below = values_.size();
      for (int r = first + s.width; r < nS; ++r)
        for (int j = 0; j < s.width; ++j) values_.push_back(l(r, first + j));
      supernodes_.push_back(s);
    }
    factor_nonzeros_ += static_cast<Eigen::Index>(nS) * (nS - 1) / 2;
  }
  for (int i = 0; i < n; ++i)
    if (!(pivot_[static_cast<std::size_t>(i)] > 0.0) || !std::isfinite(pivot_[static_cast<std::size_t>(i)])) {
      status_ = Status::NotPositiveDefinite;
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
  const SolveData data{n, rows_.data(), values_.data(), pivot_.data()};
  switch (w) {
    case 1: solve_block<1>(data, supernodes_, w, x); break;
    case 2: solve_block<2>(data, supernodes_, w, x); break;
    case 3: solve_block<3>(data, supernodes_, w, x); break;
    case 4: solve_block<4>(data, supernodes_, w, x); break;
    case 5: solve_block<5>(data, supernodes_, w, x); break;
    case 6: solve_block<6>(data, supernodes_, w, x); break;
    case 8: solve_block<8>(data, supernodes_, w, x); break;
    default: {
      // Other widths in slices of at most 64 columns (each column is solved independently).
      for (int c0 = 0; c0 < w; c0 += 64) {
        const int slice = std::min(64, w - c0);
        RowMatrix part = work.middleCols(c0, slice);
        solve_block<0>(data, supernodes_, slice, part.data());
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
