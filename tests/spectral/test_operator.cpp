// The building blocks of the solver: the nested-dissection ordering, the shift-invert operator
// (block triangular solves) and the row-block kernels, each against a plain dense computation.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>

#include "spectral/cotan_laplacian.h"
#include "spectral/mass_matrix.h"
#include "spectral/nested_dissection.h"
#include "spectral/row_block_kernels.h"
#include "spectral/shift_invert_operator.h"
#include "spectral/worker_pool.h"
#include "test_meshes.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

RowMatrix random_block(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  Rng rng(seed);
  RowMatrix X(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index j = 0; j < cols; ++j) X(i, j) = rng.uniform(-1.0, 1.0);
  return X;
}

long factor_nonzeros(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order) {
  const int n = static_cast<int>(A.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
  for (int i = 0; i < n; ++i) P.indices()[order[i]] = i;
  Eigen::SparseMatrix<double> permuted;
  permuted = A.twistedBy(P);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(permuted);
  return static_cast<long>(ldlt.matrixL().nestedExpression().nonZeros());
}

}  // namespace

TEST_CASE("nested dissection returns a permutation that beats the natural order and is near AMD") {
  const Mesh mesh = test::bumpy_icosphere(5);  // 10242 vertices
  Eigen::SparseMatrix<double> A = cotan_laplacian(mesh.V, mesh.F);
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1.0;
  const std::vector<int> order = nested_dissection(A, mesh.V);
  REQUIRE(order.size() == static_cast<std::size_t>(A.rows()));
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == static_cast<int>(i));
  std::vector<int> natural(order.size());
  for (std::size_t i = 0; i < natural.size(); ++i) natural[i] = static_cast<int>(i);
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  amd(A, inverse);
  const std::vector<int> amd_order(inverse.indices().data(), inverse.indices().data() + A.rows());
  const long nd = factor_nonzeros(A, order);
  CHECK(nd < factor_nonzeros(A, natural) / 2);
  CHECK(nd < 1.1 * static_cast<double>(factor_nonzeros(A, amd_order)));
  // Deterministic.
  CHECK(nested_dissection(A, mesh.V) == order);
}

TEST_CASE("shift-invert operator equals D (L + sM)^-1 D on blocks of any width") {
  const Mesh mesh = test::bumpy_icosphere(2);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
  const Eigen::VectorXd mass = lumped_mass(mesh.V, mesh.F);
  const Eigen::Index n = L.rows();
  const double shift = 0.3;
  for (bool generalised : {false, true}) {
    for (bool geometric : {false, true}) {
      CAPTURE(generalised);
      CAPTURE(geometric);
      const Eigen::VectorXd m = generalised ? mass : Eigen::VectorXd();
      const ShiftInvertOperator op(L, m, shift, geometric ? &mesh.V : nullptr);
      REQUIRE(op.status() == ShiftInvertOperator::Status::Ok);
      const Eigen::VectorXd d = generalised ? Eigen::VectorXd(mass.cwiseSqrt()) : Eigen::VectorXd::Ones(n);
      const Eigen::MatrixXd K = Eigen::MatrixXd(L) + shift * Eigen::MatrixXd(d.cwiseProduct(d).asDiagonal());
      const Eigen::MatrixXd dense = d.asDiagonal() * K.inverse() * d.asDiagonal();
      WorkerPool pool(3);
      for (int b : {1, 2, 3, 5, 6, 7, 8, 13, 70}) {
        CAPTURE(b);
        // Read the block out of a wider matrix, as the solver does (row stride > b).
        const RowMatrix wide = random_block(n, b + 3, 11 + b);
        RowMatrix out;
        op.apply(wide.data() + 1, wide.cols(), b, out);
        const Eigen::MatrixXd expected = dense * Eigen::MatrixXd(wide.middleCols(1, b));
        CHECK((Eigen::MatrixXd(out) - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
        // Split among threads (columns in groups of other widths): the same bits.
        RowMatrix threaded;
        op.apply(wide.data() + 1, wide.cols(), b, threaded, &pool);
        CHECK((threaded.array() == out.array()).all());
      }
    }
  }
  // Not positive definite (a negative shift far below -λ_max): reported, not thrown.
  const ShiftInvertOperator bad(L, Eigen::VectorXd(), -1e6, &mesh.V);
  CHECK(bad.status() == ShiftInvertOperator::Status::NotPositiveDefinite);
}

TEST_CASE("row-block kernels match dense products for every width") {
  const Eigen::Index n = 301;  // odd: exercises the row tails
  const RowMatrix Q = random_block(n, 40, 1);
  for (int b : {1, 2, 3, 4, 5, 6, 7, 8, 10, 12, 13, 17}) {
    CAPTURE(b);
    for (int j : {1, 7, 32}) {
      CAPTURE(j);
      const RowMatrix W = random_block(n, b, 100 + b);
      const Eigen::MatrixXd Qj = Eigen::MatrixXd(Q).leftCols(j);
      RowMatrix C(j, b);
      project_onto_columns(Q.data(), Q.cols(), j, W.data(), b, n, C.data());
      const Eigen::MatrixXd expected = Qj.transpose() * Eigen::MatrixXd(W);
      CHECK((Eigen::MatrixXd(C) - expected).cwiseAbs().maxCoeff() <= 1e-12 * n);
      RowMatrix V = W;
      subtract_combination(Q.data(), Q.cols(), j, C.data(), b, n, V.data());
      const Eigen::MatrixXd subtracted = Eigen::MatrixXd(W) - Qj * Eigen::MatrixXd(C);
      CHECK((Eigen::MatrixXd(V) - subtracted).cwiseAbs().maxCoeff() <= 1e-11 * n);
      RowMatrix X(n, b);
      combine_columns(Q.data(), Q.cols(), j, C.data(), b, n, X.data(), b);
      CHECK((Eigen::MatrixXd(X) - Qj * Eigen::MatrixXd(C)).cwiseAbs().maxCoeff() <= 1e-11 * n);
    }
  }
  // With a pool (large enough to be split): the same bits as without.
  WorkerPool pool(2);
  const Eigen::Index rows = 5000;
  const RowMatrix big = random_block(rows, 40, 3);
  for (int b : {3, 6, 8}) {
    CAPTURE(b);
    const RowMatrix W = random_block(rows, b, 7);
    RowMatrix C1(33, b), C2(33, b);
    project_onto_columns(big.data(), big.cols(), 33, W.data(), b, rows, C1.data());
    project_onto_columns(big.data(), big.cols(), 33, W.data(), b, rows, C2.data(), &pool);
    CHECK((C1.array() == C2.array()).all());
    RowMatrix V1 = W, V2 = W;
    subtract_combination(big.data(), big.cols(), 33, C1.data(), b, rows, V1.data());
    subtract_combination(big.data(), big.cols(), 33, C1.data(), b, rows, V2.data(), &pool);
    CHECK((V1.array() == V2.array()).all());
    RowMatrix X1(rows, b), X2(rows, b);
    combine_columns(big.data(), big.cols(), 33, C1.data(), b, rows, X1.data(), b);
    combine_columns(big.data(), big.cols(), 33, C1.data(), b, rows, X2.data(), b, &pool);
    CHECK((X1.array() == X2.array()).all());
  }
  // In place: the first p columns of Q replaced by Q(:, 0:j) Z.
  RowMatrix P = Q;
  const RowMatrix Z = random_block(20, 9, 5);
  combine_columns(P.data(), P.cols(), 20, Z.data(), 9, n, P.data(), P.cols());
  const Eigen::MatrixXd expected = Eigen::MatrixXd(Q).leftCols(20) * Eigen::MatrixXd(Z);
  CHECK((Eigen::MatrixXd(P).leftCols(9) - expected).cwiseAbs().maxCoeff() <= 1e-11 * n);
  CHECK((P.rightCols(31).array() == Q.rightCols(31).array()).all());
}
