#include "optim/cauchy_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace offsetopt {

CauchyPoint generalized_cauchy_point(const Eigen::VectorXd& x, const Eigen::VectorXd& g,
                                     const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                     const LbfgsMemory& memory) {
  const int n = static_cast<int>(x.size());
  const int p2 = 2 * memory.size();
  const double theta = memory.theta();
  const Eigen::MatrixXd& W = memory.w();
  const Eigen::MatrixXd& M = memory.m();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kEps = std::numeric_limits<double>::epsilon();

  CauchyPoint cp;
  cp.x = x;
  Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
  std::vector<char> fixed(n, 0);
  std::vector<std::pair<double, int>> breaks;
  for (int i = 0; i < n; ++i) {
    const bool at_lower = x(i) <= lower(i);
    const bool at_upper = x(i) >= upper(i);
    if (lower(i) == upper(i) || (at_lower && g(i) >= 0.0) || (at_upper && g(i) <= 0.0)) {
      fixed[i] = 1;  // cannot move along −g
      continue;
    }
    double t = kInf;
    if (g(i) < 0.0 && std::isfinite(upper(i))) t = (x(i) - upper(i)) / g(i);
    if (g(i) > 0.0 && std::isfinite(lower(i))) t = (x(i) - lower(i)) / g(i);
    d(i) = -g(i);
    if (t < kInf) breaks.emplace_back(t, i);
  }
  std::sort(breaks.begin(), breaks.end());

  Eigen::VectorXd p = W.transpose() * d;  // W^T d
  Eigen::VectorXd c = Eigen::VectorXd::Zero(p2);
  const double dtd = d.squaredNorm();
  double f1 = -dtd;                                  // model slope g^T d
  double f2 = theta * dtd - p.dot(M * p);            // model curvature d^T B d
  const double f2_org = f2;
  if (!(f2 > 0.0)) f2 = kEps * theta * std::max(dtd, std::numeric_limits<double>::min());
  double dt_min = -f1 / f2;
  double t_old = 0.0;

  for (const auto& [tb, b] : breaks) {
    const double dt = tb - t_old;
    if (dt_min < dt) break;  // the minimiser lies on the current segment
    // Move to breakpoint b and fix variable b at its bound.
    const double xb = d(b) > 0.0 ? upper(b) : lower(b);
    const double zb = xb - x(b);
    cp.x(b) = xb;
    c += dt * p;
    const double gb = g(b);
    const Eigen::VectorXd wb = W.row(b).transpose();
    const Eigen::VectorXd mwb = M * wb;  // M symmetric: w_b^T M v = (M w_b)^T v
    f1 = f1 + dt * f2 + gb * gb + theta * gb * zb - gb * mwb.dot(c);
    f2 = f2 - theta * gb * gb - 2.0 * gb * mwb.dot(p) - gb * gb * mwb.dot(wb);
    f2 = std::max(kEps * f2_org, f2);
    if (!(f2 > 0.0)) f2 = kEps * theta * std::max(dtd, std::numeric_limits<double>::min());
    p += gb * wb;
    d(b) = 0.0;
    fixed[b] = 1;
    t_old = tb;
    dt_min = -f1 / f2;
    ++cp.breakpoints;
  }

  if (!(dt_min > 0.0) || !std::isfinite(dt_min)) dt_min = 0.0;
  const double t_final = t_old + dt_min;
  for (int i = 0; i < n; ++i) {
    if (d(i) != 0.0) cp.x(i) = std::min(upper(i), std::max(lower(i), x(i) + t_final * d(i)));
  }
  c += dt_min * p;
  cp.c = c;
  for (int i = 0; i < n; ++i) {
    if (!fixed[i]) cp.free.push_back(i);
  }
  return cp;
}

}  // namespace offsetopt
