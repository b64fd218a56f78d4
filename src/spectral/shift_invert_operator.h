// The operator of shift-invert Lanczos for L φ = λ M φ with a diagonal M > 0 (M = I for the
// standard problem), in symmetric form:
//   Op = D (L + s M)⁻¹ D,   D = M^(1/2) (diagonal),
// whose eigenpairs are θ = 1/(λ + s), y = D φ. Op is symmetric positive definite when L is
// positive semi-definite and s > 0, so the largest θ are the smallest λ.
//
// L + sM is factorised once by Eigen's SimplicialLDLT after a fill-reducing permutation (nested
// dissection on the vertex positions when given, else Eigen's AMD). Applying Op to a block of b
// vectors runs the triangular solves on the whole block at once (row-major, one pass over the
// factor for all b vectors), which is what makes a block Lanczos cheaper per vector than a
// single-vector one.
#pragma once
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class ShiftInvertOperator {
 public:
  enum class Status { Ok, NotPositiveDefinite };

  // `L` is #V by #V symmetric (both triangles stored); `mass` is the diagonal of M (#V, all > 0)
  // or empty for M = I; `shift` > 0; `positions` (#V by 3) selects nested dissection, nullptr AMD.
  ShiftInvertOperator(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& mass, double shift,
                      const Vertices* positions);

  Status status() const { return status_; }
  Eigen::Index size() const { return n_; }
  // Nonzeros of the unit lower factor (without its diagonal).
  Eigen::Index factor_nonzeros() const { return static_cast<Eigen::Index>(row_values_.size()); }

  // out = Op * in for the first `b` columns: `in` is row-major with row stride `in_stride`,
  // `out` is row-major n by b (resized). Deterministic: fixed order of every sum.
  void apply(const double* in, Eigen::Index in_stride, int b, RowMatrix& out) const;

 private:
  Eigen::Index n_ = 0;
  Status status_ = Status::Ok;
  std::vector<int> order_;           // order_[new] = old
  std::vector<double> scale_;        // D in the new order
  std::vector<double> pivot_;        // D_ii of the LDLᵀ, new order
  // The factor of the permuted L + sM; its unit lower triangle is stored by columns, strictly
  // lower part (Eigen's SimplicialLDLT layout), which the backward solve reads as rows of Lᵀ.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> factor_;
  // The same triangle stored by rows, so the forward solve also gathers (accumulates in
  // registers) instead of scattering.
  std::vector<int> row_start_, row_columns_;
  std::vector<double> row_values_;
  mutable RowMatrix work_;
};

}  // namespace offsetopt
