#include "spectral/row_block_kernels.h"

#include <emmintrin.h>  // SSE2: part of the x86-64 baseline, so no run-time dispatch

#include <algorithm>
#include <vector>

namespace offsetopt {

namespace {

// Rows per chunk in the projection: the chunk of W stays in L1, the chunk of Q in L2. Fixed, so
// the order of the partial sums does not depend on the machine.
constexpr Eigen::Index kChunkRows = 128;

// C(a, :) = sum over rows of Q(i, a) W(i, :), kTile columns a per pass over a chunk (kWidth/2
// * kTile accumulators in registers), kWidth (even) columns of W. Each entry sums its chunk in row
// order, then the chunk partials in chunk order.
template <int kWidth, int kTile>
void project_tile(const double* Q, Eigen::Index ldq, int a, const double* W, Eigen::Index i0, Eigen::Index i1,
                  double* C) {
  constexpr int H = kWidth / 2;
  __m128d acc[kTile][H];
  for (int t = 0; t < kTile; ++t)
    for (int h = 0; h < H; ++h) acc[t][h] = _mm_setzero_pd();
  for (Eigen::Index i = i0; i < i1; ++i) {
    const double* q = Q + i * ldq + a;
    const double* w = W + i * kWidth;
    __m128d wv[H];
    for (int h = 0; h < H; ++h) wv[h] = _mm_loadu_pd(w + 2 * h);
    for (int t = 0; t < kTile; ++t) {
      const __m128d qt = _mm_set1_pd(q[t]);
      for (int h = 0; h < H; ++h) acc[t][h] = _mm_add_pd(acc[t][h], _mm_mul_pd(qt, wv[h]));
    }
  }
  for (int t = 0; t < kTile; ++t) {
    double* c = C + static_cast<std::ptrdiff_t>(a + t) * kWidth;
    for (int h = 0; h < H; ++h) _mm_storeu_pd(c + 2 * h, _mm_add_pd(_mm_loadu_pd(c + 2 * h), acc[t][h]));
  }
}

template <int kWidth>
void project_even(const double* Q, Eigen::Index ldq, int j, const double* W, Eigen::Index n, double* C) {
  // As many columns per pass as registers allow: 16 xmm registers hold kTile * kWidth/2
  // accumulators plus the kWidth/2 values of the row of W.
  constexpr int kTile = kWidth <= 4 ? 4 : (kWidth <= 6 ? 3 : 2);
  std::fill(C, C + static_cast<std::ptrdiff_t>(j) * kWidth, 0.0);
  for (Eigen::Index i0 = 0; i0 < n; i0 += kChunkRows) {
    const Eigen::Index i1 = std::min(n, i0 + kChunkRows);
    int a = 0;
    for (; a + kTile <= j; a += kTile) project_tile<kWidth, kTile>(Q, ldq, a, W, i0, i1, C);
    for (; a < j; ++a) project_tile<kWidth, 1>(Q, ldq, a, W, i0, i1, C);
  }
}

// The same sums for any width, scalar, with the same chunked order.
void project_any(const double* Q, Eigen::Index ldq, int j, const double* W, int b, Eigen::Index n, double* C) {
  std::fill(C, C + static_cast<std::ptrdiff_t>(j) * b, 0.0);
  std::vector<double> partial(static_cast<std::size_t>(b));
  for (Eigen::Index i0 = 0; i0 < n; i0 += kChunkRows) {
    const Eigen::Index i1 = std::min(n, i0 + kChunkRows);
    for (int a = 0; a < j; ++a) {
      std::fill(partial.begin(), partial.end(), 0.0);
      for (Eigen::Index i = i0; i < i1; ++i) {
        const double s = Q[i * ldq + a];
        const double* w = W + i * b;
        for (int k = 0; k < b; ++k) partial[k] += s * w[k];
      }
      double* c = C + static_cast<std::ptrdiff_t>(a) * b;
      for (int k = 0; k < b; ++k) c[k] += partial[k];
    }
  }
}

// X(i, 0:kWidth) = init(i) + sign * sum_a Q(i, a) Z(a, 0:kWidth), two rows at a time, the sum
// over a in increasing order. `init` null means zero. Z has row stride ldz.
template <int kWidth, bool kSubtract>
void combine_even(const double* Q, Eigen::Index ldq, int j, const double* Z, Eigen::Index ldz, Eigen::Index n,
                  double* X, Eigen::Index ldx) {
  constexpr int H = kWidth / 2;
  Eigen::Index i = 0;
  for (; i + 1 < n; i += 2) {
    const double* q0 = Q + i * ldq;
    const double* q1 = q0 + ldq;
    double* x0 = X + i * ldx;
    double* x1 = x0 + ldx;
    __m128d acc0[H], acc1[H];
    for (int h = 0; h < H; ++h) {
      acc0[h] = kSubtract ? _mm_loadu_pd(x0 + 2 * h) : _mm_setzero_pd();
      acc1[h] = kSubtract ? _mm_loadu_pd(x1 + 2 * h) : _mm_setzero_pd();
    }
    for (int a = 0; a < j; ++a) {
      const double* z = Z + a * ldz;
      const __m128d s0 = _mm_set1_pd(q0[a]), s1 = _mm_set1_pd(q1[a]);
      for (int h = 0; h < H; ++h) {
        const __m128d zv = _mm_loadu_pd(z + 2 * h);
        if (kSubtract) {
          acc0[h] = _mm_sub_pd(acc0[h], _mm_mul_pd(s0, zv));
          acc1[h] = _mm_sub_pd(acc1[h], _mm_mul_pd(s1, zv));
        } else {
          acc0[h] = _mm_add_pd(acc0[h], _mm_mul_pd(s0, zv));
          acc1[h] = _mm_add_pd(acc1[h], _mm_mul_pd(s1, zv));
        }
      }
    }
    for (int h = 0; h < H; ++h) {
      _mm_storeu_pd(x0 + 2 * h, acc0[h]);
      _mm_storeu_pd(x1 + 2 * h, acc1[h]);
    }
  }
  for (; i < n; ++i) {
    const double* q0 = Q + i * ldq;
    double* x0 = X + i * ldx;
    __m128d acc0[H];
    for (int h = 0; h < H; ++h) acc0[h] = kSubtract ? _mm_loadu_pd(x0 + 2 * h) : _mm_setzero_pd();
    for (int a = 0; a < j; ++a) {
      const double* z = Z + a * ldz;
      const __m128d s0 = _mm_set1_pd(q0[a]);
      for (int h = 0; h < H; ++h) {
        const __m128d p = _mm_mul_pd(s0, _mm_loadu_pd(z + 2 * h));
        acc0[h] = kSubtract ? _mm_sub_pd(acc0[h], p) : _mm_add_pd(acc0[h], p);
      }
    }
    for (int h = 0; h < H; ++h) _mm_storeu_pd(x0 + 2 * h, acc0[h]);
  }
}

// Scalar version of combine_even for one column at a time (odd widths, tails).
template <bool kSubtract>
void combine_one(const double* Q, Eigen::Index ldq, int j, const double* Z, Eigen::Index ldz, Eigen::Index n,
                 double* X, Eigen::Index ldx) {
  for (Eigen::Index i = 0; i < n; ++i) {
    const double* q = Q + i * ldq;
    double acc = kSubtract ? X[i * ldx] : 0.0;
    for (int a = 0; a < j; ++a) {
      if (kSubtract) acc -= q[a] * Z[a * ldz];
      else acc += q[a] * Z[a * ldz];
    }
    X[i * ldx] = acc;
  }
}

// Any width: columns in groups of 8, 4, 2, 1 (each output column's sum order is the same
// whichever group it falls in).
template <bool kSubtract>
void combine_any(const double* Q, Eigen::Index ldq, int j, const double* Z, Eigen::Index ldz, int p, Eigen::Index n,
                 double* X, Eigen::Index ldx) {
  int c = 0;
  for (; c + 8 <= p; c += 8) combine_even<8, kSubtract>(Q, ldq, j, Z + c, ldz, n, X + c, ldx);
  for (; c + 4 <= p; c += 4) combine_even<4, kSubtract>(Q, ldq, j, Z + c, ldz, n, X + c, ldx);
  for (; c + 2 <= p; c += 2) combine_even<2, kSubtract>(Q, ldq, j, Z + c, ldz, n, X + c, ldx);
  for (; c < p; ++c) combine_one<kSubtract>(Q, ldq, j, Z + c, ldz, n, X + c, ldx);
}

}  // namespace

namespace {

// Serial bodies: project onto columns [0, j) of the given Q pointer; subtract and combine on
// rows [0, n) of the given pointers.
void project_serial(const double* Q, Eigen::Index ldq, int j, const double* W, int b, Eigen::Index n, double* C) {
  switch (b) {
    case 2: project_even<2>(Q, ldq, j, W, n, C); break;
    case 4: project_even<4>(Q, ldq, j, W, n, C); break;
    case 6: project_even<6>(Q, ldq, j, W, n, C); break;
    case 8: project_even<8>(Q, ldq, j, W, n, C); break;
    case 10: project_even<10>(Q, ldq, j, W, n, C); break;
    case 12: project_even<12>(Q, ldq, j, W, n, C); break;
    default: project_any(Q, ldq, j, W, b, n, C);
  }
}

void subtract_serial(const double* Q, Eigen::Index ldq, int j, const double* C, int b, Eigen::Index n, double* W) {
  switch (b) {
    case 4: combine_even<4, true>(Q, ldq, j, C, b, n, W, b); break;
    case 6: combine_even<6, true>(Q, ldq, j, C, b, n, W, b); break;
    case 8: combine_even<8, true>(Q, ldq, j, C, b, n, W, b); break;
    default: combine_any<true>(Q, ldq, j, C, b, b, n, W, b);
  }
}

// By chunks of rows, so the chunk of Q stays in cache while each group of output columns
// (combine_any) passes over it; through a buffer, so X may be Q itself.
constexpr Eigen::Index kCombineRows = 64;

void combine_serial(const double* Q, Eigen::Index ldq, int j, const double* Z, int p, Eigen::Index n, double* X,
                    Eigen::Index ldx) {
  std::vector<double> buffer(static_cast<std::size_t>(kCombineRows * p));
  for (Eigen::Index i0 = 0; i0 < n; i0 += kCombineRows) {
    const Eigen::Index rows = std::min(kCombineRows, n - i0);
    combine_any<false>(Q + i0 * ldq, ldq, j, Z, p, p, rows, buffer.data(), p);
    for (Eigen::Index i = 0; i < rows; ++i)
      std::copy(buffer.data() + i * p, buffer.data() + (i + 1) * p, X + (i0 + i) * ldx);
  }
}

}  // namespace

void project_onto_columns(const double* Q, Eigen::Index ldq, int j, const double* W, int b, Eigen::Index n,
                          double* C, WorkerPool* pool) {
  if (!pool || pool->size() == 1 || j < 2 * pool->size()) {
    project_serial(Q, ldq, j, W, b, n, C);
    return;
  }
  // Each part computes the rows of C for its own range of Q's columns.
  pool->run([&](int part) {
    const int a0 = static_cast<int>(split_point(j, pool->size(), part, 4));
    const int a1 = static_cast<int>(split_point(j, pool->size(), part + 1, 4));
    if (a1 > a0) project_serial(Q + a0, ldq, a1 - a0, W, b, n, C + static_cast<std::ptrdiff_t>(a0) * b);
  });
}

void subtract_combination(const double* Q, Eigen::Index ldq, int j, const double* C, int b, Eigen::Index n,
                          double* W, WorkerPool* pool) {
  if (!pool || pool->size() == 1 || n < 1024) {
    subtract_serial(Q, ldq, j, C, b, n, W);
    return;
  }
  pool->run([&](int part) {
    const Eigen::Index i0 = split_point(n, pool->size(), part, 2);
    const Eigen::Index i1 = split_point(n, pool->size(), part + 1, 2);
    if (i1 > i0) subtract_serial(Q + i0 * ldq, ldq, j, C, b, i1 - i0, W + i0 * b);
  });
}

void combine_columns(const double* Q, Eigen::Index ldq, int j, const double* Z, int p, Eigen::Index n, double* X,
                     Eigen::Index ldx, WorkerPool* pool) {
  if (!pool || pool->size() == 1 || n < 1024) {
    combine_serial(Q, ldq, j, Z, p, n, X, ldx);
    return;
  }
  pool->run([&](int part) {
    const Eigen::Index i0 = split_point(n, pool->size(), part, kCombineRows);
    const Eigen::Index i1 = split_point(n, pool->size(), part + 1, kCombineRows);
    if (i1 > i0) combine_serial(Q + i0 * ldq, ldq, j, Z, p, i1 - i0, X + i0 * ldx, ldx);
  });
}

}  // namespace offsetopt
