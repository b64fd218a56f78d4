// The operator of shift-invert Lanczos for L φ = λ M φ with a diagonal M > 0 (M = I for the
// standard problem), in symmetric form:
//   Op = D (L + s M)⁻¹ D,   D = M^(1/2) (diagonal),
// whose eigenpairs are θ = 1/(λ + s), y = D φ. Op is symmetric positive definite when L is
// positive semi-definite and s > 0, so the largest θ are the smallest λ.
//
// L + sM is factorised once by the supernodal Cholesky of src/sparse after a fill-reducing
// permutation (sparse/fill_reducing_ordering.h: the cheaper of minimum degree and, when vertex
// positions are given, nested dissection), and the factor is taken as a unit-lower LDLᵀ in
// supernodes (runs of columns with nested patterns, stored as dense blocks sharing one row list,
// sparse/supernodal_cholesky.h: BlockLdlt). Applying Op to a block of b vectors runs the
// triangular solves on the whole block at once (row-major, one pass over the factor for all b
// vectors), which is what makes a block Lanczos cheaper per vector than a single-vector one.
#pragma once
#include <Eigen/Sparse>
#include <vector>

#include "mesh/mesh.h"
#include "sparse/supernodal_cholesky.h"
#include "util/parallel.h"

namespace offsetopt {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class ShiftInvertOperator {
 public:
  enum class Status { ok, not_positive_definite };

  // `L` is #V by #V symmetric (both triangles stored); `mass` is the diagonal of M (#V, all > 0)
  // or empty for M = I; `shift` > 0; `positions` (#V by 3) lets nested dissection compete with
  // minimum degree, nullptr minimum degree alone. With a pool of several threads, independent
  // subtrees of the factorisation run in parallel (the factor is the same for any count).
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
  Eigen::Index n_ = 0;
  Eigen::Index factor_nonzeros_ = 0;
  Status status_ = Status::ok;
  std::vector<int> order_;     // order_[factor column] = vertex
  std::vector<double> scale_;  // D in the factor's order
  BlockLdlt factor_;
  void solve_columns_into(const double* in, Eigen::Index in_stride, int w, double* out, Eigen::Index out_stride,
                          RowMatrix& work) const;
  mutable std::vector<RowMatrix> work_;  // one buffer per part
};

}  // namespace offsetopt
