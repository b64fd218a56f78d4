// Forward-mode derivatives agree with central finite differences on a formula shaped like the
// spin goal (ratios, squares and a square root of the 2x2 inertia block's discriminant).
#include <doctest/doctest.h>

#include <cmath>

#include "util/dual.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

template <class T>
T spin_like(const T& ixx, const T& iyy, const T& ixy, const T& izz, const T& m, const T& cz) {
  using std::sqrt;
  const T root = sqrt((ixx - iyy) * (ixx - iyy) + 4.0 * ixy * ixy);
  const T ia = 0.5 * (ixx + iyy - root), ib = 0.5 * (ixx + iyy + root);
  return m * cz + (ia / izz) * (ia / izz) + (ib / izz) * (ib / izz) - (-cz) / m;
}

}  // namespace

TEST_CASE("dual numbers match central finite differences") {
  Rng rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    double x[6];
    for (double& v : x) v = rng.uniform(0.5, 2.0);
    x[2] = rng.uniform(-0.5, 0.5);
    using D = Dual<6>;
    D d[6];
    for (int j = 0; j < 6; ++j) d[j] = D::variable(x[j], j);
    const D result = spin_like(d[0], d[1], d[2], d[3], d[4], d[5]);
    CHECK(result.value == doctest::Approx(spin_like(x[0], x[1], x[2], x[3], x[4], x[5])).epsilon(1e-15));
    for (int j = 0; j < 6; ++j) {
      double plus[6], minus[6];
      for (int i = 0; i < 6; ++i) plus[i] = minus[i] = x[i];
      const double h = 1e-6;
      plus[j] += h;
      minus[j] -= h;
      const double fd = (spin_like(plus[0], plus[1], plus[2], plus[3], plus[4], plus[5]) -
                         spin_like(minus[0], minus[1], minus[2], minus[3], minus[4], minus[5])) / (2 * h);
      CHECK(result.grad[static_cast<std::size_t>(j)] == doctest::Approx(fd).epsilon(1e-7));
    }
  }
}
