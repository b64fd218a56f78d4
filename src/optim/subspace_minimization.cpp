#include "optim/subspace_minimization.h"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace offsetopt {

SubspaceStep subspace_minimization(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                   const LbfgsMemory& memory, const CauchyPoint& cauchy) {
  SubspaceStep step;
  step.x_bar = cauchy.x;
  const int nf = static_cast<int>(cauchy.free.size());
  const int p2 = 2 * memory.size();
  if (p2 == 0 || nf == 0) return step;

  const double theta = memory.theta();
  const Eigen::MatrixXd& W = memory.w();
  const Eigen::VectorXd mc = memory.m() * cauchy.c;

  Eigen::MatrixXd wz(nf, p2);
  Eigen::VectorXd r(nf);
  for (int k = 0; k < nf; ++k) {
    const int i = cauchy.free[k];
    wz.row(k) = W.row(i);
    r(k) = g(i) + theta * (cauchy.x(i) - x(i)) - W.row(i).dot(mc);
  }
  const Eigen::MatrixXd kmat = memory.middle_inverse() - (wz.transpose() * wz) / theta;
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(kmat);
  if (lu.rank() < p2) {
    step.ok = false;
    return step;
  }
  const Eigen::VectorXd v = lu.solve(wz.transpose() * r);
  step.direction = -r / theta - (wz * v) / (theta * theta);
  if (!step.direction.allFinite() || !v.allFinite()) {
    step.ok = false;
    return step;
  }
  const Eigen::VectorXd& du = step.direction;

  // v3.0: try the projection of the subspace minimiser onto the box.
  Eigen::VectorXd xp = cauchy.x;
  bool hit_bound = false;
  for (int k = 0; k < nf; ++k) {
    const int i = cauchy.free[k];
    const double target = cauchy.x(i) + du(k);
    xp(i) = std::min(upper(i), std::max(lower(i), target));
    if (xp(i) == lower(i) || xp(i) == upper(i)) hit_bound = true;
  }
  if (!hit_bound) {
    step.x_bar = xp;
    return step;
  }
  double slope = 0.0;
  for (int i = 0; i < static_cast<int>(x.size()); ++i) slope += (xp(i) - x(i)) * g(i);
  if (!(slope > 0.0)) {
    step.x_bar = xp;
    step.projected = true;
    return step;
  }

  // Original L-BFGS-B: truncate the step at the first bound met by a free variable.
  double alpha = 1.0;
  int blocking = -1;
  for (int k = 0; k < nf; ++k) {
    const int i = cauchy.free[k];
    const double dk = du(k);
    double limit = alpha;
    if (dk < 0.0 && std::isfinite(lower(i))) {
      const double room = lower(i) - cauchy.x(i);
      if (room >= 0.0) {
        limit = 0.0;
      } else if (dk * alpha < room) {
        limit = room / dk;
      }
    } else if (dk > 0.0 && std::isfinite(upper(i))) {
      const double room = upper(i) - cauchy.x(i);
      if (room <= 0.0) {
        limit = 0.0;
      } else if (dk * alpha > room) {
        limit = room / dk;
      }
    }
    if (limit < alpha) {
      alpha = limit;
      blocking = k;
    }
  }
  step.truncation = alpha;
  for (int k = 0; k < nf; ++k) {
    const int i = cauchy.free[k];
    if (k == blocking) {
      step.x_bar(i) = du(k) > 0.0 ? upper(i) : lower(i);
    } else {
      step.x_bar(i) = std::min(upper(i), std::max(lower(i), cauchy.x(i) + alpha * du(k)));
    }
  }
  return step;
}

}  // namespace offsetopt
