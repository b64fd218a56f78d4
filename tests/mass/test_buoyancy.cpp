// Volume below a waterline and the floating equilibrium against closed forms.
#include <doctest/doctest.h>

#include <cmath>

#include "mass/buoyancy.h"
#include "mass/mass_properties.h"
#include "mass_test_helpers.h"
#include "mesh/primitives.h"

using namespace offsetopt;
using namespace offsetopt::test;

TEST_CASE("the part of a box below a plane, and a box floating at the density ratio") {
  const Mesh box = make_box({-1, 2, 0}, {3, 5, 4});  // 4 x 3 x 4
  const Vector10d below = mass_properties(volume_integrals_below(box, 1.5));
  CHECK(below(kMass) == doctest::Approx(4.0 * 3.0 * 1.5).epsilon(1e-14));
  CHECK(below(kCx) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(below(kCy) == doctest::Approx(3.5).epsilon(1e-14));
  CHECK(below(kCz) == doctest::Approx(0.75).epsilon(1e-14));
  CHECK(below(kIzz) == doctest::Approx(18.0 * (16.0 + 9.0) / 12.0).epsilon(1e-13));
  CHECK(volume_integrals_below(box, -1.0).values(kIntVolume) == 0.0);
  CHECK(volume_integrals_below(box, 9.0).values(kIntVolume) == doctest::Approx(48.0).epsilon(1e-14));

  FloatingOptions options;
  options.fluid_density = 1.6;  // a solid box of density 1 floats with 1/1.6 of its height under
  const FloatingEquilibrium f = floating_equilibrium(box, 48.0, options);
  REQUIRE(f.status == FloatingEquilibrium::Status::floats);
  CHECK(f.waterline == doctest::Approx(4.0 / 1.6).epsilon(1e-11));
  CHECK(f.center_of_buoyancy.z() == doctest::Approx(2.0 / 1.6).epsilon(1e-11));
  CHECK(f.iterations < 60);
  options.fluid_density = 0.9;
  CHECK(floating_equilibrium(box, 48.0, options).status == FloatingEquilibrium::Status::sinks);
  options.fluid_density = -1.0;
  CHECK(options.check() == "fluid_density must be a positive number");
  CHECK_THROWS_AS(floating_equilibrium(box, 48.0, options), std::invalid_argument);
}

TEST_CASE("a spherical cap below a plane converges to pi h^2 (3R - h) / 3") {
  const double R = 2.0, h = 1.3;
  const double exact = kPi * h * h * (3.0 * R - h) / 3.0;
  double previous = 1e300;
  for (int s = 2; s <= 5; ++s) {
    const double error = std::fabs(volume_integrals_below(make_icosphere(R, s), h - R).values(kIntVolume) - exact) / exact;
    MESSAGE("cap, icosphere s=" << s << ": relative error " << error);
    CHECK(error < previous / 3.0);
    previous = error;
  }
  CHECK(previous < 2e-3);
}
