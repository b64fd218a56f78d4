// Dense kernels of the block Lanczos on tall row-major blocks (n rows, a few dozen columns):
// projections and combinations of basis columns. Written out instead of calling Eigen's GEMM
// because GEMM's blocking depends on the cache sizes of the machine it runs on, which would change
// the order of the sums and so the last bits of the results; here every sum runs over rows in
// increasing order, on every machine.
//
// With a WorkerPool the work is split into disjoint outputs (rows of C, rows of W or X) and each
// output is computed exactly as without it: the results do not depend on the number of threads.
#pragma once
#include <Eigen/Core>

#include "spectral/worker_pool.h"

namespace offsetopt {

// C (j by b, row-major) = Q(:, 0:j)ᵀ W, with Q row-major (row stride ldq) and W row-major n by b.
void project_onto_columns(const double* Q, Eigen::Index ldq, int j, const double* W, int b, Eigen::Index n,
                          double* C, WorkerPool* pool = nullptr);

// W -= Q(:, 0:j) C, same layouts.
void subtract_combination(const double* Q, Eigen::Index ldq, int j, const double* C, int b, Eigen::Index n,
                          double* W, WorkerPool* pool = nullptr);

// X(:, 0:p) = Q(:, 0:j) Z with Z j by p row-major; X row-major with row stride ldx. X may be Q
// itself (the update is done row by row through a buffer).
void combine_columns(const double* Q, Eigen::Index ldq, int j, const double* Z, int p, Eigen::Index n, double* X,
                     Eigen::Index ldx, WorkerPool* pool = nullptr);

}  // namespace offsetopt
