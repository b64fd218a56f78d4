// Mass properties against closed forms (boxes, tetrahedra, balls, tori), their invariances and
// scaling laws, and the additivity that makes a shell outer minus inner.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "mass/mass_properties.h"
#include "mass/surface_area.h"
#include "mass/volume_integrals.h"
#include "mass_test_helpers.h"
#include "mesh/primitives.h"

using namespace offsetopt;
using namespace offsetopt::test;

namespace {

// P of the box with side lengths (a, b, c) centred at `center`, from the textbook formulas.
Vector10d box_properties(const Eigen::Vector3d& sides, const Eigen::Vector3d& center) {
  const double a = sides.x(), b = sides.y(), c = sides.z(), m = a * b * c;
  Vector10d P;
  P << m, center.x(), center.y(), center.z(), m * (b * b + c * c) / 12.0, m * (a * a + c * c) / 12.0,
      m * (a * a + b * b) / 12.0, 0.0, 0.0, 0.0;
  return P;
}

// Largest error of the ten properties, each relative to a scale that suits it: the mass for m,
// a length for the centre, the largest moment for the inertia entries.
double property_error(const Vector10d& P, const Vector10d& expected, double length) {
  const double moment_scale = expected.segment<3>(kIxx).cwiseAbs().maxCoeff();
  double error = std::fabs(P(kMass) - expected(kMass)) / std::fabs(expected(kMass));
  for (int i = kCx; i <= kCz; ++i) error = std::max(error, std::fabs(P(i) - expected(i)) / length);
  for (int i = kIxx; i <= kIzx; ++i) error = std::max(error, std::fabs(P(i) - expected(i)) / moment_scale);
  return error;
}

}  // namespace

TEST_CASE("unit cube and boxes match the closed form, also 1e6 from the origin") {
  const Vector10d cube = mass_properties(make_box({0, 0, 0}, {1, 1, 1}));
  CHECK(property_error(cube, box_properties({1, 1, 1}, {0.5, 0.5, 0.5}), 1.0) < 1e-15);
  CHECK(cube(kIxx) == doctest::Approx(1.0 / 6.0).epsilon(1e-15));

  const Eigen::Vector3d sides(1.0, 2.0, 3.0);
  for (const double offset : {0.0, -17.25, 1e6}) {
    const Eigen::Vector3d lo(offset, offset + 0.5, offset - 3.0);
    const Mesh box = make_box(lo, lo + sides);
    const Vector10d expected = box_properties(sides, lo + 0.5 * sides);
    const double error = property_error(mass_properties(box), expected, sides.norm());
    MESSAGE("box at offset " << offset << ": largest relative error " << error);
    CHECK(error < 1e-13);
  }
  // The raw integrals themselves, far away: measured from the mean vertex (the box's centre).
  const VolumeIntegrals far = volume_integrals(make_box({1e6, 1e6, 1e6}, {1e6 + 1, 1e6 + 2, 1e6 + 3}));
  CHECK(far.values(kIntVolume) == doctest::Approx(6.0).epsilon(1e-15));
  CHECK(std::fabs(far.values(kIntX)) < 1e-12);
  CHECK(far.values(kIntXX) == doctest::Approx(6.0 / 12.0).epsilon(1e-14));
  CHECK(far.values(kIntZZ) == doctest::Approx(6.0 * 9.0 / 12.0).epsilon(1e-14));
}

TEST_CASE("tetrahedron matches the closed form") {
  // Corner tetrahedron (0, a e1, b e2, c e3): the Dirichlet integrals over the unit simplex
  // (∫1 = 1/6, ∫x = 1/24, ∫x² = 1/60, ∫xy = 1/120) scaled by the axis lengths.
  const double a = 2.0, b = 3.0, c = 5.0;
  Mesh tet;
  tet.V.resize(4, 3);
  tet.V << 0, 0, 0, a, 0, 0, 0, b, 0, 0, 0, c;
  tet.F.resize(4, 3);
  tet.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  REQUIRE(closed_and_oriented(tet));
  const double J = a * b * c, m = J / 6.0;
  const double cx = a / 4.0, cy = b / 4.0, cz = c / 4.0;
  const double Sxx = J * a * a / 60.0 - m * cx * cx, Syy = J * b * b / 60.0 - m * cy * cy,
               Szz = J * c * c / 60.0 - m * cz * cz;
  const double Sxy = J * a * b / 120.0 - m * cx * cy, Syz = J * b * c / 120.0 - m * cy * cz,
               Szx = J * c * a / 120.0 - m * cz * cx;
  Vector10d expected;
  expected << m, cx, cy, cz, Syy + Szz, Sxx + Szz, Sxx + Syy, -Sxy, -Syz, -Szx;
  const double error = property_error(mass_properties(tet), expected, 1.0);
  MESSAGE("tetrahedron: largest relative error " << error);
  CHECK(error < 1e-14);
  // The same tetrahedron rotated and moved far away.
  Rng rng(7);
  const Eigen::Matrix3d R = random_rotation(rng);
  const Eigen::Vector3d t(1e4, -2e4, 3e4);
  const Vector10d moved = mass_properties(transformed(tet, R, t));
  const Eigen::Vector3d c_moved = R * Eigen::Vector3d(cx, cy, cz) + t;
  // Rotating and moving rounds the input coordinates (ulp of 3e4 is 4e-12), nothing more.
  CHECK(moved(kMass) == doctest::Approx(m).epsilon(1e-11));
  CHECK((Eigen::Vector3d(moved(kCx), moved(kCy), moved(kCz)) - c_moved).norm() < 1e-10);
}

TEST_CASE("icosphere converges to the ball as it refines") {
  const double R = 1.7, volume = 4.0 / 3.0 * kPi * R * R * R, moment = 0.4 * volume * R * R;
  double previous_volume_error = 1e300, previous_moment_error = 1e300;
  for (int s = 1; s <= 5; ++s) {
    const Mesh ball = transformed(make_icosphere(R, s), Eigen::Matrix3d::Identity(), {3.0, -1.0, 2.0});
    const Vector10d P = mass_properties(ball);
    const double volume_error = std::fabs(P(kMass) - volume) / volume;
    double moment_error = 0.0;
    for (int i = kIxx; i <= kIzz; ++i) moment_error = std::max(moment_error, std::fabs(P(i) - moment) / moment);
    for (int i = kIxy; i <= kIzx; ++i) moment_error = std::max(moment_error, std::fabs(P(i)) / moment);
    MESSAGE("icosphere s=" << s << ": volume error " << volume_error << ", inertia error " << moment_error);
    CHECK(volume_error < previous_volume_error / 3.5);
    CHECK(moment_error < previous_moment_error / 3.5);
    CHECK((Eigen::Vector3d(P(kCx), P(kCy), P(kCz)) - Eigen::Vector3d(3.0, -1.0, 2.0)).norm() < 1e-13);
    previous_volume_error = volume_error;
    previous_moment_error = moment_error;
  }
  CHECK(previous_volume_error < 1e-3);
  CHECK(previous_moment_error < 2e-3);
}

TEST_CASE("torus converges to the closed form as it refines") {
  const double R = 3.0, r = 1.0, volume = 2.0 * kPi * kPi * R * r * r;
  const double Izz = volume * (R * R + 0.75 * r * r), Ixx = volume * (0.5 * R * R + 0.625 * r * r);
  double previous = 1e300;
  for (const int n : {16, 32, 64, 128}) {
    const Vector10d P = mass_properties(make_torus(R, r, 2 * n, n));
    const double error = std::max({std::fabs(P(kMass) - volume) / volume, std::fabs(P(kIzz) - Izz) / Izz,
                                   std::fabs(P(kIxx) - Ixx) / Ixx, std::fabs(P(kIyy) - Ixx) / Ixx,
                                   std::fabs(P(kIxy)) / Izz, std::fabs(P(kIyz)) / Izz, std::fabs(P(kIzx)) / Izz});
    MESSAGE("torus " << 2 * n << "x" << n << ": largest relative error " << error);
    CHECK(error < previous / 3.5);
    previous = error;
  }
  CHECK(previous < 1e-3);
}

TEST_CASE("invariance under translation and rotation") {
  Rng rng(2024);
  const Mesh mesh = make_torus(2.0, 0.7, 24, 12);
  const Vector10d P = mass_properties(mesh);
  const Eigen::Matrix3d I = inertia_tensor(P);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const Eigen::Vector3d t(rng.uniform(-100, 100), rng.uniform(-100, 100), rng.uniform(-100, 100));
    const Vector10d Q = mass_properties(transformed(mesh, R, t));
    CHECK(Q(kMass) == doctest::Approx(P(kMass)).epsilon(1e-13));
    const Eigen::Vector3d c = R * Eigen::Vector3d(P(kCx), P(kCy), P(kCz)) + t;
    CHECK((Eigen::Vector3d(Q(kCx), Q(kCy), Q(kCz)) - c).norm() < 1e-12);
    CHECK((inertia_tensor(Q) - R * I * R.transpose()).norm() < 1e-12 * I.norm());
  }
}

TEST_CASE("scaling laws: volume grows as s^3, inertia as s^5") {
  const Mesh mesh = make_capsule(0.8, 1.1, 24, 6, 4);
  const Vector10d P = mass_properties(mesh);
  for (const double s : {0.1, 3.0, 250.0}) {
    const Vector10d Q = mass_properties(transformed(mesh, s * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()));
    CHECK(Q(kMass) == doctest::Approx(s * s * s * P(kMass)).epsilon(1e-13));
    for (int i = kIxx; i <= kIzz; ++i) CHECK(Q(i) == doctest::Approx(s * s * s * s * s * P(i)).epsilon(1e-12));
    CHECK(surface_area(transformed(mesh, s * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero())) ==
          doctest::Approx(s * s * surface_area(mesh)).epsilon(1e-13));
  }
}

TEST_CASE("a shell is the outer solid minus the inner one: box minus an off-centre inner box") {
  const Eigen::Vector3d outer_lo(-1, -2, 0), outer_sides(4, 5, 6);
  const Eigen::Vector3d inner_lo(0.0, -1.0, 2.0), inner_sides(1.5, 2.0, 3.0);  // inside, off-centre
  const Mesh outer = make_box(outer_lo, outer_lo + outer_sides);
  const Mesh inner = make_box(inner_lo, inner_lo + inner_sides);
  // Closed form: masses and centres subtract; inertia by the parallel-axis theorem about the
  // shell's centre of mass.
  const Vector10d Po = box_properties(outer_sides, outer_lo + 0.5 * outer_sides);
  const Vector10d Pi = box_properties(inner_sides, inner_lo + 0.5 * inner_sides);
  const double m = Po(kMass) - Pi(kMass);
  const Eigen::Vector3d co = Po.segment<3>(kCx), ci = Pi.segment<3>(kCx);
  const Eigen::Vector3d c = (Po(kMass) * co - Pi(kMass) * ci) / m;
  auto shifted = [](const Vector10d& P, const Eigen::Vector3d& d) {  // inertia about a point at −d from the centre
    return Eigen::Matrix3d(inertia_tensor(P) + P(kMass) * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  const Eigen::Matrix3d I = shifted(Po, co - c) - shifted(Pi, ci - c);

  const Vector10d shell = mass_properties(subtract(volume_integrals(outer), volume_integrals(inner)));
  CHECK(shell(kMass) == doctest::Approx(m).epsilon(1e-14));
  CHECK((shell.segment<3>(kCx) - c).norm() < 1e-14 * outer_sides.norm());
  CHECK((inertia_tensor(shell) - I).norm() < 1e-13 * I.norm());
  CHECK(std::fabs(shell(kIzx)) > 1.0);  // the off-centre void makes products of inertia

  // add() is the inverse: shell + inner = outer, whatever the frames.
  const Vector10d back = mass_properties(add(subtract(volume_integrals(outer), volume_integrals(inner)),
                                             volume_integrals(inner, {10, 20, 30})));
  CHECK(property_error(back, Po, 1.0) < 1e-13);
  // The shell as one mesh (inner faces reversed) gives the same numbers.
  Mesh both;
  both.V.resize(16, 3);
  both.V << outer.V, inner.V;
  both.F.resize(24, 3);
  both.F << outer.F, (inner.F.array() + 8).matrix().rowwise().reverse();
  CHECK(property_error(mass_properties(both), shell, 1.0) < 1e-13);
}

TEST_CASE("shifting the frame of the integrals changes nothing physical") {
  const Mesh mesh = make_torus(2.0, 0.5, 20, 10);
  const VolumeIntegrals a = volume_integrals(mesh);
  const VolumeIntegrals b = volume_integrals(mesh, {10.0, -5.0, 3.0});
  const VolumeIntegrals shifted = shift_integrals(a, b.origin);
  CHECK((shifted.values - b.values).cwiseAbs().maxCoeff() < 1e-12 * b.values.cwiseAbs().maxCoeff());
  CHECK(property_error(mass_properties(a), mass_properties(b), 1.0) < 1e-13);
}

TEST_CASE("principal moments and axes of a rotated box") {
  Rng rng(11);
  const Eigen::Vector3d sides(3.0, 1.0, 2.0);
  const Mesh box = make_box(-0.5 * sides, 0.5 * sides);
  const Eigen::Matrix3d R = random_rotation(rng);
  const PrincipalInertia principal = principal_inertia(mass_properties(transformed(box, R, {5, 6, 7})));
  const Vector10d expected = box_properties(sides, Eigen::Vector3d::Zero());
  // The three box moments, ascending.
  Eigen::Vector3d moments(expected(kIxx), expected(kIyy), expected(kIzz));
  std::sort(moments.data(), moments.data() + 3);
  CHECK((principal.moments - moments).norm() < 1e-12 * moments.norm());
  // Box axis k (in the rotated frame R e_k) has moment expected(kIxx + k); it must match the
  // principal axis of that moment up to sign.
  for (int k = 0; k < 3; ++k) {
    const int slot = static_cast<int>(std::find(moments.data(), moments.data() + 3, expected(kIxx + k)) - moments.data());
    CHECK(std::fabs(std::fabs(principal.axes.col(slot).dot(R.col(k))) - 1.0) < 1e-12);
  }
  CHECK((principal.axes.transpose() * principal.axes - Eigen::Matrix3d::Identity()).norm() < 1e-13);
  CHECK(principal.axes.determinant() == doctest::Approx(1.0).epsilon(1e-13));
  for (int k = 0; k < 2; ++k) {
    Eigen::Index largest;
    principal.axes.col(k).cwiseAbs().maxCoeff(&largest);
    CHECK(principal.axes(largest, k) > 0.0);
  }
}
