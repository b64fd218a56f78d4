#include "util/det_math.h"

#include <cmath>

namespace offsetopt {

namespace {

// Taylor polynomials on |r| <= pi/4; terms up to r^17 / r^18 leave < 1e-17 truncation error.
double sin_poly(double r) {
  const double r2 = r * r;
  double term = r, sum = r;
  for (int k = 1; k <= 9; ++k) {
    term = -term * r2 / static_cast<double>((2 * k) * (2 * k + 1));
    sum += term;
  }
  return sum;
}

double cos_poly(double r) {
  const double r2 = r * r;
  double term = 1.0, sum = 1.0;
  for (int k = 1; k <= 9; ++k) {
    term = -term * r2 / static_cast<double>((2 * k - 1) * (2 * k));
    sum += term;
  }
  return sum;
}

}  // namespace

void det_sincos(double x, double& s, double& c) {
  if (!std::isfinite(x)) { s = c = x - x; return; }
  // Cody-Waite reduction by pi/2 with a two-part constant; exact for |x| up to ~1e6, which
  // covers every angle the project forms (profiles, rotations, test perturbations).
  const double inv_half_pi = 0.63661977236758134308;
  const double half_pi_hi = 1.5707963267341256e+00;  // 33 significant bits
  const double half_pi_lo = 6.0771005065061922e-11;  // pi/2 - half_pi_hi
  const double q = std::nearbyint(x * inv_half_pi);
  const double r = (x - q * half_pi_hi) - q * half_pi_lo;
  const double sr = sin_poly(r), cr = cos_poly(r);
  long long quadrant = static_cast<long long>(q) & 3;
  switch (quadrant) {
    case 0: s = sr; c = cr; break;
    case 1: s = cr; c = -sr; break;
    case 2: s = -sr; c = -cr; break;
    default: s = -cr; c = sr; break;
  }
}

double det_sin(double x) { double s, c; det_sincos(x, s, c); return s; }
double det_cos(double x) { double s, c; det_sincos(x, s, c); return c; }

double det_atan(double x) {
  if (std::isnan(x)) return x;
  if (std::isinf(x)) return x > 0 ? kPi / 2 : -kPi / 2;
  const bool negative = x < 0;
  double a = negative ? -x : x;
  const bool inverted = a > 1.0;
  if (inverted) a = 1.0 / a;
  // Two half-angle steps: atan(a) = 2 atan(a / (1 + sqrt(1 + a^2))), so |a| <= tan(pi/16).
  for (int i = 0; i < 2; ++i) a = a / (1.0 + std::sqrt(1.0 + a * a));
  const double a2 = a * a;
  double power = a, sum = a;
  for (int k = 1; k <= 14; ++k) {
    power = -power * a2;
    sum += power / static_cast<double>(2 * k + 1);
  }
  double result = 4.0 * sum;
  if (inverted) result = kPi / 2 - result;
  return negative ? -result : result;
}

double det_atan2(double y, double x) {
  if (std::isnan(x) || std::isnan(y)) return x + y;
  if (x == 0.0 && y == 0.0) return 0.0;
  if (std::fabs(x) >= std::fabs(y)) {
    const double base = det_atan(y / x);
    if (x > 0) return base;
    return y >= 0 ? base + kPi : base - kPi;
  }
  const double base = det_atan(x / y);
  return y > 0 ? kPi / 2 - base : -kPi / 2 - base;
}

double det_acos(double x) {
  if (std::isnan(x)) return x;
  if (x > 1.0) x = 1.0;
  if (x < -1.0) x = -1.0;
  return det_atan2(std::sqrt((1.0 - x) * (1.0 + x)), x);
}

double det_asin(double x) {
  if (std::isnan(x)) return x;
  if (x > 1.0) x = 1.0;
  if (x < -1.0) x = -1.0;
  return det_atan2(x, std::sqrt((1.0 - x) * (1.0 + x)));
}

}  // namespace offsetopt
