// Primitives are closed and outward-oriented: their signed tetrahedron volume (computed here
// directly, independent of src/mass) approaches the closed-form volume.
#include <doctest/doctest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "../mesh_checks.h"
#include "mesh/primitives.h"
#include "util/det_math.h"

using namespace offsetopt;
using offsetopt::test::closed_and_oriented;

namespace {

double signed_volume(const Mesh& m) {
  double v = 0.0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

}  // namespace

TEST_CASE("icosphere volume converges to 4/3 pi R^3 from below") {
  const double R = 2.5, exact = 4.0 / 3.0 * kPi * R * R * R;
  double previous_error = 1e300;
  for (int s = 0; s <= 5; ++s) {
    const Mesh m = make_icosphere(R, s);
    CHECK(m.V.rows() == 10 * (1 << (2 * s)) + 2);
    CHECK(closed_and_oriented(m));
    const double error = exact - signed_volume(m);
    CHECK(error > 0.0);
    CHECK(error < previous_error / 3.0);
    previous_error = error;
  }
  CHECK(previous_error / exact < 2e-3);
}

TEST_CASE("box, torus, capsule and cylinder are closed with the expected volume") {
  const Mesh box = make_box({-1, 2, 3}, {2, 4, 7});
  CHECK(closed_and_oriented(box));
  CHECK(signed_volume(box) == doctest::Approx(3.0 * 2.0 * 4.0).epsilon(1e-14));

  const Mesh torus = make_torus(3.0, 1.0, 256, 128);
  CHECK(closed_and_oriented(torus));
  CHECK(signed_volume(torus) == doctest::Approx(2.0 * kPi * kPi * 3.0).epsilon(1e-3));

  const Mesh capsule = make_capsule(1.0, 2.0, 256, 64, 8);
  CHECK(closed_and_oriented(capsule));
  CHECK(signed_volume(capsule) == doctest::Approx(kPi * 4.0 + 4.0 / 3.0 * kPi).epsilon(1e-3));

  const Mesh cylinder = make_cylinder(0.5, -1.0, 3.0, 512, 4, 3);
  CHECK(closed_and_oriented(cylinder));
  CHECK(signed_volume(cylinder) == doctest::Approx(kPi * 0.25 * 4.0).epsilon(1e-4));
}

TEST_CASE("deterministic trigonometry matches libm to a few ulp") {
  for (int i = -2000; i <= 2000; ++i) {
    const double x = i * 0.01237;
    CHECK(std::fabs(det_sin(x) - std::sin(x)) <= 4e-16 * (1.0 + std::fabs(x)));
    CHECK(std::fabs(det_cos(x) - std::cos(x)) <= 4e-16 * (1.0 + std::fabs(x)));
    CHECK(std::fabs(det_atan(x) - std::atan(x)) <= 1e-15);
    CHECK(std::fabs(det_atan2(x, 1.3 - 0.001 * i) - std::atan2(x, 1.3 - 0.001 * i)) <= 1e-15);
  }
  for (int i = -100; i <= 100; ++i) {
    const double x = i * 0.01;
    CHECK(std::fabs(det_acos(x) - std::acos(x)) <= 1e-15);
    CHECK(std::fabs(det_asin(x) - std::asin(x)) <= 1e-15);
  }
}
