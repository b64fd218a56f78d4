// The multifrontal supernodal Cholesky solver against dense LLT on matrices with the
// contraction's pattern (L^T L + D on meshes) and on random sparse SPD matrices; refactorisation
// on the same pattern; failure on indefinite input.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>

#include "geometry/cotan_laplacian.h"
#include "mesh/primitives.h"
#include "sparse/fill_reducing_ordering.h"
#include "sparse/supernodal_cholesky.h"
#include "util/rng.h"

using namespace offsetopt;
using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

// P A Pᵀ: row/column new_to_old[k] of A becomes row/column k.
SparseMatrix permuted(const SparseMatrix& A, const std::vector<int>& new_to_old) {
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> to_new(A.rows());
  for (Eigen::Index k = 0; k < A.rows(); ++k) to_new.indices()[new_to_old[static_cast<std::size_t>(k)]] = static_cast<int>(k);
  SparseMatrix P;
  P = A.selfadjointView<Eigen::Lower>().twistedBy(to_new);
  return P;
}

double relative_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() / b.norm(); }

SparseMatrix random_spd(int n, int per_column, Rng& rng) {
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j)
    for (int e = 0; e < per_column; ++e) {
      const int i = static_cast<int>(rng.below(static_cast<std::uint64_t>(n)));
      if (i == j) continue;
      const double v = rng.uniform(-1, 1);
      t.emplace_back(i, j, v);
      t.emplace_back(j, i, v);
    }
  SparseMatrix A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  // Diagonal dominance makes it SPD.
  for (int j = 0; j < n; ++j) t.emplace_back(j, j, 1.0 + A.col(j).cwiseAbs().sum());
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("solves L^T L + D systems of mesh Laplacians like a dense Cholesky, over refactorisations") {
  Mesh m = make_torus(1.0, 0.4, 24, 10);
  Rng rng(3);
  SupernodalCholesky solver;
  for (int step = 0; step < 3; ++step) {
    for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V.row(i) *= 1.0 + 0.05 * rng.uniform(-1, 1);
    const SparseMatrix L = cotan_laplacian(m.V, m.F);
    SparseMatrix A = L * L;
    A *= 50.0 * (step + 1);
    Eigen::VectorXd d(m.V.rows());
    for (Eigen::Index i = 0; i < d.size(); ++i) d[i] = rng.uniform(0.5, 2.0);
    A.diagonal() += d;
    if (step == 0) solver.analyze(A);
    REQUIRE(solver.factorize(A));
    Eigen::MatrixXd B = Eigen::MatrixXd::Random(m.V.rows(), 3);
    const Eigen::MatrixXd expected = Eigen::MatrixXd(A).llt().solve(B);
    solver.solve_in_place(B);
    CHECK(relative_error(B, expected) < 1e-10);
  }
  CHECK(solver.stored_nonzeros() >= 0.5 * m.V.rows());
}

TEST_CASE("random sparse SPD matrices in natural and fill-reducing order") {
  Rng rng(8);
  for (int trial = 0; trial < 6; ++trial) {
    const int n = 50 + 70 * trial;
    const SparseMatrix A = random_spd(n, 1 + trial % 4, rng);
    SupernodalCholesky solver;
    solver.analyze(A);
    REQUIRE(solver.factorize(A));
    Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 2);
    const Eigen::MatrixXd expected = Eigen::MatrixXd(A).llt().solve(B);
    solver.solve_in_place(B);
    CHECK(relative_error(B, expected) < 1e-11);
    CHECK(solver.supernode_count() >= 1);
    CHECK(solver.supernode_count() <= n);
  }
}

TEST_CASE("a large mesh system: the factor matches the predicted fill and solves to round-off") {
  const Mesh m = make_icosphere(1.0, 4);
  const SparseMatrix L = cotan_laplacian(m.V, m.F);
  SparseMatrix A = L * L;
  A.diagonal().array() += 1.0;
  const FillReducingOrdering ordering = fill_reducing_ordering(A, m.V, L, 2);
  const SparseMatrix P = permuted(A, ordering.new_to_old);
  SupernodalCholesky solver;
  solver.analyze(P);
  REQUIRE(solver.factorize(P));
  // Relaxed supernodes store at least the true fill, and not much more.
  CHECK(solver.stored_nonzeros() >= ordering.counts.nonzeros);
  CHECK(solver.stored_nonzeros() <= 1.3 * ordering.counts.nonzeros);
  Eigen::MatrixXd X = Eigen::MatrixXd::Random(A.rows(), 3);
  const Eigen::MatrixXd B = P * X;
  Eigen::MatrixXd solved = B;
  solver.solve_in_place(solved);
  CHECK(relative_error(solved, X) < 1e-8);
}

TEST_CASE("one, two and three threads give bit-identical solutions") {
  const Mesh m = make_icosphere(1.0, 5);  // large enough for the subtrees to be split
  const SparseMatrix L = cotan_laplacian(m.V, m.F);
  SparseMatrix A = L * L;
  A *= 30.0;
  A.diagonal().array() += 1.0;
  const FillReducingOrdering ordering = fill_reducing_ordering(A, m.V, L, 2);
  const SparseMatrix P = permuted(A, ordering.new_to_old);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(P.rows(), 3);
  Eigen::MatrixXd solutions[3];
  for (int threads = 1; threads <= 3; ++threads) {
    SupernodalCholesky solver;
    solver.set_thread_count(threads);
    solver.analyze(P);
    REQUIRE(solver.factorize(P));
    solutions[threads - 1] = B;
    solver.solve_in_place(solutions[threads - 1]);
  }
  CHECK(solutions[0] == solutions[1]);
  CHECK(solutions[0] == solutions[2]);
  CHECK(relative_error(P * solutions[0], B) < 1e-9);
}

TEST_CASE("an indefinite matrix is reported, not factorised") {
  SparseMatrix A(3, 3);
  std::vector<Eigen::Triplet<double>> t = {{0, 0, 1.0}, {1, 1, -2.0}, {2, 2, 1.0}, {0, 1, 0.5}, {1, 0, 0.5}};
  A.setFromTriplets(t.begin(), t.end());
  SupernodalCholesky solver;
  solver.analyze(A);
  CHECK_FALSE(solver.factorize(A));
  Eigen::MatrixXd B = Eigen::MatrixXd::Ones(3, 1);
  CHECK_THROWS_AS(solver.solve_in_place(B), std::logic_error);
}

namespace {

// Dense copy of order-permuted L D Lᵀ from a BlockLdlt, back in the caller's order.
Eigen::MatrixXd reassemble(const BlockLdlt& f, Eigen::Index n) {
  Eigen::MatrixXd unit = Eigen::MatrixXd::Identity(n, n);  // factor order
  for (const BlockLdlt::Supernode& s : f.supernodes) {
    for (int i = 1; i < s.width; ++i)
      for (int j = 0; j < i; ++j) unit(s.first + i, s.first + j) = f.values[s.triangle + static_cast<std::size_t>(i * (i - 1) / 2 + j)];
    for (int r = 0; r < s.row_count; ++r)
      for (int j = 0; j < s.width; ++j)
        unit(f.rows[static_cast<std::size_t>(s.row_begin + r)], s.first + j) = f.values[s.below + static_cast<std::size_t>(r * s.width + j)];
  }
  const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(f.pivots.data(), n);
  const Eigen::MatrixXd product = unit * d.asDiagonal() * unit.transpose();
  Eigen::MatrixXd out(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) out(f.order[static_cast<std::size_t>(i)], f.order[static_cast<std::size_t>(j)]) = product(i, j);
  return out;
}

}  // namespace

TEST_CASE("block_ldlt: L D L^T equals the matrix, and D matches a dense LLT's squared diagonal") {
  Rng rng(21);
  std::vector<SparseMatrix> matrices;
  for (int trial = 0; trial < 3; ++trial) matrices.push_back(random_spd(80 + 60 * trial, 2 + trial, rng));
  const Mesh m = make_icosphere(1.0, 2);  // the eigensolver's kind of matrix: L + 0.3 I
  SparseMatrix K = cotan_laplacian(m.V, m.F);
  K.diagonal().array() += 0.3;
  matrices.push_back(K);
  for (std::size_t t = 0; t < matrices.size(); ++t) {
    CAPTURE(t);
    const SparseMatrix& A = matrices[t];
    const Eigen::Index n = A.rows();
    SupernodalCholesky solver;
    solver.analyze(A);
    REQUIRE(solver.factorize(A));
    const Eigen::MatrixXd dense(A);
    for (int width : {1, 3, 96}) {  // runs cut from the supernodes, or whole
      CAPTURE(width);
      const BlockLdlt f = solver.block_ldlt(width);
      REQUIRE(f.order.size() == static_cast<std::size_t>(n));
      for (const BlockLdlt::Supernode& s : f.supernodes) CHECK(s.width <= width);
      CHECK((reassemble(f, n) - dense).cwiseAbs().maxCoeff() <= 1e-12 * dense.cwiseAbs().maxCoeff());
      // Independent: the dense Cholesky of the matrix in the factor's order.
      Eigen::MatrixXd permuted(n, n);
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < n; ++j) permuted(i, j) = dense(f.order[static_cast<std::size_t>(i)], f.order[static_cast<std::size_t>(j)]);
      const Eigen::MatrixXd lower = permuted.llt().matrixL();
      for (Eigen::Index i = 0; i < n; ++i) CHECK(f.pivots[static_cast<std::size_t>(i)] == doctest::Approx(lower(i, i) * lower(i, i)).epsilon(1e-10));
    }
  }
}

TEST_CASE("fill_reducing_ordering: a permutation with less fill than the natural order, counted as Eigen factors it") {
  const Mesh m = make_icosphere(1.0, 4);
  const SparseMatrix L = cotan_laplacian(m.V, m.F);
  SparseMatrix shifted = L;
  shifted.diagonal().array() += 1.0;
  SparseMatrix normal = L * L;
  normal.diagonal().array() += 1.0;
  for (int hops : {1, 2}) {
    CAPTURE(hops);
    const SparseMatrix& A = hops == 1 ? shifted : normal;
    const FillReducingOrdering ordering = fill_reducing_ordering(A, m.V, L, hops);
    std::vector<int> sorted = ordering.new_to_old;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == static_cast<int>(i));
    std::vector<int> natural(sorted);
    const CholeskyCounts plain = cholesky_counts(A, natural);
    CHECK(ordering.counts.flops < 0.5 * plain.flops);
    CHECK(ordering.counts.nonzeros < plain.nonzeros);
    // The predicted fill is the true fill of the permuted matrix (Eigen's simplicial factor).
    const SparseMatrix P = permuted(A, ordering.new_to_old);
    Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> llt(P);
    REQUIRE(llt.info() == Eigen::Success);
    CHECK(static_cast<double>(llt.matrixL().nestedExpression().nonZeros()) == ordering.counts.nonzeros);
  }
}
