// The building blocks of the solver: the shift-invert operator (block triangular solves) and the
// panel kernels, each against a plain dense computation (the ordering's tests: tests/sparse).
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>

#include "../test_meshes.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/lumped_mass.h"
#include "spectral/panel_matrix.h"
#include "spectral/shift_invert_operator.h"
#include "util/parallel.h"
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

}  // namespace

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
      REQUIRE(op.status() == ShiftInvertOperator::Status::ok);
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
  CHECK(bad.status() == ShiftInvertOperator::Status::not_positive_definite);
}

TEST_CASE("panel kernels match dense products, with and without threads") {
  WorkerPool pool(3);
  for (Eigen::Index n : {Eigen::Index(301), Eigen::Index(2000)}) {  // 301: a partial last panel
    CAPTURE(n);
    const RowMatrix Qrows = random_block(n, 40, 1);
    PanelMatrix Q(n, 40);
    Q.set_columns(0, 40, Qrows.data(), 40);
    RowMatrix back(n, 40);
    Q.get_columns(0, 40, back.data(), 40);
    REQUIRE((back.array() == Qrows.array()).all());
    for (int b : {1, 2, 3, 5, 6, 7, 8, 13}) {
      CAPTURE(b);
      const RowMatrix Wrows = random_block(n, b, 100 + b);
      PanelMatrix W(n, b);
      W.set_columns(0, b, Wrows.data(), b);
      for (int j : {1, 7, 32}) {
        CAPTURE(j);
        const int a0 = 3;  // a column range not starting at 0
        const Eigen::MatrixXd Qj = Eigen::MatrixXd(Qrows).middleCols(a0, j);
        RowMatrix C(j, b), Cp(j, b);
        panel_project(Q, a0, j, W, 0, b, C.data());
        panel_project(Q, a0, j, W, 0, b, Cp.data(), &pool);
        const Eigen::MatrixXd expected = Qj.transpose() * Eigen::MatrixXd(Wrows);
        CHECK((Eigen::MatrixXd(C) - expected).cwiseAbs().maxCoeff() <= 1e-12 * n);
        CHECK((C.array() == Cp.array()).all());
        PanelMatrix V = W, Vp = W;
        panel_subtract(Q, a0, j, C.data(), V, 0, b);
        panel_subtract(Q, a0, j, C.data(), Vp, 0, b, &pool);
        RowMatrix Vrows(n, b), Vprows(n, b);
        V.get_columns(0, b, Vrows.data(), b);
        Vp.get_columns(0, b, Vprows.data(), b);
        CHECK((Eigen::MatrixXd(Vrows) - (Eigen::MatrixXd(Wrows) - Qj * Eigen::MatrixXd(C))).cwiseAbs().maxCoeff() <= 1e-11 * n);
        CHECK((Vrows.array() == Vprows.array()).all());
        PanelMatrix X(n, b + 2), Xp(n, b + 2);
        panel_combine(Q, a0, j, C.data(), b, X, 1);
        panel_combine(Q, a0, j, C.data(), b, Xp, 1, &pool);
        RowMatrix Xrows(n, b), Xprows(n, b);
        X.get_columns(1, b, Xrows.data(), b);
        Xp.get_columns(1, b, Xprows.data(), b);
        CHECK((Eigen::MatrixXd(Xrows) - Qj * Eigen::MatrixXd(C)).cwiseAbs().maxCoeff() <= 1e-11 * n);
        CHECK((Xrows.array() == Xprows.array()).all());
      }
    }
    // In place: the first columns of Q replaced by Q(:, 0:20) Z; the others untouched.
    PanelMatrix P = Q;
    const RowMatrix Z = random_block(20, 9, 5);
    panel_combine(P, 0, 20, Z.data(), 9, P, 0, &pool);
    RowMatrix Prows(n, 40);
    P.get_columns(0, 40, Prows.data(), 40);
    const Eigen::MatrixXd expected = Eigen::MatrixXd(Qrows).leftCols(20) * Eigen::MatrixXd(Z);
    CHECK((Eigen::MatrixXd(Prows).leftCols(9) - expected).cwiseAbs().maxCoeff() <= 1e-11 * n);
    CHECK((Prows.rightCols(31).array() == Qrows.rightCols(31).array()).all());
    // Norms, rows in order.
    const Eigen::VectorXd norms = panel_column_norms(Q, 2, 5);
    for (int c = 0; c < 5; ++c) CHECK(norms(c) == doctest::Approx(Eigen::MatrixXd(Qrows).col(2 + c).norm()).epsilon(1e-14));
  }
}

TEST_CASE("the factorisation on two threads gives the same operator, in either ordering") {
  // 40962 vertices: large enough for the factorisation's subtrees to run on two threads.
  const Mesh mesh = test::bumpy_icosphere(6);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
  const Eigen::VectorXd mass = lumped_mass(mesh.V, mesh.F);
  WorkerPool pool(2);
  const ShiftInvertOperator divided(L, mass, 0.3, &mesh.V, &pool);
  const ShiftInvertOperator serial(L, mass, 0.3, &mesh.V);
  const ShiftInvertOperator whole(L, mass, 0.3, nullptr);  // minimum degree only
  REQUIRE(divided.status() == ShiftInvertOperator::Status::ok);
  REQUIRE(whole.status() == ShiftInvertOperator::Status::ok);
  const RowMatrix X = random_block(L.rows(), 6, 9);
  RowMatrix a, b, c;
  divided.apply(X.data(), 6, 6, a, &pool);
  serial.apply(X.data(), 6, 6, b);
  whole.apply(X.data(), 6, 6, c);
  CHECK((a.array() == b.array()).all());  // threads change nothing
  CHECK((a - c).cwiseAbs().maxCoeff() <= 1e-11 * c.cwiseAbs().maxCoeff());
  // And it is the inverse: D⁻¹ (L + sM) D⁻¹ applied to Op X gives X back.
  const Eigen::VectorXd d = mass.cwiseSqrt();
  Eigen::SparseMatrix<double> K = L;
  for (Eigen::Index i = 0; i < K.rows(); ++i) K.coeffRef(i, i) += 0.3 * mass(i);
  const Eigen::MatrixXd back = d.cwiseInverse().asDiagonal() * (K * (d.cwiseInverse().asDiagonal() * Eigen::MatrixXd(a)));
  CHECK((back - Eigen::MatrixXd(X)).cwiseAbs().maxCoeff() <= 1e-9);
}
