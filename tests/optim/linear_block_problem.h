// A convex test problem with a large dense block of linear inequalities whose solution is known
// by construction (shared by tests/optim and bench/optim):
//   minimise  σ/2 (x − x_t)^T H (x − x_t)   s.t.  l ≤ A x ≤ u  (m rows),  lower ≤ x ≤ upper
// A has entries uniform in [−1, 1]. A point x* is drawn; a few rows get their upper side active
// at x* (ν > 0), a few their lower side (ν < 0), two variables sit on a bound; every other row
// has slack ≥ 0.05 on both sides (some sides infinite). x_t = x* − H^{-1}(A_act^T ν + bound
// multipliers)/σ makes x* a KKT point; H is positive definite, so x* is the unique minimiser.
#pragma once
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>

#include "optim/augmented_lagrangian.h"
#include "util/rng.h"

namespace offsetopt {

struct LinearBlockProblem {
  int n = 0;
  Eigen::MatrixXd a;                 // m by n
  Eigen::VectorXd row_lower, row_upper;
  Eigen::VectorXd lower, upper;      // variable bounds
  Eigen::MatrixXd h;                 // n by n, positive definite
  double sigma = 1.0;
  Eigen::VectorXd x_target;
  Eigen::VectorXd x_star;            // the solution
  Eigen::VectorXd row_multipliers;   // ν* (m), zero on inactive rows
  std::vector<int> upper_active, lower_active;
  double f_star = 0.0;

  double objective(const Eigen::VectorXd& x, Eigen::VectorXd& grad) const {
    const Eigen::VectorXd d = x - x_target;
    const Eigen::VectorXd hd = h * d;
    grad = sigma * hd;
    return 0.5 * sigma * d.dot(hd);
  }

  ConstrainedProblem problem() const {
    ConstrainedProblem p;
    p.num_variables = n;
    p.objective = [this](const Eigen::VectorXd& x, Eigen::VectorXd& g) { return objective(x, g); };
    p.lower = lower;
    p.upper = upper;
    p.linear_matrix = &a;
    p.linear_lower = row_lower;
    p.linear_upper = row_upper;
    return p;
  }
};

inline LinearBlockProblem make_linear_block_problem(int m, int n, std::uint64_t seed,
                                                    double sigma = 1e-2) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Rng rng(seed);
  LinearBlockProblem p;
  p.n = n;
  p.sigma = sigma;
  p.a.resize(m, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i) p.a(i, j) = rng.uniform(-1.0, 1.0);
  Eigen::MatrixXd g(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) g(i, j) = rng.uniform(-1.0, 1.0);
  p.h = g.transpose() * g / n + 0.2 * Eigen::MatrixXd::Identity(n, n);
  p.x_star.resize(n);
  for (int i = 0; i < n; ++i) p.x_star(i) = rng.uniform(-1.0, 1.0);
  p.lower = Eigen::VectorXd::Constant(n, -kInf);
  p.upper = Eigen::VectorXd::Constant(n, kInf);
  Eigen::VectorXd bound_mult = Eigen::VectorXd::Zero(n);
  // Variable 0 on its upper bound, variable 1 on its lower bound (multipliers of the right sign).
  p.upper(0) = p.x_star(0);
  bound_mult(0) = sigma * rng.uniform(0.5, 1.5);
  p.lower(1) = p.x_star(1);
  bound_mult(1) = -sigma * rng.uniform(0.5, 1.5);
  for (int i = 2; i < n; ++i) {
    p.lower(i) = p.x_star(i) - rng.uniform(0.5, 2.0);
    p.upper(i) = p.x_star(i) + rng.uniform(0.5, 2.0);
  }

  const Eigen::VectorXd r = p.a * p.x_star;
  p.row_lower.resize(m);
  p.row_upper.resize(m);
  p.row_multipliers = Eigen::VectorXd::Zero(m);
  const int active_each = std::max(1, std::min(10, n / 4));
  const int stride = m / (2 * active_each + 1);
  for (int i = 0; i < m; ++i) {
    p.row_lower(i) = r(i) - rng.uniform(0.05, 1.0);
    p.row_upper(i) = r(i) + rng.uniform(0.05, 1.0);
    const std::uint64_t kind = rng.below(4);
    if (kind == 0) p.row_lower(i) = -kInf;
    if (kind == 1) p.row_upper(i) = kInf;
  }
  for (int k = 0; k < 2 * active_each; ++k) {
    const int i = stride * (k + 1);
    if (k % 2 == 0) {
      p.row_upper(i) = r(i);
      p.row_lower(i) = r(i) - 1.0;
      p.row_multipliers(i) = sigma * rng.uniform(0.5, 1.5);
      p.upper_active.push_back(i);
    } else {
      p.row_lower(i) = r(i);
      p.row_upper(i) = kInf;
      p.row_multipliers(i) = -sigma * rng.uniform(0.5, 1.5);
      p.lower_active.push_back(i);
    }
  }
  // KKT: σ H (x* − x_t) + A^T ν + μ_bounds = 0.
  Eigen::VectorXd force = bound_mult;
  for (int i : p.upper_active) force += p.row_multipliers(i) * p.a.row(i).transpose();
  for (int i : p.lower_active) force += p.row_multipliers(i) * p.a.row(i).transpose();
  p.x_target = p.x_star + p.h.llt().solve(force) / sigma;
  Eigen::VectorXd grad(n);
  p.f_star = p.objective(p.x_star, grad);
  return p;
}

}  // namespace offsetopt
