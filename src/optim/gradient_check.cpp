#include "optim/gradient_check.h"

#include <algorithm>
#include <cmath>

namespace offsetopt {

namespace {

// A step h with x + h exactly representable, so the difference quotient divides by the true step.
double exact_step(double xi, const GradientCheckOptions& p) {
  const double h = p.relative_step * std::max(std::fabs(xi), p.step_floor);
  const double shifted = xi + h;
  return shifted - xi;
}

// Central-difference derivative along coordinate i from a callable value(point) -> VectorXd.
template <class Values>
Eigen::VectorXd difference(const Values& value, const Eigen::VectorXd& x, Eigen::Index i,
                           const GradientCheckOptions& p, int& evaluations) {
  const double h = exact_step(x(i), p);
  Eigen::VectorXd xs = x;
  auto at = [&](double offset) {
    xs(i) = x(i) + offset;
    ++evaluations;
    return value(xs);
  };
  const Eigen::VectorXd f1 = at(h);
  const Eigen::VectorXd fm1 = at(-h);
  if (p.order == 2) return (f1 - fm1) / (2.0 * h);
  const Eigen::VectorXd f2 = at(2.0 * h);
  const Eigen::VectorXd fm2 = at(-2.0 * h);
  return (8.0 * (f1 - fm1) - (f2 - fm2)) / (12.0 * h);
}

}  // namespace

std::string GradientCheckOptions::check() const {
  if (order != 2 && order != 4) return "order must be 2 or 4";
  if (!(relative_step > 0.0) || !std::isfinite(relative_step)) return "relative_step must be > 0";
  if (!(step_floor > 0.0) || !std::isfinite(step_floor)) return "step_floor must be > 0";
  if (!(tolerance >= 0.0)) return "tolerance must be >= 0";
  if (!(absolute_floor > 0.0)) return "absolute_floor must be > 0";
  return std::string();
}

GradientCheckResult check_gradient(const ObjectiveFunction& f, const Eigen::VectorXd& x,
                                   const GradientCheckOptions& params) {
  GradientCheckResult r;
  r.message = params.check();
  if (!r.message.empty()) return r;
  const Eigen::Index n = x.size();
  r.analytic = Eigen::VectorXd::Zero(n);
  r.numeric = Eigen::VectorXd::Zero(n);
  const double f0 = f(x, r.analytic);
  ++r.evaluations;
  r.finite = std::isfinite(f0) && r.analytic.allFinite();
  Eigen::VectorXd scratch(n);
  auto value = [&](const Eigen::VectorXd& xs) {
    scratch.setZero();
    Eigen::VectorXd out(1);
    out(0) = f(xs, scratch);
    return out;
  };
  for (Eigen::Index i = 0; i < n; ++i) r.numeric(i) = difference(value, x, i, params, r.evaluations)(0);
  r.finite = r.finite && r.numeric.allFinite();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double e = std::fabs(r.analytic(i) - r.numeric(i));
    if (e > r.max_abs_error || r.worst_index < 0) {
      r.max_abs_error = e;
      r.worst_index = static_cast<int>(i);
    }
  }
  const double scale = std::max({r.analytic.lpNorm<Eigen::Infinity>(),
                                 r.numeric.lpNorm<Eigen::Infinity>(), params.absolute_floor});
  r.normalized_error = n > 0 ? r.max_abs_error / scale : 0.0;
  r.passed = r.finite && r.normalized_error <= params.tolerance;
  return r;
}

JacobianCheckResult check_jacobian(const ConstraintFunction& c, int rows, const Eigen::VectorXd& x,
                                   const GradientCheckOptions& params) {
  JacobianCheckResult r;
  r.message = params.check();
  if (!r.message.empty()) return r;
  const Eigen::Index n = x.size();
  r.analytic = Eigen::MatrixXd::Zero(rows, n);
  r.numeric = Eigen::MatrixXd::Zero(rows, n);
  Eigen::VectorXd v0 = Eigen::VectorXd::Zero(rows);
  c(x, v0, r.analytic);
  ++r.evaluations;
  r.finite = v0.allFinite() && r.analytic.allFinite();
  Eigen::MatrixXd scratch(rows, n);
  auto value = [&](const Eigen::VectorXd& xs) {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(rows);
    scratch.setZero();
    c(xs, out, scratch);
    return out;
  };
  for (Eigen::Index i = 0; i < n; ++i) r.numeric.col(i) = difference(value, x, i, params, r.evaluations);
  r.finite = r.finite && r.numeric.allFinite();
  for (int k = 0; k < rows; ++k) {
    const double scale = std::max({r.analytic.row(k).lpNorm<Eigen::Infinity>(),
                                   r.numeric.row(k).lpNorm<Eigen::Infinity>(), params.absolute_floor});
    for (Eigen::Index i = 0; i < n; ++i) {
      const double e = std::fabs(r.analytic(k, i) - r.numeric(k, i));
      if (e > r.max_abs_error || r.worst_row < 0) {
        r.max_abs_error = e;
        r.worst_row = k;
        r.worst_col = static_cast<int>(i);
      }
      r.normalized_error = std::max(r.normalized_error, e / scale);
    }
  }
  r.passed = r.finite && r.normalized_error <= params.tolerance;
  return r;
}

}  // namespace offsetopt
