// Hock–Schittkowski problems (W. Hock, K. Schittkowski, "Test Examples for Nonlinear Programming
// Codes", 1981; K. Schittkowski, "More test examples", 1987) with their published optima, solved
// by the augmented Lagrangian from the standard start points: objective to 1e-6 relative,
// constraints to 1e-8. Inequalities of the collection (c(x) ≥ 0) are written as −c(x) ≤ 0.
// All analytic derivatives are first checked against finite differences.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "optim/augmented_lagrangian.h"
#include "optim/gradient_check.h"

using namespace offsetopt;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct HsProblem {
  std::string name;
  ConstrainedProblem problem;
  VectorXd x0;
  double f_star;
  VectorXd x_star;  // empty when the collection gives it only to a few digits
};

VectorXd vec(std::initializer_list<double> v) {
  VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double d : v) out(i++) = d;
  return out;
}

HsProblem hs021() {
  HsProblem h;
  h.name = "HS021";
  auto& p = h.problem;
  p.num_variables = 2;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << 0.02 * x(0), 2.0 * x(1);
    return 0.01 * x(0) * x(0) + x(1) * x(1) - 100.0;
  };
  p.num_inequality = 1;  // 10 x1 − x2 − 10 ≥ 0
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = -(10.0 * x(0) - x(1) - 10.0);
    j << -10.0, 1.0;
  };
  p.lower = vec({2.0, -50.0});
  p.upper = vec({50.0, 50.0});
  h.x0 = vec({-1.0, -1.0});
  h.f_star = -99.96;
  h.x_star = vec({2.0, 0.0});
  return h;
}

HsProblem hs035() {
  HsProblem h;
  h.name = "HS035";
  auto& p = h.problem;
  p.num_variables = 3;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << -8.0 + 4.0 * x(0) + 2.0 * x(1) + 2.0 * x(2), -6.0 + 4.0 * x(1) + 2.0 * x(0),
        -4.0 + 2.0 * x(2) + 2.0 * x(0);
    return 9.0 - 8.0 * x(0) - 6.0 * x(1) - 4.0 * x(2) + 2.0 * x(0) * x(0) + 2.0 * x(1) * x(1) +
           x(2) * x(2) + 2.0 * x(0) * x(1) + 2.0 * x(0) * x(2);
  };
  p.num_inequality = 1;  // 3 − x1 − x2 − 2 x3 ≥ 0
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(0) + x(1) + 2.0 * x(2) - 3.0;
    j << 1.0, 1.0, 2.0;
  };
  p.lower = VectorXd::Zero(3);
  p.upper = VectorXd::Constant(3, kInf);
  h.x0 = vec({0.5, 0.5, 0.5});
  h.f_star = 1.0 / 9.0;
  h.x_star = vec({4.0 / 3.0, 7.0 / 9.0, 4.0 / 9.0});
  return h;
}

HsProblem hs071() {
  HsProblem h;
  h.name = "HS071";
  auto& p = h.problem;
  p.num_variables = 4;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    const double s = x(0) + x(1) + x(2);
    g << x(3) * s + x(0) * x(3), x(0) * x(3), x(0) * x(3) + 1.0, x(0) * s;
    return x(0) * x(3) * s + x(2);
  };
  p.num_equality = 1;  // Σ x_i² = 40
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x.squaredNorm() - 40.0;
    j.row(0) = 2.0 * x.transpose();
  };
  p.num_inequality = 1;  // x1 x2 x3 x4 ≥ 25
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = 25.0 - x(0) * x(1) * x(2) * x(3);
    j << -x(1) * x(2) * x(3), -x(0) * x(2) * x(3), -x(0) * x(1) * x(3), -x(0) * x(1) * x(2);
  };
  p.lower = VectorXd::Constant(4, 1.0);
  p.upper = VectorXd::Constant(4, 5.0);
  h.x0 = vec({1.0, 5.0, 5.0, 1.0});
  h.f_star = 17.0140173;
  return h;
}

HsProblem hs076() {
  HsProblem h;
  h.name = "HS076";
  auto& p = h.problem;
  p.num_variables = 4;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << 2.0 * x(0) - x(2) - 1.0, x(1) - 3.0, 2.0 * x(2) - x(0) + x(3) + 1.0, x(3) + x(2) - 1.0;
    return x(0) * x(0) + 0.5 * x(1) * x(1) + x(2) * x(2) + 0.5 * x(3) * x(3) - x(0) * x(2) +
           x(2) * x(3) - x(0) - 3.0 * x(1) + x(2) - x(3);
  };
  p.num_inequality = 3;
  p.inequality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(0) + 2.0 * x(1) + x(2) + x(3) - 5.0;
    c(1) = 3.0 * x(0) + x(1) + 2.0 * x(2) - x(3) - 4.0;
    c(2) = -x(1) - 4.0 * x(2) + 1.5;
    j << 1.0, 2.0, 1.0, 1.0, 3.0, 1.0, 2.0, -1.0, 0.0, -1.0, -4.0, 0.0;
  };
  p.lower = VectorXd::Zero(4);
  p.upper = VectorXd::Constant(4, kInf);
  h.x0 = vec({0.5, 0.5, 0.5, 0.5});
  h.f_star = -103.0 / 22.0;  // −4.681818181...
  h.x_star = vec({3.0 / 11.0, 23.0 / 11.0, 0.0, 6.0 / 11.0});
  return h;
}

HsProblem hs027() {
  HsProblem h;
  h.name = "HS027";
  auto& p = h.problem;
  p.num_variables = 3;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    const double a = x(1) - x(0) * x(0);
    g << 0.02 * (x(0) - 1.0) - 4.0 * x(0) * a, 2.0 * a, 0.0;
    return 0.01 * (x(0) - 1.0) * (x(0) - 1.0) + a * a;
  };
  p.num_equality = 1;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(0) + x(2) * x(2) + 1.0;
    j << 1.0, 0.0, 2.0 * x(2);
  };
  h.x0 = vec({2.0, 2.0, 2.0});
  h.f_star = 0.04;
  h.x_star = vec({-1.0, 1.0, 0.0});
  return h;
}

HsProblem hs039() {
  HsProblem h;
  h.name = "HS039";
  auto& p = h.problem;
  p.num_variables = 4;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << -1.0, 0.0, 0.0, 0.0;
    return -x(0);
  };
  p.num_equality = 2;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(1) - x(0) * x(0) * x(0) - x(2) * x(2);
    c(1) = x(0) * x(0) - x(1) - x(3) * x(3);
    j << -3.0 * x(0) * x(0), 1.0, -2.0 * x(2), 0.0, 2.0 * x(0), -1.0, 0.0, -2.0 * x(3);
  };
  h.x0 = vec({2.0, 2.0, 2.0, 2.0});
  h.f_star = -1.0;
  h.x_star = vec({1.0, 1.0, 0.0, 0.0});
  return h;
}

HsProblem hs040() {
  HsProblem h;
  h.name = "HS040";
  auto& p = h.problem;
  p.num_variables = 4;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    g << -x(1) * x(2) * x(3), -x(0) * x(2) * x(3), -x(0) * x(1) * x(3), -x(0) * x(1) * x(2);
    return -x(0) * x(1) * x(2) * x(3);
  };
  p.num_equality = 3;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x(0) * x(0) * x(0) + x(1) * x(1) - 1.0;
    c(1) = x(0) * x(0) * x(3) - x(2);
    c(2) = x(3) * x(3) - x(1);
    j << 3.0 * x(0) * x(0), 2.0 * x(1), 0.0, 0.0,  //
        2.0 * x(0) * x(3), 0.0, -1.0, x(0) * x(0),  //
        0.0, -1.0, 0.0, 2.0 * x(3);
  };
  h.x0 = vec({0.8, 0.8, 0.8, 0.8});
  h.f_star = -0.25;
  // x* = (2^(−1/3), 2^(−1/2), 2^(−11/12), 2^(−1/4)).
  h.x_star = vec({0.79370052598409973, 0.70710678118654752, 0.52973154717964763,
                  0.84089641525371454});
  return h;
}

HsProblem hs078() {
  HsProblem h;
  h.name = "HS078";
  auto& p = h.problem;
  p.num_variables = 5;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    for (int i = 0; i < 5; ++i) {
      double prod = 1.0;
      for (int k = 0; k < 5; ++k)
        if (k != i) prod *= x(k);
      g(i) = prod;
    }
    return x(0) * x(1) * x(2) * x(3) * x(4);
  };
  p.num_equality = 3;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    c(0) = x.squaredNorm() - 10.0;
    c(1) = x(1) * x(2) - 5.0 * x(3) * x(4);
    c(2) = x(0) * x(0) * x(0) + x(1) * x(1) * x(1) + 1.0;
    j.row(0) = 2.0 * x.transpose();
    j.row(1) << 0.0, x(2), x(1), -5.0 * x(4), -5.0 * x(3);
    j.row(2) << 3.0 * x(0) * x(0), 3.0 * x(1) * x(1), 0.0, 0.0, 0.0;
  };
  h.x0 = vec({-2.0, 1.5, 2.0, -1.0, -1.0});
  h.f_star = -2.91970041;
  return h;
}

HsProblem hs079() {
  HsProblem h;
  h.name = "HS079";
  auto& p = h.problem;
  p.num_variables = 5;
  p.objective = [](const VectorXd& x, VectorXd& g) {
    const double a = x(0) - 1.0, b = x(0) - x(1), c = x(1) - x(2), d = x(2) - x(3), e = x(3) - x(4);
    g << 2.0 * a + 2.0 * b, -2.0 * b + 2.0 * c, -2.0 * c + 4.0 * d * d * d,
        -4.0 * d * d * d + 4.0 * e * e * e, -4.0 * e * e * e;
    return a * a + b * b + c * c + d * d * d * d + e * e * e * e;
  };
  p.num_equality = 3;
  p.equality = [](const VectorXd& x, VectorXd& c, MatrixXd& j) {
    const double r2 = std::sqrt(2.0);
    c(0) = x(0) + x(1) * x(1) + x(2) * x(2) * x(2) - 2.0 - 3.0 * r2;
    c(1) = x(1) - x(2) * x(2) + x(3) + 2.0 - 2.0 * r2;
    c(2) = x(0) * x(4) - 2.0;
    j.row(0) << 1.0, 2.0 * x(1), 3.0 * x(2) * x(2), 0.0, 0.0;
    j.row(1) << 0.0, 1.0, -2.0 * x(2), 1.0, 0.0;
    j.row(2) << x(4), 0.0, 0.0, 0.0, x(0);
  };
  h.x0 = vec({2.0, 2.0, 2.0, 2.0, 2.0});
  h.f_star = 0.0787768209;
  return h;
}

std::vector<HsProblem> all_problems() {
  return {hs021(), hs035(), hs071(), hs076(), hs027(), hs039(), hs040(), hs078(), hs079()};
}

}  // namespace

TEST_CASE("hock-schittkowski: analytic derivatives agree with finite differences") {
  for (const HsProblem& h : all_problems()) {
    CAPTURE(h.name);
    const auto& p = h.problem;
    VectorXd x = h.x0 + VectorXd::LinSpaced(p.num_variables, 0.11, 0.37);  // a generic point
    CHECK(check_gradient(p.objective, x).passed);
    if (p.num_equality > 0) CHECK(check_jacobian(p.equality, p.num_equality, x).passed);
    if (p.num_inequality > 0) CHECK(check_jacobian(p.inequality, p.num_inequality, x).passed);
  }
}

TEST_CASE("hock-schittkowski: published optima to 1e-6 relative, constraints to 1e-8") {
  for (const HsProblem& h : all_problems()) {
    CAPTURE(h.name);
    std::string trace;
    AlOptions params;
    params.on_outer_iteration = [&trace](const AlIterationInfo& it) {
      trace += "\n  outer " + std::to_string(it.outer_iteration) + " f=" + std::to_string(it.f) +
               " viol=" + std::to_string(it.max_violation) + " stat=" +
               std::to_string(it.stationarity) + " compl=" + std::to_string(it.complementarity) +
               " rho=" + std::to_string(it.penalty) + " inner=" + to_string(it.inner_status) +
               "/" + std::to_string(it.inner_iterations);
    };
    const AlResult r = augmented_lagrangian_minimize(h.problem, h.x0, params);
    if (r.status != AlStatus::converged) MESSAGE(trace);
    MESSAGE(h.name << ": " << std::string(to_string(r.status)) << " f=" << r.f
                   << " f*=" << h.f_star << " viol=" << r.max_violation
                   << " stat=" << r.stationarity << " outer=" << r.outer_iterations
                   << " inner=" << r.inner_iterations << " evals=" << r.evaluations);
    CHECK(r.status == AlStatus::converged);
    CHECK(std::fabs(r.f - h.f_star) <= 1e-6 * std::fabs(h.f_star));
    CHECK(r.max_violation <= 1e-8);
    const auto& p = h.problem;
    for (int i = 0; i < p.num_variables; ++i) {
      if (p.lower.size()) CHECK(r.x(i) >= p.lower(i));
      if (p.upper.size()) CHECK(r.x(i) <= p.upper(i));
    }
    if (h.x_star.size()) CHECK((r.x - h.x_star).lpNorm<Eigen::Infinity>() < 1e-6);
    CHECK((r.inequality_multipliers.array() >= 0.0).all());
  }
}
