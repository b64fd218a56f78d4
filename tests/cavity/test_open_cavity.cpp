// Openings through a cavity (cavity/open_cavity.h) against independent figures: a spherical
// shell's drain hole removes the analytic volume of a cylinder through the shell (within the
// prism's and the icosphere's facet error); a box with two spherical cavities gets one automatic
// hole per cavity, at that cavity's lowest vertex (found here by a plain scan), and the result is
// one closed, embedded piece; the void joined to the outside is checked by a flood fill on a grid;
// a channel for `z>V` opens a closed box cavity, and moves off a centroid line without room (a
// cup's central post) to the widest line; a sphere region opens a shell at the surface point
// nearest its centre; the cut below a plane keeps the analytic volume.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cavity/open_cavity.h"
#include "cavity/printable_solid.h"
#include "geometry/bvh.h"
#include "geometry/intersecting_faces.h"
#include "geometry/mesh_shells.h"
#include "geometry/point_in_solid.h"
#include "mass/volume_integrals.h"
#include "mesh/primitives.h"
#include "../mesh_checks.h"
#include "../outside_cells.h"

using namespace offsetopt;

namespace {

Mesh translated(Mesh m, const Eigen::Vector3d& by) {
  m.V.rowwise() += by.transpose();
  return m;
}

double volume(const Mesh& m) { return volume_integrals(m).values(0); }

long long self_pairs(const Mesh& m) {
  const TriangleBvh bvh(m.V, m.F);
  return static_cast<long long>(self_intersections(bvh, 1000).pairs.size());
}

// Whether the cell of `probe` is reached from the outside by a flood fill of cells of spacing h.
bool void_reaches_outside(const Mesh& solid, const Eigen::Vector3d& probe, double h) {
  const test::OutsideCells cells = test::outside_cells(solid, h);
  return cells.outside[cells.index_of(probe)] != 0;
}

// The cavity opened for `region` with `wall`: required to succeed with exactly one opening.
OpenedCavity opened_once(const Mesh& outer, const Mesh& cavity, double wall, const std::string& region) {
  OpenCavityOptions options;
  options.wall = wall;
  REQUIRE(parse_fix_region(region, options.opening).empty());
  OpenedCavity opened = open_cavity(outer, cavity, options);
  REQUIRE(opened.ok);
  REQUIRE(opened.openings.size() == 1);
  return opened;
}

}  // namespace

TEST_CASE("open_cavity: a drain hole through a spherical shell removes a cylinder's slab of it") {
  const double R = 1.0, r = 0.8, a = 0.1;
  const Mesh outer = make_icosphere(R, 5), cavity = make_icosphere(r, 5);
  OpenCavityOptions options;
  options.wall = 0.2;
  options.holes.push_back({Eigen::Vector3d(0.3, 0.2, -0.5), a});
  const OpenedCavity opened = open_cavity(outer, cavity, options);
  REQUIRE(opened.ok);
  CHECK(test::closed_and_oriented(opened.solid));
  CHECK(self_pairs(opened.solid) == 0);
  CHECK(opened.pieces_before == 2);
  CHECK(opened.pieces_after == 1);
  // The removed part: the prism (its polygon's area) from the inner to the outer sphere along a
  // radial axis, ∫ (√(R²−ρ²) − √(r²−ρ²)) dA over the disc of radius a, scaled by the polygon's
  // share of the disc.
  const double removed = volume(hollow_solid(outer, cavity)) - volume(opened.solid);
  const double cylinder = 2.0 * M_PI / 3.0 * ((R * R * R - std::pow(R * R - a * a, 1.5)) - (r * r * r - std::pow(r * r - a * a, 1.5)));
  const double polygon_share = 32 * std::sin(2 * M_PI / 32) / (2 * M_PI);
  // The icosphere's facets (level 5: ~0.06% of the radius deep) and a cap slightly inside the
  // inner sphere's facets bound the difference.
  CHECK(removed == doctest::Approx(cylinder * polygon_share).epsilon(0.02));
  CHECK(void_reaches_outside(opened.solid, Eigen::Vector3d(0.0, 0.0, 0.0), 0.05));
  CHECK_FALSE(void_reaches_outside(hollow_solid(outer, cavity), Eigen::Vector3d(0.0, 0.0, 0.0), 0.05));
}

TEST_CASE("open_cavity: automatic drain holes, one per cavity shell, at its lowest vertex") {
  const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(6, 3, 3));
  const Mesh first = translated(make_icosphere(1.0, 3), Eigen::Vector3d(1.5, 1.5, 1.4));
  const Mesh second = translated(make_icosphere(0.8, 3), Eigen::Vector3d(4.3, 1.4, 1.7));
  const Mesh cavity = test::join(first, second);
  OpenCavityOptions options;
  options.wall = 0.3;
  options.auto_holes = true;
  options.hole_radius = 0.15;
  const OpenedCavity opened = open_cavity(outer, cavity, options);
  REQUIRE(opened.ok);
  CHECK(opened.cavity_shells == 2);
  REQUIRE(opened.openings.size() == 2);
  CHECK(test::closed_and_oriented(opened.solid));
  CHECK(self_pairs(opened.solid) == 0);
  CHECK(mesh_shells(opened.solid, Eigen::Vector3d(3, 1.5, 1.5)).count == 1);
  for (const Mesh* shell : {&first, &second}) {
    Eigen::Index low = 0;
    shell->V.col(2).minCoeff(&low);
    const Eigen::Vector3d lowest = shell->V.row(low).transpose();
    bool found = false;
    for (const CutOpening& o : opened.openings) {
      // The hole starts in the void within half its radius of the lowest vertex (moved along the
      // inward normal; the prism is also moved 1e-5 of its radius sideways, cavity/open_cavity.h)
      // and leaves straight down through the floor (z = 0), the nearest wall.
      const Eigen::Vector3d axis = (o.outer - o.inner).normalized();
      if ((o.inner - lowest).norm() <= 0.5 * o.radius + 1e-4 && o.inner.z() > lowest.z())
        found = found || (axis.z() < -0.99 && o.outer.z() < 0.0);
    }
    CHECK(found);
    CHECK(void_reaches_outside(opened.solid, lowest + Eigen::Vector3d(0, 0, 0.3), 0.1));
  }
}

TEST_CASE("open_cavity: a channel for z>V opens a box's cavity, keeping the wall around it") {
  const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 2, 4));
  const Mesh cavity = translated(make_icosphere(0.7, 3), Eigen::Vector3d(1.03, 0.98, 2.0));
  const double wall = 0.25;
  const OpenedCavity opened = opened_once(outer, cavity, wall, "z>3.5");
  // The box's section is the 2 × 2 square centred at (1, 1): room 1, radius at most 1 − wall,
  // shrunk by 0.8 steps until the channel's end fits in the spherical cavity (radius 0.7).
  CHECK(opened.openings[0].radius == doctest::Approx(0.6));
  CHECK(opened.openings[0].inner.z() < 2.7);
  CHECK(test::closed_and_oriented(opened.solid));
  CHECK(self_pairs(opened.solid) == 0);
  REQUIRE(opened.spill_height);
  CHECK(*opened.spill_height == doctest::Approx(4.0));
  CHECK(void_reaches_outside(opened.solid, Eigen::Vector3d(1.03, 0.98, 2.0), 0.1));
}

TEST_CASE("open_cavity: a channel for z>V moves off a centroid line without room, to the widest line") {
  // A cup of revolution (radius 2, rim at z = 4.05, inner wall radius 1, floor at 3.2) with a post of
  // radius 0.3 up its middle, over a cylindrical cavity (radius 1.7, z in [0.3, 2.7]). The line
  // through the section's centroid runs up the post, 0.3 from the surface: too little for the
  // wall 0.25 and a quarter more. The widest vertical line runs through the cup's wall, half-way
  // between radius 1 and 2 (room 0.5), and leaves the surface at the rim, passing the post by
  // 1.2; one through the cup's inside would pass the post and the inner wall by 0.35 at most.
  const Mesh outer = make_revolution({{0.0, 0.0}, {2.0, 0.0}, {2.0, 4.05}, {1.0, 4.05}, {1.0, 3.2}, {0.3, 3.2}, {0.3, 4.5}, {0.0, 4.5}}, 96);
  const Mesh cavity = make_cylinder(1.7, 0.3, 2.7, 96, 4, 4);
  for (const Mesh* m : {&outer, &cavity}) REQUIRE(test::closed_and_oriented(*m));
  const double wall = 0.25;
  const OpenedCavity opened = opened_once(outer, cavity, wall, "z>3");
  const Eigen::Vector3d axis = opened.openings[0].inner;
  const double from_middle = std::hypot(axis.x(), axis.y());
  CHECK(from_middle > 1.0 + wall);
  CHECK(from_middle < 2.0 - wall);
  CHECK(opened.openings[0].radius <= 0.5 - wall + 1e-9);
  CHECK(test::closed_and_oriented(opened.solid));
  CHECK(self_pairs(opened.solid) == 0);
  CHECK(void_reaches_outside(opened.solid, Eigen::Vector3d(0.0, 0.0, 1.5), 0.1));
}

TEST_CASE("open_cavity: a sphere region opens a spherical shell at the surface point nearest its centre") {
  // Shell radii 5 and 3 about the origin, the region a ball of radius 2 about (0, 0, 5.5): the
  // nearest surface point is the pole (0, 0, 5), the region reaches √(4 − 0.25) = 1.94 across the
  // surface there, so the hole's radius is 0.97 (less where the void is narrower, never more).
  const Mesh outer = make_icosphere(5.0, 4), cavity = make_icosphere(3.0, 4);
  const double wall = 0.5;
  const OpenedCavity opened = opened_once(outer, cavity, wall, "sphere:0,0,5.5,2");
  const CutOpening& hole = opened.openings[0];
  CHECK(hole.kind == "opening");
  CHECK(hole.radius <= 0.5 * std::sqrt(4.0 - 0.25) + 1e-12);
  CHECK(hole.radius >= 0.25 * wall);
  // Along the z axis (through both poles; moved sideways by 1e-5 of the radius), from the void out
  // past the region.
  CHECK(std::hypot(hole.inner.x(), hole.inner.y()) < 2e-5 * hole.radius);
  CHECK(std::hypot(hole.outer.x(), hole.outer.y()) < 2e-5 * hole.radius);
  CHECK(hole.inner.z() > 2.0);
  CHECK(hole.inner.z() < 3.0);
  CHECK(hole.outer.z() > 5.0);
  CHECK(test::closed_and_oriented(opened.solid));
  CHECK(self_pairs(opened.solid) == 0);
  CHECK(void_reaches_outside(opened.solid, Eigen::Vector3d(0.0, 0.0, 0.0), 0.2));
}

TEST_CASE("cut_by_plane: a box below a plane keeps the analytic volume") {
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  Mesh below;
  REQUIRE(cut_by_plane(box, 2, 1.25, false, below));
  CHECK(test::closed_and_oriented(below));
  CHECK(volume(below) == doctest::Approx(2.5).epsilon(1e-8));
  Mesh above;
  REQUIRE(cut_by_plane(make_icosphere(1.0, 3), 2, 0.3, true, above));
  CHECK(test::closed_and_oriented(above));
  CHECK(volume(above) > 0.0);
}
