// The reduced problem's exact gradient (goal ∘ integrals ∘ offset surfaces ∘ clamp ∘ basis)
// against central finite differences, in every mode: clamp and hard bounds, with and without
// outer offsets, with fixed vertices; and the clamp keeps every offset inside its band.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>

#include <Eigen/QR>

#include "mesh/primitives.h"
#include "shape/reduced_problem.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

struct Setup {
  Mesh mesh;
  OffsetBand band;
  Eigen::MatrixXd basis;
};

// A unit sphere resting on z = 0, radial directions, a smooth random basis (low-order
// polynomials of the position, orthonormalised), a few fixed vertices at the top. Subdivision 4
// (2,562 vertices) is large enough for an evaluation to run its parts on two threads.
Setup sphere_setup(int k, int subdivisions = 2) {
  Setup s;
  s.mesh = make_icosphere(0.5, subdivisions);
  s.mesh.V.col(2).array() += 0.5;
  const Eigen::Index n = s.mesh.V.rows();
  s.band.inner_direction.resize(n, 3);
  s.band.lower.resize(n);
  s.band.upper.resize(n);
  s.band.fixed.assign(static_cast<std::size_t>(n), 0);
  Rng rng(5);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector3d radial = s.mesh.V.row(i) - Eigen::RowVector3d(0, 0, 0.5);
    s.band.inner_direction.row(i) = -radial.normalized();
    s.band.lower(i) = 0.02 + 0.01 * rng.uniform();
    s.band.upper(i) = 0.3 + 0.1 * rng.uniform();
    if (s.mesh.V(i, 2) > 0.97) s.band.fixed[static_cast<std::size_t>(i)] = 1;
  }
  s.band.lower(3) = s.band.upper(3) + 0.05;  // one band empty: a part left solid
  s.band.outer_direction = -s.band.inner_direction;
  s.band.outer_limit = Eigen::VectorXd::Constant(n, 0.05);
  Eigen::MatrixXd raw(n, k);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = s.mesh.V(i, 0), y = s.mesh.V(i, 1), z = s.mesh.V(i, 2);
    const double features[] = {1, x, y, z, x * y, y * z, z * x, x * x - y * y, z * z, x * y * z};
    for (int j = 0; j < k; ++j) raw(i, j) = features[j % 10] + 0.01 * rng.uniform();
  }
  s.basis = raw.householderQr().householderQ() * Eigen::MatrixXd::Identity(n, k);
  return s;
}

GoalSpec spin_goal() {
  GoalSpec g;
  g.kind = GoalKind::spin;
  g.axis_point = {0.0, 0.0, 0.0};
  return g;
}

GoalSpec volume_goal() {
  GoalSpec g;
  g.kind = GoalKind::volume;
  g.target_volume = 0.2;
  return g;
}

GoalSpec roly_goal() {
  GoalSpec g;
  g.kind = GoalKind::roly_poly;
  g.axis_point = {0.0, 0.0, 0.5};
  return g;
}

GoalSpec filled_goal() {
  GoalSpec g;
  g.kind = GoalKind::stand_filled;
  g.support_polygon = {{-0.2, -0.2}, {0.2, -0.2}, {0.2, 0.2}, {-0.2, 0.2}};
  g.margin = 0.01;
  g.fill_density = 0.7;
  return g;
}

void check_gradients(ReducedProblem& problem, const Eigen::VectorXd& x0) {
  const ReducedProblem::Evaluation at = problem.evaluate(x0);
  const Eigen::Index nv = x0.size();
  double worst = 0.0;
  for (Eigen::Index j = 0; j < nv; ++j) {
    const double h = 1e-7;
    Eigen::VectorXd xp = x0, xm = x0;
    xp(j) += h;
    xm(j) -= h;
    const ReducedProblem::Evaluation plus = problem.evaluate(xp);
    const ReducedProblem::Evaluation minus = problem.evaluate(xm);
    auto compare = [&](double fd, double analytic, double scale) {
      worst = std::max(worst, std::fabs(fd - analytic) / (1e-3 + scale));
    };
    compare((plus.objective - minus.objective) / (2 * h), at.objective_gradient(j), at.objective_gradient.cwiseAbs().maxCoeff());
    for (Eigen::Index r = 0; r < at.goal.equality.size(); ++r)
      compare((plus.goal.equality(r) - minus.goal.equality(r)) / (2 * h), at.equality_jacobian(r, j),
              at.equality_jacobian.row(r).cwiseAbs().maxCoeff());
    for (Eigen::Index r = 0; r < at.goal.inequality.size(); ++r)
      compare((plus.goal.inequality(r) - minus.goal.inequality(r)) / (2 * h), at.inequality_jacobian(r, j),
              at.inequality_jacobian.row(r).cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-5);
}

}  // namespace

TEST_CASE("reduced problem gradients match finite differences in every mode") {
  const Setup s = sphere_setup(10);
  for (bool outer : {false, true})
    for (BoundsMode bounds : {BoundsMode::clamp, BoundsMode::hard})
      for (const GoalSpec& goal : {spin_goal(), filled_goal()}) {
        CAPTURE(outer);
        CAPTURE(static_cast<int>(bounds));
        CAPTURE(to_string(goal.kind));
        ReducedOptions options;
        options.outer = outer;
        options.outer_penalty = 0.5;
        options.bounds = bounds;
        options.ramp_width = 0.02;
        options.start_fraction = 0.0;  // many inner offsets near the wall, where the outer offset drags them
        ReducedProblem problem(s.mesh, s.band, s.basis, false, goal, options);
        Eigen::VectorXd x = problem.start_point();
        Rng rng(9);
        for (Eigen::Index j = 0; j < x.size(); ++j) x(j) += 0.3 * rng.uniform(-1, 1);
        const ReducedProblem::Evaluation& e = problem.evaluate(x);
        int near_wall = 0;
        for (Eigen::Index i = 0; i < s.mesh.V.rows(); ++i)
          near_wall += std::fabs(e.inner_offset(i) + e.outer_offset(i) - s.band.lower(i)) < 0.02;
        CHECK(near_wall > 10);  // the lower ramp is exercised
        check_gradients(problem, x);
      }
}

TEST_CASE("clamped offsets stay in their band and fixed vertices do not move") {
  const Setup s = sphere_setup(10);
  ReducedOptions options;
  options.outer = true;
  ReducedProblem problem(s.mesh, s.band, s.basis, false, filled_goal(), options);
  Rng rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(problem.num_variables());
    for (Eigen::Index j = 0; j < x.size(); ++j) x(j) = rng.uniform(-5, 5);
    const ReducedProblem::Evaluation& e = problem.evaluate(x);
    for (Eigen::Index i = 0; i < s.mesh.V.rows(); ++i) {
      if (s.band.fixed[static_cast<std::size_t>(i)]) {
        CHECK(e.inner_offset(i) == 0.0);
        CHECK(e.outer_offset(i) == 0.0);
        continue;
      }
      CHECK(e.outer_offset(i) >= -std::min(0.05, std::max(0.0, 0.5 * (s.band.upper(i) - s.band.lower(i)))));
      CHECK(e.outer_offset(i) <= 0.05);
      CHECK(e.inner_offset(i) <= s.band.upper(i));
      // The wall: inner + outer >= δl wherever the part is not left solid.
      if (s.band.lower(i) - e.outer_offset(i) < s.band.upper(i))
        CHECK(e.inner_offset(i) + e.outer_offset(i) >= s.band.lower(i) - 1e-15);
    }
  }
}

TEST_CASE("identity basis (per-vertex problem) has the same gradient structure") {
  Setup s = sphere_setup(4);
  ReducedOptions options;
  options.ramp_width = 0.01;
  ReducedProblem problem(s.mesh, s.band, Eigen::MatrixXd(), true, spin_goal(), options);
  CHECK(problem.num_variables() == s.mesh.V.rows());
  Eigen::VectorXd x = problem.start_point();
  Rng rng(4);
  for (Eigen::Index j = 0; j < x.size(); ++j) x(j) += 0.02 * rng.uniform(-1, 1);
  const ReducedProblem::Evaluation at = problem.evaluate(x);
  // Spot-check a few coordinates (the full FD sweep over 162 variables is the same code path).
  for (Eigen::Index j : {0, 7, 40, 161}) {
    Eigen::VectorXd xp = x, xm = x;
    xp(j) += 1e-7;
    xm(j) -= 1e-7;
    const double fd = (problem.evaluate(xp).objective - problem.evaluate(xm).objective) / 2e-7;
    CHECK(std::fabs(fd - at.objective_gradient(j)) <= 1e-5 * (1e-3 + at.objective_gradient.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("with outer offsets, one and two threads give bit-identical evaluations") {
  const Setup s = sphere_setup(8);
  ReducedOptions serial_options;
  serial_options.outer = true;
  serial_options.outer_penalty = 0.5;
  serial_options.threads = 1;
  ReducedOptions threaded_options = serial_options;
  threaded_options.threads = 2;
  // serial_while switches a threaded problem's evaluations to one thread and back between them
  // (trial 1 runs serially): the same bits either way.
  std::atomic<bool> another_task_running{false};
  threaded_options.serial_while = &another_task_running;
  ReducedProblem serial(s.mesh, s.band, s.basis, false, filled_goal(), serial_options);
  ReducedProblem threaded(s.mesh, s.band, s.basis, false, filled_goal(), threaded_options);
  Rng rng(9);
  for (int trial = 0; trial < 3; ++trial) {
    another_task_running = trial == 1;
    Eigen::VectorXd x = serial.start_point();
    for (Eigen::Index j = 0; j < x.size(); ++j) x(j) += 0.05 * rng.uniform(-1.0, 1.0);
    const ReducedProblem::Evaluation a = serial.evaluate(x);
    const ReducedProblem::Evaluation& b = threaded.evaluate(x);
    CHECK(a.objective == b.objective);
    CHECK((a.objective_gradient.array() == b.objective_gradient.array()).all());
    CHECK((a.inner_integrals.array() == b.inner_integrals.array()).all());
    CHECK((a.outer_integrals.array() == b.outer_integrals.array()).all());
    CHECK((a.inequality_jacobian.array() == b.inequality_jacobian.array()).all());
  }
}

TEST_CASE("the solver's evaluations (only the integrals the goal reads) agree bit for bit with evaluate()") {
  // The solver's closures sum only goal_integral_rows integrals; evaluate() sums all ten. Each is
  // checked against a new problem's first evaluation at the same x (nothing reused), for goals
  // reading 1, 4 and 10 integrals, with and without outer offsets, over several points so the
  // work space kept between evaluations is exercised.
  const Setup s = sphere_setup(8);
  for (const GoalSpec& goal : {volume_goal(), roly_goal(), filled_goal(), spin_goal()})
    for (bool outer : {false, true}) {
      CAPTURE(to_string(goal.kind));
      CAPTURE(outer);
      ReducedOptions options;
      options.outer = outer;
      options.threads = 1;
      ReducedProblem kept(s.mesh, s.band, s.basis, false, goal, options);
      const ConstrainedProblem solver_view = kept.constrained_problem();
      Rng rng(31);
      for (int trial = 0; trial < 3; ++trial) {
        Eigen::VectorXd x = kept.start_point();
        for (Eigen::Index j = 0; j < x.size(); ++j) x(j) += 0.05 * rng.uniform(-1.0, 1.0);
        ReducedProblem fresh(s.mesh, s.band, s.basis, false, goal, options);
        const ReducedProblem::Evaluation expected = fresh.evaluate(x);
        Eigen::VectorXd gradient, equality, inequality;
        Eigen::MatrixXd equality_jacobian, inequality_jacobian;
        const double objective = solver_view.objective(x, gradient);
        solver_view.equality(x, equality, equality_jacobian);
        solver_view.inequality(x, inequality, inequality_jacobian);
        CHECK(objective == expected.objective);
        CHECK((gradient.array() == expected.objective_gradient.array()).all());
        CHECK((equality.array() == expected.goal.equality.array()).all());
        CHECK((inequality.array() == expected.goal.inequality.array()).all());
        CHECK((equality_jacobian.array() == expected.equality_jacobian.array()).all());
        CHECK((inequality_jacobian.array() == expected.inequality_jacobian.array()).all());
        // evaluate() at the point the solver just saw: all ten integrals, not the solver's cache.
        const ReducedProblem::Evaluation& full = kept.evaluate(x);
        CHECK((full.inner_integrals.array() == expected.inner_integrals.array()).all());
        CHECK((full.outer_integrals.array() == expected.outer_integrals.array()).all());
        CHECK(full.objective == expected.objective);
      }
    }
}

TEST_CASE("the solver's combined gradient agrees with the Jacobians of evaluate() and is the same on one and two threads") {
  // Inside its subproblems the solver asks for the values alone, then for one combination
  // objective_weight ∇f + Σ w_r ∇row_r, which the problem projects onto Γ as one row per vertex.
  // Checked against the dense product with evaluate()'s Jacobians on a fresh problem, for goals
  // reading 1, 4 and 10 integrals, every bounds mode, with and without outer offsets, and the
  // identity basis (on the small sphere: its hard mode is dense #V by #V); values-only calls at
  // other points come in between, as a line search makes them.
  const Setup large = sphere_setup(8, 4), small = sphere_setup(8);
  for (const GoalSpec& goal : {volume_goal(), roly_goal(), filled_goal(), spin_goal()})
    for (bool outer : {false, true})
      for (BoundsMode bounds : {BoundsMode::clamp, BoundsMode::hard})
        for (bool identity : {false, true}) {
          CAPTURE(to_string(goal.kind));
          CAPTURE(outer);
          CAPTURE(static_cast<int>(bounds));
          CAPTURE(identity);
          const Setup& s = identity ? small : large;
          ReducedOptions options;
          options.outer = outer;
          options.outer_penalty = 0.5;
          options.bounds = bounds;
          options.ramp_width = 0.02;
          const Eigen::MatrixXd basis = identity ? Eigen::MatrixXd() : s.basis;
          ReducedOptions two_threads = options;
          options.threads = 1;
          two_threads.threads = 2;
          ReducedProblem kept(s.mesh, s.band, basis, identity, goal, options);
          ReducedProblem kept2(s.mesh, s.band, basis, identity, goal, two_threads);
          const ConstrainedProblem view = kept.constrained_problem(), view2 = kept2.constrained_problem();
          REQUIRE(view.values);
          REQUIRE(view.weighted_gradient);
          const Eigen::Index rows = view.num_equality + view.num_inequality;
          Rng rng(41);
          for (int trial = 0; trial < 3; ++trial) {
            Eigen::VectorXd x = kept.start_point(), elsewhere = x;
            for (Eigen::Index j = 0; j < x.size(); ++j) {
              x(j) += 0.05 * rng.uniform(-1.0, 1.0);
              elsewhere(j) += 0.05 * rng.uniform(-1.0, 1.0);
            }
            const double objective_weight = trial == 1 ? 0.0 : rng.uniform(0.5, 2.0);
            Eigen::VectorXd weights(rows);
            for (Eigen::Index r = 0; r < rows; ++r) weights(r) = rng.uniform(-1.0, 1.0);
            ReducedProblem fresh(s.mesh, s.band, basis, identity, goal, options);
            const ReducedProblem::Evaluation expected = fresh.evaluate(x);
            Eigen::VectorXd dense = objective_weight * expected.objective_gradient;
            const Eigen::Index ne = expected.goal.equality.size();
            dense += expected.equality_jacobian.transpose() * weights.head(ne);
            dense += expected.inequality_jacobian.transpose() * weights.tail(rows - ne);
            double scale = std::fabs(objective_weight) * expected.objective_gradient.cwiseAbs().maxCoeff();
            for (Eigen::Index r = 0; r < ne; ++r) scale += std::fabs(weights(r)) * expected.equality_jacobian.row(r).cwiseAbs().maxCoeff();
            for (Eigen::Index r = ne; r < rows; ++r)
              scale += std::fabs(weights(r)) * expected.inequality_jacobian.row(r - ne).cwiseAbs().maxCoeff();

            Eigen::VectorXd values(rows), values2(rows), gradient(x.size()), gradient2(x.size());
            if (trial == 2) {  // a values-only call elsewhere first: its derivatives are never read
              view.values(elsewhere, values);
              view2.values(elsewhere, values2);
            }
            const double objective = view.values(x, values);
            view.weighted_gradient(x, objective_weight, weights, gradient);
            const double objective2 = view2.values(x, values2);
            view2.weighted_gradient(x, objective_weight, weights, gradient2);
            CHECK(objective == expected.objective);
            CHECK((values.head(ne).array() == expected.goal.equality.array()).all());
            CHECK((values.tail(rows - ne).array() == expected.goal.inequality.array()).all());
            CHECK((gradient - dense).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + scale));
            CHECK(objective2 == objective);
            CHECK((gradient2.array() == gradient.array()).all());
            // And evaluate() right after, at the point the solver saw: every row's own derivative.
            const ReducedProblem::Evaluation& full = kept.evaluate(x);
            CHECK((full.objective_gradient.array() == expected.objective_gradient.array()).all());
            CHECK((full.inequality_jacobian.array() == expected.inequality_jacobian.array()).all());
          }
        }
}
