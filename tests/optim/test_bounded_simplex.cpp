// The bounded-variable simplex against independent answers: a brute-force enumeration of every
// vertex of small random boxed LPs (each vertex solved densely), the duality conditions on larger
// ones, degenerate and equality-constrained cases, and an infeasible case whose Farkas
// certificate is checked by its own inequality.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "optim/bounded_simplex.h"
#include "util/rng.h"

using namespace offsetopt;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

LinearProgram random_lp(Rng& rng, int m, int n, bool with_equalities) {
  LinearProgram lp;
  lp.A.resize(m, n);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) lp.A(i, j) = rng.uniform(-1.0, 1.0);
  lp.c.resize(n);
  lp.lower.resize(n);
  lp.upper.resize(n);
  VectorXd inside(n);
  for (int j = 0; j < n; ++j) {
    lp.c(j) = rng.uniform(-1.0, 1.0);
    lp.lower(j) = rng.uniform(-1.0, 0.0);
    lp.upper(j) = lp.lower(j) + rng.uniform(0.2, 2.0);
    inside(j) = rng.uniform(lp.lower(j), lp.upper(j));
  }
  // Right-hand sides around a point of the box: usually feasible, sometimes not.
  lp.b = lp.A * inside;
  for (int i = 0; i < m; ++i) {
    const int kind = static_cast<int>(rng.below(with_equalities ? 3 : 2));
    lp.sense.push_back(kind == 0 ? RowSense::less_equal : kind == 1 ? RowSense::greater_equal : RowSense::equal);
    if (kind == 0) lp.b(i) += rng.uniform(-0.5, 0.5);
    if (kind == 1) lp.b(i) -= rng.uniform(-0.5, 0.5);
  }
  return lp;
}

// Every vertex: n active constraints among the rows (as equalities) and the bounds, solved
// densely; the best feasible one, or -inf when none is feasible.
double brute_force_optimum(const LinearProgram& lp) {
  const int m = static_cast<int>(lp.A.rows()), n = static_cast<int>(lp.A.cols());
  const int total = m + 2 * n;
  double best = -kInf;
  std::vector<bool> mask(static_cast<std::size_t>(total), false);
  std::fill(mask.begin(), mask.begin() + n, true);
  do {
    MatrixXd M(n, n);
    VectorXd r(n);
    int k = 0;
    for (int c = 0; c < total; ++c) {
      if (!mask[static_cast<std::size_t>(c)]) continue;
      if (c < m) {
        M.row(k) = lp.A.row(c);
        r(k) = lp.b(c);
      } else {
        const int j = (c - m) / 2;
        M.row(k).setZero();
        M(k, j) = 1.0;
        r(k) = (c - m) % 2 == 0 ? lp.lower(j) : lp.upper(j);
      }
      ++k;
    }
    Eigen::FullPivLU<MatrixXd> lu(M);
    if (!lu.isInvertible()) continue;
    const VectorXd x = lu.solve(r);
    bool ok = true;
    for (int j = 0; j < n && ok; ++j) ok = x(j) >= lp.lower(j) - 1e-9 && x(j) <= lp.upper(j) + 1e-9;
    for (int i = 0; i < m && ok; ++i) {
      const double v = lp.A.row(i).dot(x) - lp.b(i);
      const RowSense s = lp.sense[static_cast<std::size_t>(i)];
      ok = s == RowSense::less_equal ? v <= 1e-9 : s == RowSense::greater_equal ? v >= -1e-9 : std::fabs(v) <= 1e-9;
    }
    if (ok) best = std::max(best, lp.c.dot(x));
  } while (std::prev_permutation(mask.begin(), mask.end()));
  return best;
}

// Primal feasibility, the dual signs, reduced-cost signs at the bounds and a zero duality gap:
// together they prove optimality without trusting the solver.
void check_optimality(const LinearProgram& lp, const LpResult& r, double tol) {
  const VectorXd row = lp.A * r.x;
  for (Eigen::Index i = 0; i < lp.A.rows(); ++i) {
    const RowSense s = lp.sense[static_cast<std::size_t>(i)];
    const double v = row(i) - lp.b(i);
    if (s == RowSense::less_equal) {
      CHECK(v <= tol);
      CHECK(r.y(i) >= -tol);
    } else if (s == RowSense::greater_equal) {
      CHECK(v >= -tol);
      CHECK(r.y(i) <= tol);
    } else {
      CHECK(std::fabs(v) <= tol);
    }
  }
  const VectorXd d = lp.c - lp.A.transpose() * r.y;
  double dual = lp.b.dot(r.y);
  for (Eigen::Index j = 0; j < lp.A.cols(); ++j) {
    CHECK(r.x(j) >= lp.lower(j) - tol);
    CHECK(r.x(j) <= lp.upper(j) + tol);
    if (d(j) > tol) CHECK(r.x(j) >= lp.upper(j) - tol);
    if (d(j) < -tol) CHECK(r.x(j) <= lp.lower(j) + tol);
    if (d(j) != 0.0) dual += d(j) > 0.0 ? d(j) * lp.upper(j) : d(j) * lp.lower(j);
  }
  CHECK(dual == doctest::Approx(r.objective).epsilon(1e-7));
}

// 300 random LPs (drawn from rng) of at most 3 rows and 4 columns (every other one with free columns) solved with
// `options`: each optimum equals the brute-force vertex enumeration's and meets the duality
// conditions, each infeasible one comes with a Farkas certificate; both kinds occur.
// `r` solves `lp` as the brute-force vertex enumeration says: its optimum, meeting the duality
// conditions, or infeasible with a Farkas certificate. Returns whether it is optimal.
bool matches_brute_force(const LinearProgram& lp, const LpResult& r) {
  const double expected = brute_force_optimum(lp);
  if (expected == -kInf) {
    REQUIRE(r.status == LpStatus::infeasible);
    CHECK(farkas_gap(lp, r.y) > 0.0);
    return false;
  }
  REQUIRE(r.status == LpStatus::optimal);
  CHECK(r.objective == doctest::Approx(expected).epsilon(1e-9).scale(1.0));
  check_optimality(lp, r, 1e-8);
  return true;
}

void random_lps_match_brute_force(const BoundedSimplexOptions& options, Rng& rng) {
  int optimal = 0, infeasible = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(4)), m = 1 + static_cast<int>(rng.below(3));
    const LinearProgram lp = random_lp(rng, m, n, trial % 2 == 1);
    if (matches_brute_force(lp, bounded_simplex(lp, options))) ++optimal;
    else ++infeasible;
  }
  CHECK(optimal > 100);
  CHECK(infeasible > 10);
}

}  // namespace

TEST_CASE("bounded simplex: small random LPs match the brute-force vertex enumeration") {
  Rng rng(20261125);
  random_lps_match_brute_force(BoundedSimplexOptions::defaults(), rng);
}

TEST_CASE("bounded simplex: many columns, few rows, warm start: the duality conditions hold") {
  Rng rng(7);
  const LinearProgram lp = random_lp(rng, 8, 3000, true);
  const LpResult r = bounded_simplex(lp);
  REQUIRE(r.status == LpStatus::optimal);
  check_optimality(lp, r, 1e-8);
  // Started from the optimum's bounds, the same answer in fewer steps.
  std::vector<std::int8_t> start(3000);
  for (int j = 0; j < 3000; ++j) start[static_cast<std::size_t>(j)] = r.x(j) > 0.5 * (lp.lower(j) + lp.upper(j));
  const LpResult warm = bounded_simplex(lp, {}, &start);
  REQUIRE(warm.status == LpStatus::optimal);
  CHECK(warm.objective == doctest::Approx(r.objective).epsilon(1e-9));
  CHECK(warm.iterations < r.iterations);
}

TEST_CASE("bounded simplex: many pricing windows and near-equality row pairs: the duality conditions hold") {
  // Past 8192 columns a pass prices an eighth of them at a time, and after a pivot only the pass's
  // candidates are priced again: optimality must still hold over every column. Pairs of rows a
  // hair apart (the reach programme's axis rows) make most steps pivots.
  Rng rng(19);
  int optimal = 0;
  for (int trial = 0; trial < 4; ++trial) {
    const int m = 3 + 2 * trial, n = 9000 + 2500 * trial;
    LinearProgram lp = random_lp(rng, m, n, false);
    VectorXd inside(n);
    for (int j = 0; j < n; ++j) inside(j) = rng.uniform(lp.lower(j), lp.upper(j));
    for (int pair = 0; pair < 2; ++pair) {
      VectorXd a(n);
      for (int j = 0; j < n; ++j) a(j) = rng.uniform(-1.0, 1.0);
      const double centre = a.dot(inside);
      lp.A.conservativeResize(lp.A.rows() + 2, Eigen::NoChange);
      lp.A.row(lp.A.rows() - 2) = a.transpose();
      lp.A.row(lp.A.rows() - 1) = a.transpose();
      lp.b.conservativeResize(lp.b.size() + 2);
      lp.b(lp.b.size() - 2) = centre + 1e-6;
      lp.b(lp.b.size() - 1) = centre - 1e-6;
      lp.sense.push_back(RowSense::less_equal);
      lp.sense.push_back(RowSense::greater_equal);
    }
    const LpResult r = bounded_simplex(lp);
    if (r.status == LpStatus::infeasible) {
      CHECK(farkas_gap(lp, r.y) > 0.0);
      continue;
    }
    REQUIRE(r.status == LpStatus::optimal);
    check_optimality(lp, r, 1e-8);
    ++optimal;
  }
  CHECK(optimal >= 3);
}

TEST_CASE("bounded simplex: a degenerate vertex (many rows through one point) and a free column") {
  // max x + y + z s.t. x + y <= 1, y + z <= 1, x + z <= 1, x + y + z <= 1.5, x - y <= 0, y - x <= 0,
  // 0 <= x, y, z <= 1: every row is active at (0.5, 0.5, 0.5); objective 1.5.
  LinearProgram lp;
  lp.A.resize(6, 4);
  lp.A << 1, 1, 0, 0,  //
      0, 1, 1, 0,      //
      1, 0, 1, 0,      //
      1, 1, 1, 0,      //
      1, -1, 0, 0,     //
      -1, 1, 0, 1;     // the free column w enters here only
  lp.b.resize(6);
  lp.b << 1, 1, 1, 1.5, 0, 0;
  lp.sense.assign(6, RowSense::less_equal);
  lp.c = Eigen::Vector4d(1, 1, 1, 0);
  lp.lower = Eigen::Vector4d(0, 0, 0, -kInf);
  lp.upper = Eigen::Vector4d(1, 1, 1, 0.0);  // w <= 0: y - x <= -w, one-sided
  const LpResult r = bounded_simplex(lp);
  REQUIRE(r.status == LpStatus::optimal);
  CHECK(r.objective == doctest::Approx(1.5));
  check_optimality(lp, r, 1e-9);
}

TEST_CASE("bounded simplex: equality rows and an unbounded free column") {
  // max x0 + 2 x1 s.t. x0 + x1 = 1, x0 - x1 >= -0.5, 0 <= x <= 1: x1 = 0.75, x0 = 0.25, 1.75.
  LinearProgram lp;
  lp.A.resize(2, 2);
  lp.A << 1, 1, 1, -1;
  lp.b = Eigen::Vector2d(1, -0.5);
  lp.sense = {RowSense::equal, RowSense::greater_equal};
  lp.c = Eigen::Vector2d(1, 2);
  lp.lower = Eigen::Vector2d(0, 0);
  lp.upper = Eigen::Vector2d(1, 1);
  const LpResult r = bounded_simplex(lp);
  REQUIRE(r.status == LpStatus::optimal);
  CHECK(r.x(0) == doctest::Approx(0.25));
  CHECK(r.x(1) == doctest::Approx(0.75));
  CHECK(r.objective == doctest::Approx(1.75));
  check_optimality(lp, r, 1e-12);
  // A free column that only raises the objective and meets no row: unbounded.
  LinearProgram open = lp;
  open.A.conservativeResize(2, 3);
  open.A.col(2).setZero();
  open.c = Eigen::Vector3d(1, 2, 1);
  open.lower = Eigen::Vector3d(0, 0, -kInf);
  open.upper = Eigen::Vector3d(1, 1, kInf);
  CHECK(bounded_simplex(open).status == LpStatus::unbounded);
}

TEST_CASE("bounded simplex: an infeasible box gives a Farkas certificate that proves it") {
  // x0 + x1 + x2 >= 2.5 and x0 - x1 = 0.9 with 0 <= x <= 1: x0 = 1, x1 = 0.1 at most gives 2.1.
  LinearProgram lp;
  lp.A.resize(2, 3);
  lp.A << 1, 1, 1, 1, -1, 0;
  lp.b = Eigen::Vector2d(2.5, 0.9);
  lp.sense = {RowSense::greater_equal, RowSense::equal};
  lp.c = Eigen::Vector3d(0, 0, 0);
  lp.lower = Eigen::Vector3d::Zero();
  lp.upper = Eigen::Vector3d::Ones();
  const LpResult r = bounded_simplex(lp);
  REQUIRE(r.status == LpStatus::infeasible);
  CHECK(farkas_gap(lp, r.y) > 0.1);
  // The same certificate on a feasible neighbour cannot be positive (weak duality).
  LinearProgram feasible = lp;
  feasible.b(0) = 2.0;
  CHECK(bounded_simplex(feasible).status == LpStatus::optimal);
  CHECK(farkas_gap(feasible, r.y) <= 1e-12);
}

TEST_CASE("bounded simplex: options are checked, and the iteration cap returns the iterate") {
  BoundedSimplexOptions o;
  CHECK(o.check().empty());
  o.refactor_every = 0;
  CHECK(!o.check().empty());
  Rng rng(3);
  const LinearProgram lp = random_lp(rng, 5, 400, false);
  BoundedSimplexOptions capped;
  capped.max_iterations = 3;
  const LpResult r = bounded_simplex(lp, capped);
  CHECK(r.status == LpStatus::iteration_cap);
  CHECK(r.x.size() == 400);
}

TEST_CASE("bounded simplex, dual method first: brute force, duality conditions, free columns and certificates") {
  BoundedSimplexOptions dual;
  dual.dual = true;
  Rng rng(20261126);
  random_lps_match_brute_force(dual, rng);
  // Many columns and a free one (the reach programme's margin z: max z s.t. rows − z ≥ b): the
  // same optimum as the primal method, in fewer iterations when the optimum moves most columns.
  for (int trial = 0; trial < 3; ++trial) {
    const int m = 4 + 2 * trial, n = 4000 + 3000 * trial;
    LinearProgram lp = random_lp(rng, m, n, false);
    lp.A.conservativeResize(Eigen::NoChange, n + 1);
    lp.A.col(n).setConstant(-1.0);
    lp.sense.assign(static_cast<std::size_t>(m), RowSense::greater_equal);
    lp.c = VectorXd::Zero(n + 1);
    lp.c(n) = 1.0;
    lp.lower.conservativeResize(n + 1);
    lp.upper.conservativeResize(n + 1);
    lp.lower(n) = -kInf;
    lp.upper(n) = kInf;
    const LpResult primal = bounded_simplex(lp);
    const LpResult r = bounded_simplex(lp, dual);
    REQUIRE(primal.status == LpStatus::optimal);
    REQUIRE(r.status == LpStatus::optimal);
    // Feasible, and as good as the primal method's optimum (whose conditions the tests above check).
    const VectorXd row = lp.A * r.x - lp.b;
    CHECK(row.minCoeff() >= -1e-9);
    for (int j = 0; j < n; ++j) CHECK((r.x(j) >= lp.lower(j) - 1e-12 && r.x(j) <= lp.upper(j) + 1e-12));
    CHECK(r.objective == doctest::Approx(primal.objective).epsilon(1e-9));
    CHECK(r.iterations < primal.iterations);
  }
  // A free column that only raises the objective: unbounded, through the primal method.
  LinearProgram open;
  open.A.resize(1, 2);
  open.A << 1, 0;
  open.b = VectorXd::Constant(1, 1.0);
  open.sense = {RowSense::less_equal};
  open.c = Eigen::Vector2d(1, 1);
  open.lower = Eigen::Vector2d(0, -kInf);
  open.upper = Eigen::Vector2d(2, kInf);
  CHECK(bounded_simplex(open, dual).status == LpStatus::unbounded);
}

TEST_CASE("bounded simplex, dual method from a neighbouring programme's basis: brute force and duality conditions") {
  BoundedSimplexOptions dual;
  dual.dual = true;
  Rng rng(20261127);
  // Small programmes: solved, moved a little (as a Dinkelbach step moves the reach programme's
  // rows), solved again from the first one's basis: the moved programme's brute-force optimum.
  int warm_optimal = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + static_cast<int>(rng.below(4)), m = 1 + static_cast<int>(rng.below(3));
    const LinearProgram lp = random_lp(rng, m, n, trial % 2 == 1);
    const LpResult first = bounded_simplex(lp, dual);
    if (first.status != LpStatus::optimal) continue;
    REQUIRE(static_cast<int>(first.basis.size()) == m);
    LinearProgram moved = lp;
    for (int i = 0; i < m; ++i) {
      moved.b(i) += rng.uniform(-0.05, 0.05);
      for (int j = 0; j < n; ++j) moved.A(i, j) += rng.uniform(-0.05, 0.05);
    }
    if (matches_brute_force(moved, bounded_simplex(moved, dual, nullptr, &first.basis))) ++warm_optimal;
  }
  CHECK(warm_optimal > 100);
  // Many columns and the free margin column: the warm basis gives the cold start's optimum in fewer
  // iterations; a basis that names a variable twice is ignored (the slack basis is used).
  LinearProgram lp = random_lp(rng, 6, 6000, false);
  const int n = 6000;
  lp.A.conservativeResize(Eigen::NoChange, n + 1);
  lp.A.col(n).setConstant(-1.0);
  lp.sense.assign(6, RowSense::greater_equal);
  lp.c = VectorXd::Zero(n + 1);
  lp.c(n) = 1.0;
  lp.lower.conservativeResize(n + 1);
  lp.upper.conservativeResize(n + 1);
  lp.lower(n) = -kInf;
  lp.upper(n) = kInf;
  const LpResult first = bounded_simplex(lp, dual);
  REQUIRE(first.status == LpStatus::optimal);
  LinearProgram moved = lp;
  for (int i = 0; i < 6; ++i) moved.A.row(i).head(n) *= 1.0 + 0.01 * (i + 1);
  const LpResult cold = bounded_simplex(moved, dual);
  const LpResult warm = bounded_simplex(moved, dual, nullptr, &first.basis);
  REQUIRE(cold.status == LpStatus::optimal);
  REQUIRE(warm.status == LpStatus::optimal);
  check_optimality(moved, warm, 1e-8);
  CHECK(warm.objective == doctest::Approx(cold.objective).epsilon(1e-9));
  CHECK(warm.iterations < cold.iterations);
  std::vector<int> twice = first.basis;
  twice[1] = twice[0];
  const LpResult fallback = bounded_simplex(moved, dual, nullptr, &twice);
  REQUIRE(fallback.status == LpStatus::optimal);
  CHECK(fallback.objective == doctest::Approx(cold.objective).epsilon(1e-9));
  CHECK(fallback.iterations == cold.iterations);
}
