// The augmented Lagrangian on problems with known answers: a 100,000-row linear block with a
// solution known by construction, infeasible problems (linear and nonlinear) that must end as
// Infeasible at the least-violation point, repeated runs with identical iterates, bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "linear_block_problem.h"
#include "optim/augmented_lagrangian.h"
#include "optim/gradient_check.h"

using namespace offsetopt;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string describe(const AlResult& r) {
  return std::string(to_string(r.status)) + " f=" + std::to_string(r.f) +
         " viol=" + std::to_string(r.max_violation) + " stat=" + std::to_string(r.stationarity) +
         " outer=" + std::to_string(r.outer_iterations) + " inner=" +
         std::to_string(r.inner_iterations) + " evals=" + std::to_string(r.evaluations);
}

// Rosenbrock in 10 variables on the sphere |x|² = 4.
ConstrainedProblem rosenbrock_on_sphere() {
  ConstrainedProblem p;
  p.num_variables = 10;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    double f = 0.0;
    g.setZero();
    for (int i = 0; i + 1 < 10; ++i) {
      const double a = x(i + 1) - x(i) * x(i), b = 1.0 - x(i);
      f += 100.0 * a * a + b * b;
      g(i) += -400.0 * a * x(i) - 2.0 * b;
      g(i + 1) += 200.0 * a;
    }
    return f;
  };
  p.num_equality = 1;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x.squaredNorm() - 4.0;
    j.row(0) = 2.0 * x.transpose();
  };
  return p;
}

// min x1 x4 (x1+x2+x3) + x3, Σx² = 40, x1x2x3x4 ≥ 25, the linear row `a` (x2 − x3) ≤ 0.8,
// 1 ≤ x ≤ 5. The problem refers to `a`, which must outlive it.
MatrixXd hs071_like_linear_row() {
  MatrixXd a(1, 4);
  a << 0.0, 1.0, -1.0, 0.0;
  return a;
}

// The same without the linear row: HS071 itself.
ConstrainedProblem hs071_without_row() {
  ConstrainedProblem p;
  p.num_variables = 4;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    const double s = x(0) + x(1) + x(2);
    g << x(3) * s + x(0) * x(3), x(0) * x(3), x(0) * x(3) + 1.0, x(0) * s;
    return x(0) * x(3) * s + x(2);
  };
  p.num_equality = 1;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x.squaredNorm() - 40.0;
    j.row(0) = 2.0 * x.transpose();
  };
  p.num_inequality = 1;
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = 25.0 - x(0) * x(1) * x(2) * x(3);
    j << -x(1) * x(2) * x(3), -x(0) * x(2) * x(3), -x(0) * x(1) * x(3), -x(0) * x(1) * x(2);
  };
  p.lower = VectorXd::Constant(4, 1.0);
  p.upper = VectorXd::Constant(4, 5.0);
  return p;
}

ConstrainedProblem hs071_like(const MatrixXd& a) {
  ConstrainedProblem p = hs071_without_row();
  p.linear_matrix = &a;
  p.linear_lower = VectorXd::Constant(1, -kInf);
  p.linear_upper = VectorXd::Constant(1, 0.8);  // active: x2 − x3 = 0.92 at HS071's solution
  return p;
}

}  // namespace

TEST_CASE("augmented-lagrangian: 100,000 linear rows, 36 variables, solution known by construction") {
  const LinearBlockProblem lb = make_linear_block_problem(100000, 36, 2015);
  const ConstrainedProblem p = lb.problem();
  // Sanity of the construction: x* feasible, KKT residual zero.
  const VectorXd ax = lb.a * lb.x_star;
  CHECK(((ax - lb.row_lower).array() >= -1e-12).all());
  CHECK(((lb.row_upper - ax).array() >= -1e-12).all());

  const AlResult r = augmented_lagrangian_minimize(p, VectorXd::Zero(36));
  MESSAGE(describe(r));
  CHECK(r.status == AlStatus::converged);
  // x is determined to (stationarity 1e-8) / (smallest curvature of σH on the free subspace,
  // ≈ 2e-3): a few 1e-6; the objective much more tightly.
  CHECK((r.x - lb.x_star).lpNorm<Eigen::Infinity>() < 1e-5);
  CHECK(std::fabs(r.f - lb.f_star) <= 1e-9 * std::fabs(lb.f_star));
  CHECK(r.max_violation <= 1e-8);
  for (int i = 0; i < 36; ++i) {
    CHECK(r.x(i) >= lb.lower(i));
    CHECK(r.x(i) <= lb.upper(i));
  }
  // The multipliers of the active rows are recovered; inactive rows carry none.
  REQUIRE(r.linear_multipliers.size() == 100000);
  double worst = 0.0;
  for (int i : lb.upper_active) worst = std::max(worst, std::fabs(r.linear_multipliers(i) - lb.row_multipliers(i)));
  for (int i : lb.lower_active) worst = std::max(worst, std::fabs(r.linear_multipliers(i) - lb.row_multipliers(i)));
  CHECK(worst < 1e-3 * lb.sigma);  // multipliers are of size σ
  double inactive = 0.0;
  for (int i = 0; i < 100000; ++i)
    if (lb.row_multipliers(i) == 0.0) inactive = std::max(inactive, std::fabs(r.linear_multipliers(i)));
  CHECK(inactive == 0.0);
}

TEST_CASE("augmented-lagrangian: contradictory linear rows end Infeasible at the least-violation point") {
  // x1 + x2 ≥ 2 and x1 + x2 ≤ 1 cannot both hold; ½(2 − s)² + ½(s − 1)² is least at s = 1.5.
  MatrixXd a(2, 2);
  a << 1.0, 1.0, 1.0, 1.0;
  ConstrainedProblem p;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g = 2.0 * x;
    return x.squaredNorm();
  };
  p.linear_matrix = &a;
  p.linear_lower = Eigen::Vector2d(2.0, -kInf);
  p.linear_upper = Eigen::Vector2d(kInf, 1.0);
  const AlResult r = augmented_lagrangian_minimize(p, Eigen::Vector2d(3.0, -1.0));
  MESSAGE(describe(r));
  CHECK(r.status == AlStatus::infeasible);
  CHECK(r.x(0) + r.x(1) == doctest::Approx(1.5).epsilon(1e-7));
  CHECK(r.max_violation == doctest::Approx(0.5).epsilon(1e-7));
  CHECK(r.outer_iterations < 20);
}

TEST_CASE("augmented-lagrangian: nonlinear constraint out of reach of the bounds ends Infeasible") {
  // x1² + x2² ≤ 1 with 2 ≤ x1 ≤ 3: least violation at (2, 0), violation 3.
  ConstrainedProblem p;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << 1.0, -1.0;
    return x(0) - x(1);
  };
  p.num_inequality = 1;
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x.squaredNorm() - 1.0;
    j.row(0) = 2.0 * x.transpose();
  };
  p.lower = Eigen::Vector2d(2.0, -5.0);
  p.upper = Eigen::Vector2d(3.0, 5.0);
  const AlResult r = augmented_lagrangian_minimize(p, Eigen::Vector2d(2.5, 4.0));
  MESSAGE(describe(r));
  CHECK(r.status == AlStatus::infeasible);
  CHECK(r.x(0) == 2.0);
  CHECK(std::fabs(r.x(1)) < 1e-6);
  CHECK(r.max_violation == doctest::Approx(3.0).epsilon(1e-9));
  CHECK(r.outer_iterations < 20);
  // A clearly infeasible problem (violation far above the tolerance) is checked after one
  // stagnant outer iteration: the same answer, sooner.
  AlOptions quick;
  quick.clear_violation_factor = 1e4;
  const AlResult q = augmented_lagrangian_minimize(p, Eigen::Vector2d(2.5, 4.0), quick);
  MESSAGE(describe(q));
  CHECK(q.status == AlStatus::infeasible);
  CHECK(q.max_violation == doctest::Approx(3.0).epsilon(1e-9));
  CHECK(q.outer_iterations < r.outer_iterations);
}

TEST_CASE("augmented-lagrangian: identical iterates on repeated runs") {
  const LinearBlockProblem lb = make_linear_block_problem(5000, 12, 99);
  auto run = [&lb](std::vector<double>& trace) {
    ConstrainedProblem p = lb.problem();
    p.objective = [&lb, &trace](const VectorXd& x, VectorXd& g) {
      trace.insert(trace.end(), x.data(), x.data() + x.size());
      return lb.objective(x, g);
    };
    p.num_inequality = 1;  // plus a nonlinear row: ‖x‖² ≤ 100 (inactive)
    p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
      c(0) = x.squaredNorm() - 100.0;
      j.row(0) = 2.0 * x.transpose();
    };
    return augmented_lagrangian_minimize(p, VectorXd::Constant(12, 0.25));
  };
  std::vector<double> t1, t2;
  const AlResult a = run(t1);
  const AlResult b = run(t2);
  CHECK(a.status == AlStatus::converged);
  CHECK(t1.size() > 100);
  CHECK(t1 == t2);
  CHECK(a.x == b.x);
  CHECK(a.linear_multipliers == b.linear_multipliers);
  CHECK(a.evaluations == b.evaluations);
}

TEST_CASE("augmented-lagrangian: KKT residual with the returned multipliers (HS071-like mix)") {
  // min x1 x4 (x1+x2+x3) + x3, Σx² = 40, x1x2x3x4 ≥ 25, a linear row x2 − x3 ≤ 0.8,
  // 1 ≤ x ≤ 5. The stationarity of the Lagrangian with the returned (unscaled) multipliers is
  // checked on the variables strictly inside their bounds.
  const MatrixXd a = hs071_like_linear_row();
  const ConstrainedProblem p = hs071_like(a);
  VectorXd x0(4);
  x0 << 1.0, 5.0, 5.0, 1.0;
  const AlResult r = augmented_lagrangian_minimize(p, x0);
  MESSAGE(describe(r));
  REQUIRE(r.status == AlStatus::converged);
  CHECK(r.x(1) - r.x(2) == doctest::Approx(0.8).epsilon(1e-8));
  CHECK(r.linear_multipliers(0) > 0.0);
  VectorXd g(4), ce(1), ci(1);
  MatrixXd je(1, 4), ji(1, 4);
  p.objective(r.x, g);
  p.equality(r.x, ce, je);
  p.inequality(r.x, ci, ji);
  const VectorXd residual = g + je.transpose() * r.equality_multipliers +
                            ji.transpose() * r.inequality_multipliers +
                            a.transpose() * r.linear_multipliers;
  for (int i = 0; i < 4; ++i) {
    if (r.x(i) > 1.0 + 1e-9 && r.x(i) < 5.0 - 1e-9) CHECK(std::fabs(residual(i)) < 1e-6);
    if (r.x(i) == 1.0) CHECK(residual(i) > -1e-6);  // lower bound multiplier ≥ 0
  }
}

TEST_CASE("augmented-lagrangian: values and one weighted gradient per point give the run of the full callbacks") {
  // The same HS071-like problem offered both ways. The weighted gradient is formed here exactly
  // as the solver forms it from the full callbacks (w_f ∇f, then + J^T w), so the two runs must
  // take the same iterates bit for bit; and with values offered, the full callbacks (every row's
  // gradient) are asked for at the start point only, for the row scales.
  const MatrixXd a = hs071_like_linear_row();
  const ConstrainedProblem p = hs071_like(a);
  VectorXd x0(4);
  x0 << 1.0, 5.0, 5.0, 1.0;
  const AlResult plain = augmented_lagrangian_minimize(p, x0);
  REQUIRE(plain.status == AlStatus::converged);

  ConstrainedProblem combined = p;
  int full_calls = 0;
  const ObjectiveFunction objective = p.objective;
  combined.objective = [&full_calls, objective](const VectorXd& x, VectorXd& g) {
    ++full_calls;
    return objective(x, g);
  };
  combined.values = [&p](const VectorXd& x, VectorXd& rows) {
    VectorXd g(4), ce(1), ci(1);
    MatrixXd je(1, 4), ji(1, 4);
    p.equality(x, ce, je);
    p.inequality(x, ci, ji);
    rows << ce(0), ci(0);
    return p.objective(x, g);
  };
  combined.weighted_gradient = [&p](const VectorXd& x, double objective_weight, const VectorXd& w, VectorXd& grad) {
    VectorXd g(4), ce(1), ci(1);
    MatrixXd je(1, 4), ji(1, 4), jac(2, 4);
    p.objective(x, g);
    p.equality(x, ce, je);
    p.inequality(x, ci, ji);
    jac << je, ji;
    if (objective_weight == 0.0) {
      grad.setZero();
    } else {
      grad = objective_weight * g;
    }
    grad.noalias() += jac.transpose() * w;
  };
  const AlResult r = augmented_lagrangian_minimize(combined, x0);
  MESSAGE(describe(r));
  CHECK(r.status == plain.status);
  CHECK(r.evaluations == plain.evaluations);
  CHECK(r.inner_iterations == plain.inner_iterations);
  CHECK((r.x.array() == plain.x.array()).all());
  CHECK(full_calls == 1);

  ConstrainedProblem half = p;
  half.values = combined.values;
  const AlResult refused = augmented_lagrangian_minimize(half, x0);
  CHECK(refused.status == AlStatus::invalid_input);
}

TEST_CASE("augmented-lagrangian: a noisy gradient ends Stalled at a feasible point, not in a loop") {
  // (x1 − 1)² + (x2 − 2)² on x1 + x2 = 1 (solution (0, 1)), with a deterministic gradient error
  // of 1e-6 that makes the stationarity tolerance 1e-8 unreachable.
  ConstrainedProblem p;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    std::uint64_t b0, b1;
    std::memcpy(&b0, &x(0), 8);
    std::memcpy(&b1, &x(1), 8);
    Rng noise(b0 ^ (b1 * 0x9E3779B97F4A7C15ull));
    g << 2.0 * (x(0) - 1.0) + 1e-6 * noise.uniform(-1.0, 1.0),
        2.0 * (x(1) - 2.0) + 1e-6 * noise.uniform(-1.0, 1.0);
    return (x(0) - 1.0) * (x(0) - 1.0) + (x(1) - 2.0) * (x(1) - 2.0);
  };
  p.num_equality = 1;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(0) + x(1) - 1.0;
    j << 1.0, 1.0;
  };
  const AlResult r = augmented_lagrangian_minimize(p, Eigen::Vector2d(3.0, 3.0));
  MESSAGE(describe(r));
  CHECK(r.status == AlStatus::stalled);
  CHECK(r.max_violation <= 1e-8);
  CHECK((r.x - Eigen::Vector2d(0.0, 1.0)).lpNorm<Eigen::Infinity>() < 1e-5);
  CHECK(r.outer_iterations < 30);
}

TEST_CASE("augmented-lagrangian: a feasible problem with a flat constraint is not called Infeasible") {
  // min (x1 − 1)² + (x2 − 1)² with 1e-4 (x1 + x2 − 1) = 0: the row's gradient (1e-4) is below
  // the scale floor, so near the solution the violation is tiny while its gradient is tinier
  // still. A stationarity test of the least-violation step that is not relative to the
  // violation stops there and calls a feasible problem infeasible.
  ConstrainedProblem p;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << 2.0 * (x(0) - 1.0), 2.0 * (x(1) - 1.0);
    return (x(0) - 1.0) * (x(0) - 1.0) + (x(1) - 1.0) * (x(1) - 1.0);
  };
  p.num_equality = 1;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = 1e-4 * (x(0) + x(1) - 1.0);
    j << 1e-4, 1e-4;
  };
  AlOptions params;
  params.feasibility_tolerance = 1e-12;
  params.stationarity_tolerance = 1e-6;
  const AlResult r = augmented_lagrangian_minimize(p, Eigen::Vector2d(0.0, 0.0), params);
  MESSAGE(describe(r));
  CHECK(r.status != AlStatus::infeasible);
  CHECK(r.max_violation <= 1e-12);
  CHECK((r.x - Eigen::Vector2d(0.5, 0.5)).lpNorm<Eigen::Infinity>() < 1e-4);
}

TEST_CASE("augmented-lagrangian: a warm start with the solution's multipliers needs fewer evaluations") {
  // The HS071-like problem above without its linear row, solved cold, then again from a nearby
  // start with the returned multipliers and penalty: same answer, fewer evaluations. Wrong
  // multiplier counts are refused.
  const ConstrainedProblem p = hs071_without_row();
  VectorXd x0(4);
  x0 << 1.0, 5.0, 5.0, 1.0;
  const AlResult cold = augmented_lagrangian_minimize(p, x0);
  REQUIRE(cold.status == AlStatus::converged);
  const VectorXd nearby = cold.x + VectorXd::Constant(4, 1e-3);
  const AlResult cold_again = augmented_lagrangian_minimize(p, nearby);
  AlOptions warm_params;
  warm_params.initial_equality_multipliers = cold.equality_multipliers;
  warm_params.initial_inequality_multipliers = cold.inequality_multipliers;
  warm_params.initial_penalty = cold.penalty;
  const AlResult warm = augmented_lagrangian_minimize(p, nearby, warm_params);
  MESSAGE("cold " << describe(cold_again) << "; warm " << describe(warm));
  REQUIRE(warm.status == AlStatus::converged);
  CHECK((warm.x - cold.x).lpNorm<Eigen::Infinity>() < 1e-6);
  CHECK(warm.evaluations < cold_again.evaluations);
  CHECK(warm.equality_multipliers(0) == doctest::Approx(cold.equality_multipliers(0)).epsilon(1e-4));

  AlOptions wrong;
  wrong.initial_inequality_multipliers = VectorXd::Zero(2);
  const AlResult refused = augmented_lagrangian_minimize(p, x0, wrong);
  CHECK(refused.status == AlStatus::invalid_input);
  CHECK(refused.message.find("initial_inequality_multipliers") != std::string::npos);
}

TEST_CASE("augmented-lagrangian: no constraints is a plain bound-constrained solve") {
  ConstrainedProblem p;
  p.num_variables = 3;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g = 2.0 * (x - Eigen::Vector3d(1.0, 2.0, 3.0));
    return (x - Eigen::Vector3d(1.0, 2.0, 3.0)).squaredNorm();
  };
  p.upper = Eigen::Vector3d(kInf, 1.5, kInf);
  p.lower = Eigen::Vector3d(-kInf, -kInf, -kInf);
  const AlResult r = augmented_lagrangian_minimize(p, VectorXd::Zero(3));
  CHECK(r.status == AlStatus::converged);
  CHECK((r.x - Eigen::Vector3d(1.0, 1.5, 3.0)).lpNorm<Eigen::Infinity>() < 1e-8);
  CHECK(r.outer_iterations <= 2);
}

TEST_CASE("augmented-lagrangian: bad input and non-finite start are reported, not thrown") {
  ConstrainedProblem p;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g = 2.0 * x;
    return x.squaredNorm();
  };
  CHECK(augmented_lagrangian_minimize(p, VectorXd::Zero(3)).status == AlStatus::invalid_input);
  ConstrainedProblem q = p;
  q.num_equality = 1;  // no function
  CHECK(augmented_lagrangian_minimize(q, VectorXd::Zero(2)).status == AlStatus::invalid_input);
  MatrixXd a = MatrixXd::Ones(3, 2);
  ConstrainedProblem r = p;
  r.linear_matrix = &a;
  r.linear_lower = VectorXd::Zero(3);
  r.linear_upper = VectorXd::Zero(2);
  CHECK(augmented_lagrangian_minimize(r, VectorXd::Zero(2)).status == AlStatus::invalid_input);
  r.linear_upper = VectorXd::Constant(3, -1.0);  // lower > upper
  const AlResult bad_rows = augmented_lagrangian_minimize(r, VectorXd::Zero(2));
  CHECK(bad_rows.status == AlStatus::invalid_input);
  CHECK(bad_rows.message.find("row 0") != std::string::npos);
  CHECK(bad_rows.x.size() == 2);  // the start point comes back: callers may use x regardless
  ConstrainedProblem empty_box = p;
  empty_box.lower = Eigen::Vector2d(0.0, 1.0);
  empty_box.upper = Eigen::Vector2d(1.0, 0.5);
  const AlResult empty = augmented_lagrangian_minimize(empty_box, Eigen::Vector2d(0.5, 0.75));
  CHECK(empty.status == AlStatus::invalid_input);
  CHECK(empty.message.find("variable 1") != std::string::npos);
  CHECK(empty.x == Eigen::Vector2d(0.5, 0.75));
  AlOptions params;
  params.feasibility_tolerance = 0.0;
  CHECK(augmented_lagrangian_minimize(p, VectorXd::Zero(2), params).status == AlStatus::invalid_input);
  ConstrainedProblem s = p;
  s.objective = [](const VectorXd&, VectorXd& g) {
    g.setZero();
    return std::numeric_limits<double>::infinity();
  };
  CHECK(augmented_lagrangian_minimize(s, VectorXd::Zero(2)).status == AlStatus::numerical_issue);
}

TEST_CASE("gradient-check: accepts exact derivatives and pinpoints a wrong component") {
  ObjectiveFunction good = [](const VectorXd& x, VectorXd& g) {
    g << 2.0 * x(0) * x(1), x(0) * x(0) + 3.0 * x(2), 3.0 * x(1);
    return x(0) * x(0) * x(1) + 3.0 * x(1) * x(2);
  };
  ObjectiveFunction bad = [&good](const VectorXd& x, VectorXd& g) {
    const double f = good(x, g);
    g(2) *= 1.0001;
    return f;
  };
  const Eigen::Vector3d x(0.3, -1.2, 2.5);
  const GradientCheckResult ok4 = check_gradient(good, x);
  CHECK(ok4.passed);
  CHECK(ok4.normalized_error < 1e-10);
  GradientCheckOptions second;
  second.order = 2;
  second.relative_step = 1e-6;
  CHECK(check_gradient(good, x, second).passed);
  const GradientCheckResult wrong = check_gradient(bad, x);
  CHECK_FALSE(wrong.passed);
  CHECK(wrong.worst_index == 2);
  CHECK(wrong.max_abs_error == doctest::Approx(3.6e-4).epsilon(1e-4));  // 1e-4 of |−3.6|

  ConstraintFunction jac_bad = [](const VectorXd& v, VectorXd& c, MatrixXd& j) {
    c << v(0) * v(1), v.squaredNorm();
    j << v(1), v(0), 0.0, 2.0 * v(0), 2.0 * v(1), 2.0 * v(2) + 1e-3;
  };
  const JacobianCheckResult jr = check_jacobian(jac_bad, 2, x);
  CHECK_FALSE(jr.passed);
  CHECK(jr.worst_row == 1);
  CHECK(jr.worst_col == 2);
  GradientCheckOptions invalid;
  invalid.order = 3;
  CHECK_FALSE(check_gradient(good, x, invalid).passed);
  CHECK_FALSE(check_gradient(good, x, invalid).message.empty());
}

TEST_CASE("augmented-lagrangian: an exhausted evaluation budget ends max_evaluations at once") {
  // Rosenbrock in 10 variables on the sphere |x|² = 4: far more than the budget allows. When the
  // budget runs out inside a subproblem, the next subproblem's only evaluation is the cached
  // start point, so no outer iteration can move: the solve must stop there, not raise the
  // penalty outer iteration after outer iteration and then call the problem infeasible.
  const ConstrainedProblem p = rosenbrock_on_sphere();
  for (int budget : {7, 25, 60}) {
    CAPTURE(budget);
    AlOptions params;
    params.max_evaluations = budget;
    const AlResult r = augmented_lagrangian_minimize(p, VectorXd::Constant(10, -1.0), params);
    MESSAGE(describe(r));
    CHECK(r.status == AlStatus::max_evaluations);
    CHECK(r.evaluations <= budget);
    // Each budget runs out inside the first subproblem: the solve ends with it.
    CHECK(r.outer_iterations == 1);
  }
}

TEST_CASE("augmented-lagrangian: a stop flag ends the solve within the subproblem in flight") {
  // Rosenbrock in 10 variables on the sphere |x|² = 4, as above; the flag is raised from inside
  // the objective after `after` evaluations (in use, by another thread). The solve must end
  // `stopped` with far fewer evaluations than the whole solve, claim nothing (status), and have
  // followed the same iterates as the unstopped solve up to there.
  ConstrainedProblem p = rosenbrock_on_sphere();
  std::vector<double> trace;
  std::atomic<bool>* raise = nullptr;
  int after = 0;
  p.objective = [&trace, &raise, &after, rosenbrock = p.objective](const VectorXd& x, VectorXd& g) {
    trace.push_back(x(0));
    if (raise && static_cast<int>(trace.size()) == after) raise->store(true);
    return rosenbrock(x, g);
  };
  const AlResult full = augmented_lagrangian_minimize(p, VectorXd::Constant(10, -1.0));
  REQUIRE(full.status == AlStatus::converged);
  const std::vector<double> full_trace = trace;
  for (int stop_after : {2, 30, 90}) {
    CAPTURE(stop_after);
    std::atomic<bool> stop{false};
    raise = &stop;
    after = stop_after;
    trace.clear();
    AlOptions params;
    params.stop = &stop;
    const AlResult r = augmented_lagrangian_minimize(p, VectorXd::Constant(10, -1.0), params);
    MESSAGE(describe(r));
    CHECK(r.status == AlStatus::stopped);
    CHECK(std::string(to_string(r.status)) == "stopped");
    CHECK(r.evaluations < full.evaluations);
    // At most the rest of one line search, the subproblem's final evaluation and the stop's own.
    CHECK(r.evaluations <= stop_after + params.inner.max_line_search_evaluations + 2);
    const std::size_t common = std::min(trace.size(), full_trace.size()) - 1;  // the stop's own evaluation may differ
    CHECK(std::equal(trace.begin(), trace.begin() + static_cast<std::ptrdiff_t>(common), full_trace.begin()));
  }
}

TEST_CASE("augmented-lagrangian: a hand-off takes the first iterate within its violation, once, and declined changes nothing") {
  // Rosenbrock on the sphere |x|² = 4, as above. Declined, the run is the same to the bit as one
  // without a hand-off, and it was asked once, at an iterate within its violation. Taken, the run
  // ends there `handed_off`, that iterate and its violation (measured here on the sphere) within
  // the bound, in fewer evaluations; from its multipliers and penalty a warm run converges to the
  // same point as the whole one.
  const ConstrainedProblem p = rosenbrock_on_sphere();
  const VectorXd x0 = VectorXd::Constant(10, -1.0);
  AlOptions params;
  params.feasibility_tolerance = 1e-10;
  const AlResult full = augmented_lagrangian_minimize(p, x0, params);
  REQUIRE(full.status == AlStatus::converged);
  const double bound = 1e-6;
  std::vector<VectorXd> asked;
  AlOptions declining = params;
  declining.hand_off_violation = bound;
  declining.hand_off = [&asked](const VectorXd& x) {
    asked.push_back(x);
    return false;
  };
  const AlResult declined = augmented_lagrangian_minimize(p, x0, declining);
  REQUIRE(asked.size() == 1);
  CHECK(std::fabs(asked[0].squaredNorm() - 4.0) <= bound * (1.0 + 1e-9));
  CHECK(declined.status == full.status);
  CHECK(declined.evaluations == full.evaluations);
  CHECK(declined.x == full.x);

  AlOptions taking = params;
  taking.hand_off_violation = bound;
  taking.hand_off = [](const VectorXd&) { return true; };
  const AlResult taken = augmented_lagrangian_minimize(p, x0, taking);
  MESSAGE(describe(taken));
  CHECK(taken.status == AlStatus::handed_off);
  CHECK(std::string(to_string(taken.status)) == "handed-off");
  CHECK(taken.x == asked[0]);
  CHECK(std::fabs(taken.x.squaredNorm() - 4.0) <= bound * (1.0 + 1e-9));
  CHECK(taken.evaluations < full.evaluations);
  AlOptions warm = params;
  warm.initial_equality_multipliers = taken.equality_multipliers;
  warm.initial_inequality_multipliers = taken.inequality_multipliers;
  warm.initial_penalty = taken.penalty;
  const AlResult rest = augmented_lagrangian_minimize(p, taken.x, warm);
  REQUIRE(rest.status == AlStatus::converged);
  CHECK((rest.x - full.x).lpNorm<Eigen::Infinity>() < 1e-6);

  AlOptions bad = params;
  bad.hand_off_violation = -1.0;
  CHECK(augmented_lagrangian_minimize(p, x0, bad).status == AlStatus::invalid_input);
}
