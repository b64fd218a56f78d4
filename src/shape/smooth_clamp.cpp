#include "shape/smooth_clamp.h"

namespace offsetopt {

namespace {

double ramp(double y, double tau, double& derivative) {
  if (y <= -tau) { derivative = 0.0; return 0.0; }
  if (y >= tau) { derivative = 1.0; return y; }
  const double shifted = y + tau;
  derivative = shifted / (2.0 * tau);
  return shifted * shifted / (4.0 * tau);
}

}  // namespace

double smooth_clamp(double x, double lo, double hi, double tau, double* slope, double* slope_lo) {
  double d_lo = 0.0, d_hi = 0.0;
  const double rise = ramp(x - lo, tau, d_lo) - ramp(x - hi, tau, d_hi);
  if (slope) *slope = d_lo - d_hi;
  if (slope_lo) *slope_lo = 1.0 - d_lo;
  // Mathematically in [lo, hi]; the min/max only removes rounding that would leave the band.
  const double value = lo + rise;
  return value < lo ? lo : (value > hi ? hi : value);
}

Eigen::VectorXd smooth_clamp(const Eigen::VectorXd& x, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                             double tau, Eigen::VectorXd* slope) {
  Eigen::VectorXd value(x.size());
  if (slope) slope->resize(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    double s = 0.0;
    value(i) = smooth_clamp(x(i), lo(i), hi(i), tau, &s);
    if (slope) (*slope)(i) = s;
  }
  return value;
}

}  // namespace offsetopt
