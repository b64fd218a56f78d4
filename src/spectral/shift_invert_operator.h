// The operator of shift-invert Lanczos for L φ = λ M φ with a diagonal M > 0 (M = I for the
// standard problem), in symmetric form:
//   Op = D (L + s M)⁻¹ D,   D = M^(1/2) (diagonal),
// whose eigenpairs are θ = 1/(λ + s), y = D φ. Op is symmetric positive definite when L is
// positive semi-definite and s > 0, so the largest θ are the smallest λ.
//
// L + sM is factorised once by Eigen's SimplicialLDLT after a fill-reducing permutation (nested
// dissection on the vertex positions when given, else Eigen's AMD). On large meshes the
// factorisation is split at the first dissection level (parts A, B and their separator S): Eigen
// factors K[A∪S] and K[B∪S], independently (two threads when available), whose trailing blocks
// are the Schur complements of A and of B; the separator's own Schur complement is their sum
// minus K_SS and is factored densely. That is the same LDLᵀ of K, at half the wall time on two
// cores, for the price of factoring the (small) separator three times. The factor is then copied
// into supernodes (runs of columns with nested patterns, stored as dense blocks sharing one row
// list; the separators of the dissection become large ones) and Eigen's copy is dropped. Applying
// Op to a block of b vectors runs the triangular solves on the whole block at once (row-major,
// one pass over the factor for all b vectors), which is what makes a block Lanczos cheaper per
// vector than a single-vector one.
#pragma once
#include <Eigen/Sparse>
#include <vector>

#include "mesh/mesh.h"
#include "util/parallel.h"

namespace offsetopt {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class ShiftInvertOperator {
 public:
  enum class Status { Ok, NotPositiveDefinite };

  // `L` is #V by #V symmetric (both triangles stored); `mass` is the diagonal of M (#V, all > 0)
  // or empty for M = I; `shift` > 0; `positions` (#V by 3) selects nested dissection, nullptr AMD.
  // With a pool, the two halves of the first dissection level are factorised in parallel (the
  // factor is the same for any number of threads).
  ShiftInvertOperator(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, double shift,
                      const Vertices* positions, WorkerPool* pool = nullptr);

  Status status() const { return status_; }
  Eigen::Index size() const { return n_; }
  // Nonzeros of the unit lower factor (without its diagonal).
  Eigen::Index factor_nonzeros() const { return factor_nonzeros_; }

  // out = Op * in for the first `b` columns: `in` is row-major with row stride `in_stride`,
  // `out` is row-major n by b (resized). Deterministic: fixed order of every sum; with a pool the
  // columns are split among its threads, each solved exactly as without it.
  void apply(const double* in, Eigen::Index in_stride, int b, RowMatrix& out, WorkerPool* pool = nullptr) const;

 private:
  // A run of factor columns [first, first + width) with nested patterns: a dense unit lower
  // triangle on those rows and a dense block on the rows below them that all its columns share.
  struct Supernode {
    int first = 0, width = 0;
    int row_begin = 0, row_count = 0;  // in rows_
    std::size_t triangle = 0, below = 0;  // offsets in values_: packed strictly lower triangle
                                          // (row ii holds ii entries), then row_count x width
  };

  Eigen::Index n_ = 0;
  Eigen::Index factor_nonzeros_ = 0;
  Status status_ = Status::Ok;
  std::vector<int> order_;     // order_[new] = old
  std::vector<double> scale_;  // D in the new order
  std::vector<double> pivot_;  // D_ii of the LDLᵀ, new order
  std::vector<Supernode> supernodes_;
  std::vector<int> rows_;
  std::vector<double> values_;
  void add_supernodes(const int* start, const int* index, const double* value, int columns, int column_offset,
                      const std::vector<int>& row_map);
  void solve_columns_into(const double* in, Eigen::Index in_stride, int w, double* out, Eigen::Index out_stride,
                          RowMatrix& work) const;
  mutable std::vector<RowMatrix> work_;  // one buffer per part
};

}  // namespace offsetopt
