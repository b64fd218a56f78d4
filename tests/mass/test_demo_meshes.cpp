// The demo meshes are valid inputs (closed, oriented, no self-intersection, 2k-6k vertices or,
// for top-coarse, 770 (paper figure 10's size), resting on z = 0, bit-identical on every call) and each is a real case for its goal: the
// solid fails it, and carving the hand-made cavity (which lies strictly inside) meets it.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "geometry_checks.h"
#include "mass/buoyancy.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/volume_integrals.h"
#include "mass_test_helpers.h"
#include "mesh/demo_meshes.h"

using namespace offsetopt;
using namespace offsetopt::test;

namespace {

int euler_characteristic(const Mesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  return static_cast<int>(mesh.V.rows()) - static_cast<int>(edges.size()) + static_cast<int>(mesh.F.rows());
}

Vector10d shell_properties(const Mesh& outer, const Mesh& cavity) {
  const Eigen::Vector3d origin = mean_vertex(outer);
  return mass_properties(subtract(volume_integrals(outer, origin), volume_integrals(cavity, origin)));
}

// The cavity is a valid closed surface strictly inside the outer one: no crossing triangles, a
// vertex inside, and every cavity vertex at least `min_wall` from the outer surface.
void check_cavity_inside(const std::string& name, const Mesh& outer, const Mesh& cavity, double min_wall) {
  CHECK(closed_and_oriented(cavity));
  CHECK(mass_properties(cavity)(kMass) > 0.0);
  CHECK(self_intersections(cavity) == 0);
  CHECK(crossings_between(outer, cavity) == 0);
  CHECK(winding_number(outer, cavity.V.row(0).transpose()) == doctest::Approx(1.0).epsilon(1e-9));
  const double wall = min_vertex_distance(cavity, outer);
  MESSAGE(name << ": thinnest wall at a cavity vertex " << wall << " (" << 100.0 * wall / bbox_diagonal(outer) << "% of the diagonal)");
  CHECK(wall >= min_wall);
}

}  // namespace

TEST_CASE("every demo mesh is a closed, oriented, self-intersection-free solid of 2k-6k vertices (top-coarse 700-800) on z = 0") {
  for (const auto& name : demo_mesh_names()) {
    CAPTURE(name);
    const Mesh mesh = make_demo_mesh(name);
    CHECK(mesh.V.rows() >= (name == "top-coarse" ? 700 : 2000));
    CHECK(mesh.V.rows() <= (name == "top-coarse" ? 800 : 6000));
    CHECK(closed_and_oriented(mesh));
    CHECK(mass_properties(mesh)(kMass) > 0.0);
    CHECK(mesh.V.col(2).minCoeff() == 0.0);
    const bool genus_one = name == "handle" || name == "torus";
    CHECK(euler_characteristic(mesh) == (genus_one ? 0 : 2));
    CHECK(self_intersections(mesh) == 0);
    const Mesh again = make_demo_mesh(name);
    CHECK((again.V.array() == mesh.V.array()).all());
    CHECK((again.F.array() == mesh.F.array()).all());
  }
  CHECK_THROWS_AS(make_demo_mesh("teapot"), std::invalid_argument);
  CHECK_THROWS_AS(make_demo_cavity("sphere"), std::invalid_argument);
}

TEST_CASE("bottle: the solid falls over, the bottle hollowed above a thick bottom stands") {
  const Mesh bottle = make_demo_mesh("bottle");
  const Vector10d solid = mass_properties(bottle);
  const Stability s = compute_stability(bottle, solid.segment<3>(kCx));
  // Flat circular base: a regular 64-gon around the z axis.
  CHECK(s.support_polygon.size() == 64);
  const double base_radius = s.support_polygon[0].norm();
  for (const auto& p : s.support_polygon) CHECK(p.norm() == doctest::Approx(base_radius).epsilon(1e-12));
  MESSAGE("bottle solid: com_margin " << s.com_margin << ", tipping angle " << s.tipping_angle_deg << " deg, base radius " << base_radius);
  CHECK(s.com_margin < -0.2 * base_radius);
  CHECK_FALSE(s.stands);

  const Mesh cavity = make_demo_cavity("bottle");
  check_cavity_inside("bottle", bottle, cavity, 0.009 * bbox_diagonal(bottle));
  const Vector10d shell = shell_properties(bottle, cavity);
  const Stability carved = compute_stability(bottle, shell.segment<3>(kCx));
  MESSAGE("bottle carved: void " << 1.0 - shell(kMass) / solid(kMass) << ", com_margin " << carved.com_margin << ", tipping angle "
                                 << carved.tipping_angle_deg << " deg");
  CHECK(carved.com_margin > 0.05 * base_radius);
  CHECK(carved.stands);
}

TEST_CASE("top: a single tip at the lowest point, off-axis solid with tilted axes, balanced by carving the lump side") {
  const Mesh top = make_demo_mesh("top");
  CHECK(top.V.row(0) == Eigen::RowVector3d(0, 0, 0));
  for (Eigen::Index i = 1; i < top.V.rows(); ++i) CHECK(top.V(i, 2) > 0.5);
  const Vector10d solid = mass_properties(top);
  const double radius = top.V.col(0).maxCoeff();
  MESSAGE("top solid: c = (" << solid(kCx) << ", " << solid(kCy) << ", " << solid(kCz) << "), Izx/Izz " << solid(kIzx) / solid(kIzz)
                             << ", Iyz/Izz " << solid(kIyz) / solid(kIzz));
  CHECK(solid(kCx) > 0.01 * radius);                      // off the tip axis...
  CHECK(std::fabs(solid(kIzx)) > 1e-3 * solid(kIzz));      // ...and tilted principal axes
  CHECK(std::fabs(solid(kCy)) < 1e-4 * radius);            // the lump is symmetric in y

  // The lens on the lump side is inside; removing all of it overshoots (cx < 0 and Izx > 0).
  // A copy scaled by s about its centre and moved up by dz is a two-parameter family: for each
  // dz, bisection on s puts the centre of mass on the tip axis; Izx is then monotone in dz, so a
  // second bisection zeroes it too. The result, checked to lie inside, balances the top.
  const Mesh lens = make_demo_cavity("top");
  check_cavity_inside("top", top, lens, 0.01 * bbox_diagonal(top));
  const Vector10d full = shell_properties(top, lens);
  CHECK(full(kCx) < 0.0);
  CHECK(full(kIzx) * solid(kIzx) < 0.0);
  const Eigen::Vector3d center = mass_properties(lens).segment<3>(kCx);
  auto moved_lens = [&](double scale, double dz) {
    return transformed(lens, scale * Eigen::Matrix3d::Identity(), (1.0 - scale) * center + Eigen::Vector3d(0, 0, dz));
  };
  auto scale_for_axis = [&](double dz) {
    double lo = 0.0, hi = 1.0;
    for (int step = 0; step < 45; ++step) {
      const double mid = 0.5 * (lo + hi);
      (shell_properties(top, moved_lens(mid, dz))(kCx) > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  double dz_lo = -1.0, dz_hi = 1.0;
  const double izx_lo = shell_properties(top, moved_lens(scale_for_axis(dz_lo), dz_lo))(kIzx);
  REQUIRE(izx_lo * shell_properties(top, moved_lens(scale_for_axis(dz_hi), dz_hi))(kIzx) < 0.0);
  for (int step = 0; step < 40; ++step) {
    const double mid = 0.5 * (dz_lo + dz_hi);
    const double izx = shell_properties(top, moved_lens(scale_for_axis(mid), mid))(kIzx);
    ((izx < 0.0) == (izx_lo < 0.0) ? dz_lo : dz_hi) = mid;
  }
  const double dz = 0.5 * (dz_lo + dz_hi), scale = scale_for_axis(dz);
  const Mesh balanced_lens = moved_lens(scale, dz);
  check_cavity_inside("top (balanced lens)", top, balanced_lens, 0.01 * bbox_diagonal(top));
  const Vector10d balanced = shell_properties(top, balanced_lens);
  MESSAGE("top: lens scaled " << scale << " and raised " << dz << " gives c = (" << balanced(kCx) << ", " << balanced(kCy)
                              << "), Izx/Izz " << balanced(kIzx) / balanced(kIzz) << ", Iyz/Izz " << balanced(kIyz) / balanced(kIzz)
                              << ", void " << 1.0 - balanced(kMass) / solid(kMass));
  CHECK(std::fabs(balanced(kCx)) < 1e-6 * radius);
  CHECK(std::fabs(balanced(kCy)) < 1e-4 * radius);                      // y-symmetric up to triangulation
  CHECK(std::fabs(balanced(kIzx)) < 1e-6 * balanced(kIzz));
  CHECK(std::fabs(balanced(kIyz)) < 1e-4 * balanced(kIzz));
}

TEST_CASE("rolypoly: hemisphere of radius 30 at the bottom, the solid's centre of mass above its centre, the carved one below") {
  const double r = 30.0;
  const Mesh toy = make_demo_mesh("rolypoly");
  CHECK(toy.V.row(0) == Eigen::RowVector3d(0, 0, 0));
  for (Eigen::Index i = 0; i < toy.V.rows(); ++i)
    if (toy.V(i, 2) <= r) CHECK((toy.V.row(i) - Eigen::RowVector3d(0, 0, r)).norm() == doctest::Approx(r).epsilon(1e-12));
  const Vector10d solid = mass_properties(toy);
  MESSAGE("rolypoly solid: cz " << solid(kCz) << " (hemisphere radius " << r << ")");
  CHECK(solid(kCz) > r + 0.1 * r);

  const Mesh cavity = make_demo_cavity("rolypoly");
  check_cavity_inside("rolypoly", toy, cavity, 0.009 * bbox_diagonal(toy));
  const Vector10d shell = shell_properties(toy, cavity);
  MESSAGE("rolypoly carved: void " << 1.0 - shell(kMass) / solid(kMass) << ", cz " << shell(kCz));
  CHECK(shell(kCz) < r - 0.05 * r);
}

TEST_CASE("buoy: sinks when solid in fluid 0.806, floats upright with a 20-50% void") {
  const double fluid = 0.806;
  const Mesh buoy = make_demo_mesh("buoy");
  const Vector10d solid = mass_properties(buoy);
  CHECK(solid(kMass) > fluid * solid(kMass));  // density 1 > 0.806: the solid sinks
  FloatingOptions options;
  options.fluid_density = fluid;
  CHECK(floating_equilibrium(buoy, solid(kMass), options).status == FloatingEquilibrium::Status::sinks);

  const Mesh cavity = make_demo_cavity("buoy");
  check_cavity_inside("buoy", buoy, cavity, 0.009 * bbox_diagonal(buoy));
  const Vector10d shell = shell_properties(buoy, cavity);
  const double void_fraction = 1.0 - shell(kMass) / solid(kMass);
  const FloatingEquilibrium floating = floating_equilibrium(buoy, shell(kMass), options);
  MESSAGE("buoy carved: void " << void_fraction << ", waterline " << floating.waterline << ", centre of buoyancy z "
                               << floating.center_of_buoyancy.z() << ", centre of mass z " << shell(kCz));
  CHECK(void_fraction > 0.2);
  CHECK(void_fraction < 0.5);
  REQUIRE(floating.status == FloatingEquilibrium::Status::floats);
  CHECK(floating.displaced_volume * fluid == doctest::Approx(shell(kMass)).epsilon(1e-9));
  CHECK(shell(kCz) < floating.center_of_buoyancy.z() - 1.0);
  CHECK((floating.center_of_buoyancy.head<2>() - shell.segment<2>(kCx)).norm() < 1e-9);
}

TEST_CASE("handle: genus one, lying flat, with a part thinner than two walls of 2% of the diagonal") {
  const Mesh handle = make_demo_mesh("handle");
  const double diagonal = bbox_diagonal(handle);
  // make_torus layout: ring i (one meridian circle) is vertices [32 i, 32 i + 32).
  double thinnest = 1e300, thickest = 0.0;
  for (Eigen::Index ring = 0; ring < handle.V.rows() / 32; ++ring) {
    double diameter = 0.0;
    for (int a = 0; a < 32; ++a)
      for (int b = a + 1; b < 32; ++b)
        diameter = std::max(diameter, (handle.V.row(32 * ring + a) - handle.V.row(32 * ring + b)).norm());
    thinnest = std::min(thinnest, diameter);
    thickest = std::max(thickest, diameter);
  }
  MESSAGE("handle: tube diameter from " << thinnest << " to " << thickest << ", diagonal " << diagonal);
  CHECK(thinnest < 2.0 * 0.02 * diagonal);
  CHECK(thickest > 0.15 * diagonal);
  const Stability s = compute_stability(handle, mass_properties(handle).segment<3>(kCx));
  CHECK(s.contact_vertex_count > 96);
  CHECK(s.stands);
}
