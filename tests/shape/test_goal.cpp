// Goal values agree with the mass-property module on a real shell (box minus an offset inner
// box), and their derivatives with central finite differences of the same functions.
#include <doctest/doctest.h>

#include <cmath>

#include "mass/mass_properties.h"
#include "mesh/primitives.h"
#include "shape/goal.h"

using namespace offsetopt;

namespace {

struct Shell {
  Vector10d outer, inner;
};

Shell off_centre_shell() {
  const Mesh outer = make_box({-0.3, -0.2, 0.0}, {0.4, 0.25, 0.6});
  const Mesh inner = make_box({-0.1, -0.15, 0.1}, {0.35, 0.1, 0.5});
  return {volume_integrals(outer, Eigen::Vector3d::Zero()).values, volume_integrals(inner, Eigen::Vector3d::Zero()).values};
}

GoalSpec spec_for(GoalKind kind) {
  GoalSpec spec;
  spec.kind = kind;
  spec.support_polygon = {{-0.3, -0.2}, {0.4, -0.2}, {0.4, 0.25}, {-0.3, 0.25}};
  spec.margin = 0.01;
  spec.fill_density = 0.8;
  spec.axis_point = {0.01, -0.02, 0.3};
  spec.epsilon = 0.005;
  spec.target_volume = 0.05;
  spec.fluid_density = 0.7;
  return spec;
}

}  // namespace

TEST_CASE("goal values match the mass-property module") {
  const Shell s = off_centre_shell();
  VolumeIntegrals shell;
  shell.values = s.outer - s.inner;
  const Vector10d P = mass_properties(shell);

  const GoalValues stand = evaluate_goal(spec_for(GoalKind::stand), s.outer, s.inner);
  CHECK(stand.objective == doctest::Approx(P(kCx) * P(kCx) + P(kCy) * P(kCy) + P(kCz)).epsilon(1e-14));
  REQUIRE(stand.inequality.size() == 5);
  // Edge 0 runs along y = -0.2 (inward +y): margin - (cy + 0.2).
  CHECK(stand.inequality(0) == doctest::Approx(0.01 - (P(kCy) + 0.2)).epsilon(1e-14));
  CHECK(stand.inequality(1) == doctest::Approx(0.01 - (0.4 - P(kCx))).epsilon(1e-14));

  const GoalValues spin = evaluate_goal(spec_for(GoalKind::spin), s.outer, s.inner);
  REQUIRE(spin.equality.size() == 4);
  CHECK(spin.equality(2) == doctest::Approx(P(kIzx) / P(kIzz)).epsilon(1e-12));
  CHECK(spin.equality(3) == doctest::Approx(P(kIyz) / P(kIzz)).epsilon(1e-12));

  const GoalValues vol = evaluate_goal(spec_for(GoalKind::volume), s.outer, s.inner);
  CHECK(vol.equality(0) == doctest::Approx((s.inner(0) - 0.05) / 0.05).epsilon(1e-14));

  const GoalValues flt = evaluate_goal(spec_for(GoalKind::floating), s.outer, s.inner);
  CHECK(flt.equality(0) == doctest::Approx((0.7 * s.outer(0) - P(kMass)) / s.outer(0)).epsilon(1e-14));
  CHECK(flt.equality(1) == doctest::Approx(P(kCx) - s.outer(1) / s.outer(0)).epsilon(1e-14));

  // Filling the void with density 1 gives back the solid box: its centre is the box centre.
  GoalSpec full = spec_for(GoalKind::stand_filled);
  full.fill_density = 1.0;
  const GoalValues filled = evaluate_goal(full, s.outer, s.inner);
  const double cx = 0.05, cy = 0.025, cz = 0.3;
  CHECK(filled.objective == doctest::Approx(P(kCx) * P(kCx) + P(kCy) * P(kCy) + P(kCz) + cx * cx + cy * cy + cz).epsilon(1e-13));
}

TEST_CASE("goal derivatives match central finite differences for every goal") {
  const Shell s = off_centre_shell();
  for (GoalKind kind : {GoalKind::stand, GoalKind::stand_filled, GoalKind::roly_poly, GoalKind::spin, GoalKind::volume,
                        GoalKind::floating}) {
    CAPTURE(to_string(kind));
    const GoalSpec spec = spec_for(kind);
    CHECK(check_goal_spec(spec).empty());
    const GoalValues at = evaluate_goal(spec, s.outer, s.inner);
    CHECK(static_cast<std::size_t>(at.equality.size()) == goal_equality_names(spec).size());
    CHECK(static_cast<std::size_t>(at.inequality.size()) == goal_inequality_names(spec).size());
    for (int j = 0; j < 20; ++j) {
      Vector10d out_p = s.outer, out_m = s.outer, in_p = s.inner, in_m = s.inner;
      const double h = 1e-7 * (1.0 + std::fabs(j < 10 ? s.outer(j) : s.inner(j - 10)));
      if (j < 10) { out_p(j) += h; out_m(j) -= h; } else { in_p(j - 10) += h; in_m(j - 10) -= h; }
      const GoalValues plus = evaluate_goal(spec, out_p, in_p), minus = evaluate_goal(spec, out_m, in_m);
      const double scale = 1.0 + at.objective_gradient.cwiseAbs().maxCoeff();
      CHECK(std::fabs((plus.objective - minus.objective) / (2 * h) - at.objective_gradient(j)) <= 1e-6 * scale);
      for (Eigen::Index r = 0; r < at.equality.size(); ++r) {
        const double fd = (plus.equality(r) - minus.equality(r)) / (2 * h);
        CHECK(std::fabs(fd - at.equality_jacobian(r, j)) <= 1e-6 * (1.0 + at.equality_jacobian.row(r).cwiseAbs().maxCoeff()));
      }
      for (Eigen::Index r = 0; r < at.inequality.size(); ++r) {
        const double fd = (plus.inequality(r) - minus.inequality(r)) / (2 * h);
        CHECK(std::fabs(fd - at.inequality_jacobian(r, j)) <= 1e-6 * (1.0 + at.inequality_jacobian.row(r).cwiseAbs().maxCoeff()));
      }
    }
  }
}

TEST_CASE("goal spec validation names the problem") {
  GoalSpec spec = spec_for(GoalKind::stand);
  spec.support_polygon.resize(2);
  CHECK(check_goal_spec(spec).find("support polygon") != std::string::npos);
  spec = spec_for(GoalKind::floating);
  spec.fluid_density = 1.2;
  CHECK(check_goal_spec(spec).find("fluid density") != std::string::npos);
  GoalKind kind;
  CHECK(parse_goal_kind("roly-poly", kind));
  CHECK(kind == GoalKind::roly_poly);
  CHECK_FALSE(parse_goal_kind("fly", kind));
}

TEST_CASE("a goal ignores the integrals beyond goal_integral_rows: exact zeros there, same values when they change or are NaN") {
  const Shell s = off_centre_shell();
  for (GoalKind kind : {GoalKind::stand, GoalKind::stand_filled, GoalKind::roly_poly, GoalKind::spin, GoalKind::volume,
                        GoalKind::floating}) {
    CAPTURE(to_string(kind));
    const GoalSpec spec = spec_for(kind);
    const int used = goal_integral_rows(spec);
    REQUIRE((used == 1 || used == 4 || used == 10));
    const GoalValues at = evaluate_goal(spec, s.outer, s.inner);
    Vector10d outer = s.outer, inner = s.inner;
    for (int j = used; j < 10; ++j) {
      outer(j) *= 1.7;
      inner(j) *= 0.3;
    }
    const GoalValues moved = evaluate_goal(spec, outer, inner);
    CHECK(moved.objective == at.objective);
    CHECK((moved.equality.array() == at.equality.array()).all());
    CHECK((moved.inequality.array() == at.inequality.array()).all());
    // NaN there (what the optimiser's inner evaluations pass, shape/reduced_problem.cpp): values and
    // every derivative the same, bit for bit.
    for (int j = used; j < 10; ++j) outer(j) = inner(j) = std::nan("");
    const GoalValues unknown = evaluate_goal(spec, outer, inner);
    CHECK(unknown.objective == at.objective);
    CHECK((unknown.objective_gradient.array() == at.objective_gradient.array()).all());
    CHECK((unknown.equality.array() == at.equality.array()).all());
    CHECK((unknown.inequality.array() == at.inequality.array()).all());
    CHECK((unknown.equality_jacobian.array() == at.equality_jacobian.array()).all());
    CHECK((unknown.inequality_jacobian.array() == at.inequality_jacobian.array()).all());
    for (int j = 0; j < 20; ++j) {
      if (j % 10 < used) continue;
      CAPTURE(j);
      CHECK(at.objective_gradient(j) == 0.0);
      for (Eigen::Index r = 0; r < at.equality.size(); ++r) CHECK(at.equality_jacobian(r, j) == 0.0);
      for (Eigen::Index r = 0; r < at.inequality.size(); ++r) CHECK(at.inequality_jacobian(r, j) == 0.0);
    }
  }
}
