#include "spectral/panel_matrix.h"

#include <emmintrin.h>  // SSE2: part of the x86-64 baseline, so no run-time dispatch

#include <algorithm>
#include <cmath>
#include <cstring>

namespace offsetopt {

constexpr Eigen::Index P = kPanelRows;
static_assert(kPanelRows % 4 == 0, "kernels step through a panel four rows at a time");

void PanelMatrix::resize(Eigen::Index rows, int cols) {
  rows_ = rows;
  cols_ = cols;
  panels_ = (rows + P - 1) / P;
  data_.assign(static_cast<std::size_t>(panels_ * cols_ * P), 0.0);
}

void PanelMatrix::resize_columns(int cols) {
  PanelMatrix grown(rows_, cols);
  const int keep = std::min(cols, cols_);
  for (Eigen::Index p = 0; p < panels_; ++p)
    if (keep > 0) std::memcpy(grown.column(p, 0), column(p, 0), sizeof(double) * static_cast<std::size_t>(keep * P));
  *this = std::move(grown);
}

void PanelMatrix::set_columns(int col, int width, const double* rows_major, Eigen::Index ld) {
  for (Eigen::Index p = 0; p < panels_; ++p) {
    const Eigen::Index count = std::min(P, rows_ - p * P);
    for (int c = 0; c < width; ++c) {
      double* dst = column(p, col + c);
      const double* src = rows_major + p * P * ld + c;
      for (Eigen::Index i = 0; i < count; ++i) dst[i] = src[i * ld];
    }
  }
}

void PanelMatrix::get_columns(int col, int width, double* rows_major, Eigen::Index ld) const {
  for (Eigen::Index p = 0; p < panels_; ++p) {
    const Eigen::Index count = std::min(P, rows_ - p * P);
    for (int c = 0; c < width; ++c) {
      const double* src = column(p, col + c);
      double* dst = rows_major + p * P * ld + c;
      for (Eigen::Index i = 0; i < count; ++i) dst[i * ld] = src[i];
    }
  }
}

void PanelMatrix::copy_columns(int col, const PanelMatrix& source, int from, int width) {
  for (Eigen::Index p = 0; p < panels_; ++p)
    std::memcpy(column(p, col), source.column(p, from), sizeof(double) * static_cast<std::size_t>(width * P));
}

namespace {

// Sum of one panel: partial[t][u] = sum over the panel's rows of A(:, a + t) B(:, b + u), even
// and odd rows in the two lanes, then lane 1 onto lane 0.
template <int kA, int kB>
void project_panel_tile(const PanelMatrix& A, int a, const PanelMatrix& B, int b, Eigen::Index p, double* C, int ldc) {
  __m128d acc[kA][kB];
  for (int t = 0; t < kA; ++t)
    for (int u = 0; u < kB; ++u) acc[t][u] = _mm_setzero_pd();
  const double* qa[kA];
  const double* wb[kB];
  for (int t = 0; t < kA; ++t) qa[t] = A.column(p, a + t);
  for (int u = 0; u < kB; ++u) wb[u] = B.column(p, b + u);
  for (Eigen::Index i = 0; i < P; i += 2) {
    __m128d q[kA];
    for (int t = 0; t < kA; ++t) q[t] = _mm_load_pd(qa[t] + i);
    for (int u = 0; u < kB; ++u) {
      const __m128d w = _mm_load_pd(wb[u] + i);
      for (int t = 0; t < kA; ++t) acc[t][u] = _mm_add_pd(acc[t][u], _mm_mul_pd(q[t], w));
    }
  }
  for (int t = 0; t < kA; ++t) {
    for (int u = 0; u < kB; ++u) {
      double lanes[2];
      _mm_storeu_pd(lanes, acc[t][u]);
      C[t * ldc + u] += lanes[0] + lanes[1];
    }
  }
}

template <int kB>
void project_columns(const PanelMatrix& A, int a0, int j, const PanelMatrix& B, int b, Eigen::Index p, double* C,
                     int ldc) {
  int a = 0;
  for (; a + 1 < j; a += 2) project_panel_tile<2, kB>(A, a0 + a, B, b, p, C + a * ldc, ldc);
  if (a < j) project_panel_tile<1, kB>(A, a0 + a, B, b, p, C + a * ldc, ldc);
}

void project_serial(const PanelMatrix& A, int a0, int j, const PanelMatrix& B, int b0, int b, double* C) {
  std::fill(C, C + static_cast<std::ptrdiff_t>(j) * b, 0.0);
  for (Eigen::Index p = 0; p < A.panels(); ++p) {
    // Columns of B in groups of at most 6 (2 x 6 accumulators fill the 16 SSE registers).
    for (int g = 0; g < b; g += 6) {
      double* Cg = C + g;
      switch (std::min(6, b - g)) {
        case 1: project_columns<1>(A, a0, j, B, b0 + g, p, Cg, b); break;
        case 2: project_columns<2>(A, a0, j, B, b0 + g, p, Cg, b); break;
        case 3: project_columns<3>(A, a0, j, B, b0 + g, p, Cg, b); break;
        case 4: project_columns<4>(A, a0, j, B, b0 + g, p, Cg, b); break;
        case 5: project_columns<5>(A, a0, j, B, b0 + g, p, Cg, b); break;
        default: project_columns<6>(A, a0, j, B, b0 + g, p, Cg, b);
      }
    }
  }
}

// X(:, x0 + u) (u < kB) = [X(:, x0 + u) if kSubtract] -/+ sum_a A(:, a0 + a) Z(a, u) on one
// panel, four rows at a time; the terms in increasing a. Zd holds Z duplicated into SSE pairs
// (row stride 2 * ldz).
template <int kB, bool kSubtract>
void combine_panel(const PanelMatrix& A, int a0, int j, const double* Zd, int ldz, Eigen::Index p, double* const* out) {
  for (Eigen::Index i = 0; i < P; i += 4) {
    __m128d acc[2][kB];
    for (int u = 0; u < kB; ++u) {
      acc[0][u] = kSubtract ? _mm_load_pd(out[u] + i) : _mm_setzero_pd();
      acc[1][u] = kSubtract ? _mm_load_pd(out[u] + i + 2) : _mm_setzero_pd();
    }
    for (int a = 0; a < j; ++a) {
      const double* q = A.column(p, a0 + a) + i;
      const __m128d x0 = _mm_load_pd(q), x1 = _mm_load_pd(q + 2);
      const double* z = Zd + 2 * a * ldz;
      for (int u = 0; u < kB; ++u) {
        const __m128d c = _mm_load_pd(z + 2 * u);
        if (kSubtract) {
          acc[0][u] = _mm_sub_pd(acc[0][u], _mm_mul_pd(x0, c));
          acc[1][u] = _mm_sub_pd(acc[1][u], _mm_mul_pd(x1, c));
        } else {
          acc[0][u] = _mm_add_pd(acc[0][u], _mm_mul_pd(x0, c));
          acc[1][u] = _mm_add_pd(acc[1][u], _mm_mul_pd(x1, c));
        }
      }
    }
    for (int u = 0; u < kB; ++u) {
      _mm_store_pd(out[u] + i, acc[0][u]);
      _mm_store_pd(out[u] + i + 2, acc[1][u]);
    }
  }
}

template <bool kSubtract>
void combine_group(const PanelMatrix& A, int a0, int j, const double* Zd, int ldz, int width, Eigen::Index p,
                   double* const* out) {
  switch (width) {
    case 1: combine_panel<1, kSubtract>(A, a0, j, Zd, ldz, p, out); break;
    case 2: combine_panel<2, kSubtract>(A, a0, j, Zd, ldz, p, out); break;
    case 3: combine_panel<3, kSubtract>(A, a0, j, Zd, ldz, p, out); break;
    case 4: combine_panel<4, kSubtract>(A, a0, j, Zd, ldz, p, out); break;
    case 5: combine_panel<5, kSubtract>(A, a0, j, Zd, ldz, p, out); break;
    default: combine_panel<6, kSubtract>(A, a0, j, Zd, ldz, p, out);
  }
}

using AlignedVector = std::vector<double, Eigen::aligned_allocator<double>>;

AlignedVector duplicated(const double* Z, int j, int p) {
  AlignedVector Zd(static_cast<std::size_t>(2 * j * p));
  for (int e = 0; e < j * p; ++e) Zd[2 * e] = Zd[2 * e + 1] = Z[e];
  return Zd;
}

// Fewer panels than this run on the calling thread: waking the pool costs more than it saves.
constexpr double kMinParallelPanels = 16;

template <class Body>
void for_panels(Eigen::Index panels, WorkerPool* pool, const Body& body) {
  if (execution_policy(pool, static_cast<double>(panels), kMinParallelPanels) == ExecutionPolicy::serial) {
    for (Eigen::Index p = 0; p < panels; ++p) body(p);
    return;
  }
  pool->run([&](int part) {
    for (Eigen::Index p = split_point(panels, pool->size(), part); p < split_point(panels, pool->size(), part + 1); ++p)
      body(p);
  });
}

}  // namespace

void panel_project(const PanelMatrix& A, int a0, int j, const PanelMatrix& B, int b0, int b, double* C,
                   WorkerPool* pool) {
  // At least four columns of A per thread.
  if (execution_policy(pool, j, 4.0 * (pool ? pool->size() : 1)) == ExecutionPolicy::serial) {
    project_serial(A, a0, j, B, b0, b, C);
    return;
  }
  // Each part computes the rows of C of its own range of A's columns.
  pool->run([&](int part) {
    const int lo = static_cast<int>(split_point(j, pool->size(), part, 2));
    const int hi = static_cast<int>(split_point(j, pool->size(), part + 1, 2));
    if (hi > lo) project_serial(A, a0 + lo, hi - lo, B, b0, b, C + static_cast<std::ptrdiff_t>(lo) * b);
  });
}

void panel_subtract(const PanelMatrix& A, int a0, int j, const double* C, PanelMatrix& B, int b0, int b,
                    WorkerPool* pool) {
  const AlignedVector Cd = duplicated(C, j, b);
  for_panels(A.panels(), pool, [&](Eigen::Index p) {
    for (int g = 0; g < b; g += 6) {
      const int width = std::min(6, b - g);
      double* out[6];
      for (int u = 0; u < width; ++u) out[u] = B.column(p, b0 + g + u);
      combine_group<true>(A, a0, j, Cd.data() + 2 * g, b, width, p, out);
    }
  });
}

void panel_combine(const PanelMatrix& A, int a0, int j, const double* Z, int p, PanelMatrix& X, int x0,
                   WorkerPool* pool) {
  const AlignedVector Zd = duplicated(Z, j, p);
  const bool in_place = &A == &X;
  const int parts = pool ? pool->size() : 1;
  std::vector<AlignedVector> buffers(static_cast<std::size_t>(parts));
  auto body = [&](Eigen::Index panel, AlignedVector& buffer) {
    if (in_place && buffer.size() < static_cast<std::size_t>(p * P)) buffer.resize(static_cast<std::size_t>(p * P));
    for (int g = 0; g < p; g += 6) {
      const int width = std::min(6, p - g);
      double* out[6];
      for (int u = 0; u < width; ++u) out[u] = in_place ? buffer.data() + (g + u) * P : X.column(panel, x0 + g + u);
      combine_group<false>(A, a0, j, Zd.data() + 2 * g, p, width, panel, out);
    }
    if (in_place)
      std::memcpy(X.column(panel, x0), buffer.data(), sizeof(double) * static_cast<std::size_t>(p * P));
  };
  if (execution_policy(pool, static_cast<double>(A.panels()), kMinParallelPanels) == ExecutionPolicy::serial) {
    for (Eigen::Index panel = 0; panel < A.panels(); ++panel) body(panel, buffers[0]);
    return;
  }
  pool->run([&](int part) {
    for (Eigen::Index panel = split_point(A.panels(), parts, part); panel < split_point(A.panels(), parts, part + 1);
         ++panel)
      body(panel, buffers[static_cast<std::size_t>(part)]);
  });
}

Eigen::VectorXd panel_column_norms(const PanelMatrix& A, int c0, int b) {
  Eigen::VectorXd norms(b);
  for (int c = 0; c < b; ++c) {
    double sum = 0.0;
    for (Eigen::Index p = 0; p < A.panels(); ++p) {
      const double* x = A.column(p, c0 + c);
      for (Eigen::Index i = 0; i < P; ++i) sum += x[i] * x[i];
    }
    norms(c) = std::sqrt(sum);
  }
  return norms;
}

}  // namespace offsetopt
