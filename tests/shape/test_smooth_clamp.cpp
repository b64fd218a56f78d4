// The smooth clamp is the identity inside the band, stays within [lo, hi], is monotone, C1,
// and its slope matches a central finite difference.
#include <doctest/doctest.h>

#include <cmath>

#include "shape/smooth_clamp.h"
#include "util/rng.h"

using namespace offsetopt;

TEST_CASE("smooth clamp: identity inside, bounded, monotone, slope = finite difference") {
  Rng rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const double lo = rng.uniform(-1.0, 1.0);
    const double hi = lo + (trial % 5 == 0 ? 0.0 : rng.uniform(0.0, 2.0));
    const double tau = rng.uniform(1e-3, 0.2);
    double previous = -1e300;
    for (int i = 0; i <= 400; ++i) {
      const double x = lo - 1.0 + (hi - lo + 2.0) * i / 400.0;
      double slope = 0.0;
      const double y = smooth_clamp(x, lo, hi, tau, &slope);
      CHECK(y >= lo);
      CHECK(y <= hi);
      CHECK(y >= previous - 4e-16 * (1.0 + std::fabs(y)));
      previous = y;
      CHECK(slope >= 0.0);
      CHECK(slope <= 1.0);
      if (x - lo >= tau && hi - x >= tau) CHECK(y == doctest::Approx(x).epsilon(1e-15));
      if (x <= lo - tau) CHECK(y == lo);
      const double h = 1e-6;
      const double fd = (smooth_clamp(x + h, lo, hi, tau) - smooth_clamp(x - h, lo, hi, tau)) / (2 * h);
      CHECK(std::fabs(fd - slope) <= 1e-6 / tau + 1e-8);
      double slope_lo = 0.0;
      smooth_clamp(x, lo, hi, tau, nullptr, &slope_lo);
      if (hi - lo > 2e-6) {  // moving lo by ±h must keep lo <= hi
        const double fd_lo = (smooth_clamp(x, lo + h, hi, tau) - smooth_clamp(x, lo - h, hi, tau)) / (2 * h);
        CHECK(std::fabs(fd_lo - slope_lo) <= 1e-6 / tau + 1e-8);
      }
    }
    if (hi == lo) CHECK(smooth_clamp(lo + 0.3, lo, hi, tau) == lo);
  }
}

TEST_CASE("smooth clamp: slope is continuous across the ramp ends") {
  const double lo = 0.0, hi = 1.0, tau = 0.1;
  for (double edge : {lo - tau, lo + tau, hi - tau, hi + tau}) {
    double below = 0.0, above = 0.0;
    smooth_clamp(edge - 1e-12, lo, hi, tau, &below);
    smooth_clamp(edge + 1e-12, lo, hi, tau, &above);
    CHECK(std::fabs(below - above) < 1e-10);
  }
  Eigen::VectorXd x(3), l(3), u(3), slope;
  x << -5, 0.5, 5;
  l << 0, 0, 0;
  u << 1, 1, 1;
  const Eigen::VectorXd y = smooth_clamp(x, l, u, tau, &slope);
  CHECK(y(0) == 0.0);
  CHECK(y(1) == 0.5);
  CHECK(y(2) == 1.0);
  CHECK(slope(1) == 1.0);
}
