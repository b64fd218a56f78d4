#include "optimize/quadric_correction.h"

#include <algorithm>
#include <cmath>

namespace offsetopt {

Eigen::VectorXd goal_rows(const GoalValues& values) {
  Eigen::VectorXd rows(values.equality.size() + values.inequality.size());
  rows << values.equality, values.inequality;
  return rows;
}

Eigen::MatrixXd goal_row_jacobian(const GoalValues& values) {
  const Eigen::Index e = values.equality.size(), n = e + values.inequality.size();
  Eigen::MatrixXd R(n, 10);
  for (Eigen::Index r = 0; r < e; ++r) R.row(r) = values.equality_jacobian.row(r).tail<10>();
  for (Eigen::Index r = e; r < n; ++r) R.row(r) = values.inequality_jacobian.row(r - e).tail<10>();
  return R;
}

namespace {

// How far one row is from met.
double row_violation(const Eigen::VectorXd& rows, Eigen::Index r, Eigen::Index equalities) {
  return r < equalities ? std::fabs(rows(r)) : std::max(rows(r), 0.0);
}

}  // namespace

double goal_violation(const Eigen::VectorXd& rows, Eigen::Index equalities) {
  double squared = 0.0;
  for (Eigen::Index r = 0; r < rows.size(); ++r) {
    const double v = row_violation(rows, r, equalities);
    squared += v * v;
  }
  return std::sqrt(squared);
}

double step_back_fraction(const Eigen::VectorXd& best, const Eigen::VectorXd& now, Eigen::Index equalities) {
  Eigen::Index worst = 0;
  double largest = -1.0;
  for (Eigen::Index r = 0; r < best.size(); ++r) {
    const double v = row_violation(best, r, equalities);
    if (v > largest) {
      largest = v;
      worst = r;
    }
  }
  if (worst >= now.size()) return 0.5;
  const double a = best(worst), b = now(worst);
  if (a != 0.0 && a * b < 0.0) return std::min(0.9, std::max(0.1, a / (a - b)));
  return 0.5;
}

double observed_gain(const Eigen::VectorXd& before, const Eigen::VectorXd& predicted, const Eigen::VectorXd& after) {
  const Eigen::VectorXd expected = predicted - before, moved = after - before;
  const double norm = expected.squaredNorm();
  if (!(norm > 0.0)) return 1.0;
  return std::min(5.0, std::max(0.2, moved.dot(expected) / norm));
}

}  // namespace offsetopt
