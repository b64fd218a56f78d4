// Finite-difference checks of analytic gradients (ObjectiveFunction, optim/lbfgsb.h) and
// Jacobians (ConstraintFunction, optim/augmented_lagrangian.h), for every objective of the
// project. Each coordinate i is perturbed by h_i = relative_step · max(|x_i|, step_floor),
// rounded so that x_i ± h_i is exact, and differentiated by central differences:
//   order 2:  (f(x+h) − f(x−h)) / 2h                                       error O(h²)
//   order 4:  (8(f(x+h) − f(x−h)) − (f(x+2h) − f(x−2h))) / 12h            error O(h⁴)
// The error reported is normalised: ‖analytic − numeric‖_∞ / max(‖analytic‖_∞, ‖numeric‖_∞,
// absolute_floor) for a gradient, and the largest such ratio over the rows of a Jacobian (each
// constraint has its own scale). Kinks within 2h of x (clamps, max) legitimately fail the test.
#pragma once
#include <string>

#include <Eigen/Core>

#include "optim/augmented_lagrangian.h"
#include "optim/lbfgsb.h"

namespace offsetopt {

struct GradientCheckOptions {
  int order = 4;                // 2 or 4
  double relative_step = 1e-3;  // ~ε^(1/5) for order 4; use ~1e-6 (≈ ε^(1/3)) for order 2
  double step_floor = 1.0;      // lower bound of the scale of x_i in the step (units of x)
  double tolerance = 1e-6;      // passed when the normalised error ≤ tolerance
  double absolute_floor = 1e-300;  // denominator floor of the normalised error

  // Empty when valid, else what is wrong. The checks below return passed = false with this message.
  std::string check() const;
};

struct GradientCheckResult {
  bool passed = false;
  bool finite = true;         // every value seen was finite
  Eigen::VectorXd analytic;   // n
  Eigen::VectorXd numeric;    // n
  double max_abs_error = 0.0;
  double normalized_error = 0.0;
  int worst_index = -1;       // coordinate of the largest absolute error
  int evaluations = 0;
  std::string message;        // invalid parameters
};

GradientCheckResult check_gradient(const ObjectiveFunction& f, const Eigen::VectorXd& x,
                                   const GradientCheckOptions& params = GradientCheckOptions());

struct JacobianCheckResult {
  bool passed = false;
  bool finite = true;
  Eigen::MatrixXd analytic;  // rows by n
  Eigen::MatrixXd numeric;   // rows by n
  double max_abs_error = 0.0;
  double normalized_error = 0.0;  // worst row
  int worst_row = -1;
  int worst_col = -1;
  int evaluations = 0;
  std::string message;
};

JacobianCheckResult check_jacobian(const ConstraintFunction& c, int rows, const Eigen::VectorXd& x,
                                   const GradientCheckOptions& params = GradientCheckOptions());

}  // namespace offsetopt
