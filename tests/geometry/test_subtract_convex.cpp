// The boolean difference solid − convex cutter (geometry/subtract_convex.h) against independent
// figures: volumes against the analytic difference (box minus a prism through it or ending inside
// it: the removed volume is the prism's polygon area times the length inside), connectivity against
// tests/mesh_checks.h (each directed edge once, its opposite once), self-intersections by the exact
// pair rule (geometry/intersecting_faces.h), shells by mesh_shells, and a degenerate cutter refused.
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/bvh.h"
#include "geometry/cylinder_prism.h"
#include "geometry/intersecting_faces.h"
#include "geometry/mesh_shells.h"
#include "geometry/subtract_convex.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"
#include "../mesh_checks.h"

using namespace offsetopt;

namespace {

double volume(const Mesh& m) { return volume_integrals(m, Eigen::Vector3d(0.5, 0.5, 0.5)).values(0); }

double polygon_area(double r, int sides) { return 0.5 * sides * r * r * std::sin(2.0 * M_PI / sides); }

long long self_pairs(const Mesh& m) {
  const TriangleBvh bvh(m.V, m.F);
  return static_cast<long long>(self_intersections(bvh, 1000).pairs.size());
}

Mesh reversed(Mesh m) {
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) std::swap(m.F(f, 1), m.F(f, 2));
  return m;
}

}  // namespace

TEST_CASE("subtract_convex: a prism through a cube removes its polygon's area times the cube's height") {
  const Mesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  for (int sides : {5, 16, 32}) {
    const double r = 0.3;
    const Mesh prism = cylinder_prism(Eigen::Vector3d(0.45, 0.52, -0.5), Eigen::Vector3d(0.45, 0.52, 1.5), r, sides, 0.1);
    const SubtractResult cut = subtract_convex(cube, prism);
    REQUIRE(cut.status == SubtractStatus::ok);
    CHECK(cut.touched);
    CHECK(test::closed_and_oriented(cut.mesh));
    CHECK(volume(cut.mesh) == doctest::Approx(1.0 - polygon_area(r, sides)).epsilon(1e-12));
    CHECK(self_pairs(cut.mesh) == 0);
    // A through hole makes a torus: still one shell, Euler characteristic 0.
    const MeshShells shells = mesh_shells(cut.mesh, Eigen::Vector3d(0.5, 0.5, 0.5));
    CHECK(shells.count == 1);
    CHECK(cut.mesh.V.rows() - cut.mesh.F.rows() * 3 / 2 + cut.mesh.F.rows() == 0);
  }
}

TEST_CASE("subtract_convex: a tilted blind hole removes area times depth, and the cut is embedded") {
  const Mesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  // Enters through the top face (z = 1), ends at depth 0.4 measured along a tilted axis; the
  // entry cap is above the cube, so the removed part is the prism between the top face and the
  // bottom cap: its volume is the prism's cross-section times the axial length below z = 1, which
  // for a tilted axis is still area × (axial length) only if the top plane cuts every side edge:
  // the sheared ends have equal volume (Cavalieri along the axis).
  const Eigen::Vector3d bottom(0.5, 0.45, 0.6), dir = Eigen::Vector3d(0.1, 0.05, 1.0).normalized();
  const Eigen::Vector3d top = bottom + 1.0 * dir;
  const double r = 0.2;
  const int sides = 24;
  const Mesh prism = cylinder_prism(bottom, top, r, sides, 0.05);
  const SubtractResult cut = subtract_convex(cube, prism);
  REQUIRE(cut.status == SubtractStatus::ok);
  CHECK(test::closed_and_oriented(cut.mesh));
  CHECK(self_pairs(cut.mesh) == 0);
  // The plane z = 1 cuts the prism's axis at axial length (1 − 0.6)/dir.z from the bottom cap.
  const double depth = (1.0 - bottom.z()) / dir.z();
  CHECK(volume(cut.mesh) == doctest::Approx(1.0 - polygon_area(r, sides) * depth).epsilon(1e-12));
  CHECK(cut.cutter_faces_kept > 0);
}

TEST_CASE("subtract_convex: a drain hole into a cavity joins the two shells into one") {
  const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  const Mesh inner = reversed(make_box(Eigen::Vector3d(0.2, 0.2, 0.2), Eigen::Vector3d(0.8, 0.8, 0.8)));
  const Mesh solid = test::join(outer, inner);
  REQUIRE(mesh_shells(solid, Eigen::Vector3d(0.5, 0.5, 0.5)).count == 2);
  const double r = 0.1;
  const int sides = 32;
  // From below the floor (z < 0) into the cavity (z = 0.5): the removed part is the floor's 0.2.
  const Mesh prism = cylinder_prism(Eigen::Vector3d(0.43, 0.51, -0.3), Eigen::Vector3d(0.43, 0.51, 0.5), r, sides, 0.2);
  const SubtractResult cut = subtract_convex(solid, prism);
  REQUIRE(cut.status == SubtractStatus::ok);
  CHECK(test::closed_and_oriented(cut.mesh));
  CHECK(self_pairs(cut.mesh) == 0);
  CHECK(mesh_shells(cut.mesh, Eigen::Vector3d(0.5, 0.5, 0.5)).count == 1);
  CHECK(volume(cut.mesh) == doctest::Approx(1.0 - 0.216 - polygon_area(r, sides) * 0.2).epsilon(1e-12));
  // Faces away from the hole are copied unchanged.
  int copied = 0;
  for (int s : cut.source_face) copied += s >= 0 ? 1 : 0;
  CHECK(copied >= 20);
}

TEST_CASE("subtract_convex: a cutter with a cap in a solid vertex's plane is refused as degenerate") {
  const Mesh cube = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  const Mesh prism = cylinder_prism(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.5, 0.5, 1.0), 0.7, 8, 0.1);
  const SubtractResult cut = subtract_convex(cube, prism);
  CHECK(cut.status == SubtractStatus::degenerate);
  // A tiny shift makes it cut.
  const Mesh moved = cylinder_prism(Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.5, 0.5, 1.0 + 1e-9), 0.3, 8, 0.1);
  const SubtractResult ok = subtract_convex(cube, moved);
  REQUIRE(ok.status == SubtractStatus::ok);
  CHECK(test::closed_and_oriented(ok.mesh));
  CHECK(volume(ok.mesh) == doctest::Approx(1.0 - polygon_area(0.3, 8) * 0.5).epsilon(1e-9));
}

TEST_CASE("subtract_convex: a cutter away from the solid changes nothing, one around it removes all") {
  const Mesh sphere = make_icosphere(1.0, 2);
  const SubtractResult away = subtract_convex(sphere, cylinder_prism(Eigen::Vector3d(3, 0, 0), Eigen::Vector3d(4, 0, 0), 0.5, 8));
  REQUIRE(away.status == SubtractStatus::ok);
  CHECK_FALSE(away.touched);
  CHECK(away.mesh.F.rows() == sphere.F.rows());
  const SubtractResult all = subtract_convex(sphere, cylinder_prism(Eigen::Vector3d(0.01, 0.02, -2), Eigen::Vector3d(0.01, 0.02, 2), 3.0, 8));
  REQUIRE(all.status == SubtractStatus::ok);
  CHECK(all.mesh.F.rows() == 0);
}

TEST_CASE("subtract_convex: a sphere cut by many prism directions stays closed and embedded") {
  const Mesh sphere = make_icosphere(1.0, 3);
  for (int i = 0; i < 12; ++i) {
    const double a = 0.37 * i + 0.11, b = 0.23 * i + 0.05;
    const Eigen::Vector3d dir(std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b));
    const Mesh prism = cylinder_prism(0.6 * dir, 1.5 * dir, 0.25, 16, 0.01 * i);
    const SubtractResult cut = subtract_convex(sphere, prism);
    REQUIRE(cut.status == SubtractStatus::ok);
    CHECK(test::closed_and_oriented(cut.mesh));
    CHECK(self_pairs(cut.mesh) == 0);
    CHECK(volume(cut.mesh) < volume(sphere));
    CHECK(volume(cut.mesh) > volume(sphere) - polygon_area(0.25, 16) * 0.41);
  }
}
