// The carvable cells (cavity/carvable_cells.h) of a box, whose distance field is known in closed
// form (inside: the distance to the nearest face plane; outside: the distance to the box), checked
// cell by cell on the same grid: the inner set is exactly the cells whose 8 nodes are at least
// wall + margin deep, the outer set exactly those whose centre is at least wall − r deep; with the
// band, the cells whose centre is outside within outer_max, above the kept base. And the cube integrals
// against a product rule.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "cavity/carvable_cells.h"
#include "cavity/contour_cavity.h"
#include "geometry/aabb.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/grid_winding.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

// Signed distance to the box [lo, hi], positive inside.
double box_signed_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const Eigen::Vector3d below = lo - p, above = p - hi;
  const Eigen::Vector3d out = below.cwiseMax(above).cwiseMax(0.0);
  if (out.squaredNorm() > 0.0) return -out.norm();
  return std::min((p - lo).minCoeff(), (hi - p).minCoeff());
}

bool contains(const std::vector<std::int64_t>& list, std::int64_t cell) {
  return std::binary_search(list.begin(), list.end(), cell);
}

// The six lists by the header's definitions, every distance an unbounded nearest-face query at the
// point itself (no block, bound or gathered faces): what the block passes must reproduce exactly.
struct CellLists {
  std::vector<std::int64_t> inner, outer, mid, band_inner, band_outer, skin_outer;
};

CellLists brute_force_cells(const Mesh& mesh, const TriangleBvh& bvh, const CarvableCellsOptions& o, const CarvableCells& cells) {
  const NodeGrid& g = cells.grid;
  const double h = g.spacing, r = 0.5 * std::sqrt(3.0) * h;
  NodeGrid centres = g;
  centres.origin = g.origin + Eigen::Vector3d::Constant(0.5 * h);
  const std::vector<std::int8_t> node_winding = grid_winding(mesh, g, 1), centre_winding = grid_winding(mesh, centres, 1);
  std::vector<char> deep(static_cast<std::size_t>(g.node_count()), 0);
  if (o.strict)
    for (std::int64_t v = 0; v < g.node_count(); ++v)
      deep[static_cast<std::size_t>(v)] = node_winding[static_cast<std::size_t>(v)] >= 1 &&
                                          closest_point(bvh, g.position(v)).distance >= o.wall + cells.margin;
  const double level = o.wall - r - (o.band ? o.outer_max : 0.0);
  const double base = o.ground_z + 2.0 * o.outer_max + o.ground_tol;
  CellLists out;
  for (std::int64_t k = 0; k + 1 < g.nz; ++k)
    for (std::int64_t j = 0; j + 1 < g.ny; ++j)
      for (std::int64_t i = 0; i + 1 < g.nx; ++i) {
        const std::int64_t cell = g.index(i, j, k);
        bool whole = o.strict;
        for (int c = 0; c < 8 && whole; ++c) whole = deep[static_cast<std::size_t>(g.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)))];
        const bool inside = centre_winding[static_cast<std::size_t>(cell)] >= 1;
        const Eigen::Vector3d p = cells.centre(cell);
        const double d = closest_point(bvh, p).distance;
        if (whole) out.inner.push_back(cell);
        if (whole || (inside ? d >= level : (level < 0.0 && d < -level))) out.outer.push_back(cell);
        if (inside && d >= o.wall) out.mid.push_back(cell);
        if (!o.band) continue;
        if (!inside && d < o.outer_max && p.z() - 0.5 * h >= base) out.band_inner.push_back(cell);
        const bool above_contacts = p.z() + 0.5 * h > o.ground_z + o.ground_tol;
        if ((inside ? d < r : d < o.outer_max + r) && above_contacts) out.band_outer.push_back(cell);
        if (inside && d < o.outer_max + r && above_contacts) out.skin_outer.push_back(cell);
      }
  return out;
}

void check_against_brute_force(const Mesh& mesh, CarvableCellsOptions o) {
  const TriangleBvh bvh(mesh.V, mesh.F);
  const CarvableCells cells = carvable_cells(mesh, bvh, o);
  REQUIRE(cells.ok);
  const CellLists expected = brute_force_cells(mesh, bvh, o, cells);
  CHECK(cells.inner == expected.inner);
  CHECK(cells.outer == expected.outer);
  CHECK(cells.mid == expected.mid);
  CHECK(cells.band_inner == expected.band_inner);
  CHECK(cells.band_outer == expected.band_outer);
  CHECK(cells.skin_outer == expected.skin_outer);
  CHECK(!expected.outer.empty());
  CHECK(!expected.mid.empty());
  if (o.strict) CHECK(!expected.inner.empty());
  if (o.band) CHECK(!expected.band_inner.empty());
  o.threads = 1;
  const CarvableCells serial = carvable_cells(mesh, bvh, o);
  CHECK(serial.outer == cells.outer);
  CHECK(serial.mid == cells.mid);
  CHECK(serial.band_outer == cells.band_outer);
}

}  // namespace

TEST_CASE("carvable cells: every list equals the per-point nearest-face reading on curved meshes") {
  CarvableCellsOptions o;
  SUBCASE("a coarse icosphere (edges and vertices nearest), strict") {
    o.wall = 1.0;
    check_against_brute_force(make_icosphere(8.0, 2), o);
  }
  SUBCASE("a torus, strict, with the band and a margin") {
    const Mesh torus = make_torus(7.0, 2.5, 40, 20);
    o.wall = 0.7;
    o.margin_cells = 0.5;
    o.band = true;
    o.outer_max = 0.6;
    o.ground_z = torus.V.col(2).minCoeff();
    o.ground_tol = 0.01;
    check_against_brute_force(torus, o);
  }
  SUBCASE("a capsule, the mid reading on a finer grid") {
    o.wall = 0.8;
    o.cells_per_wall = 3.0;
    o.strict = false;
    check_against_brute_force(make_capsule(4.0, 5.0, 24, 6, 8), o);
  }
  SUBCASE("a fine icosphere with an outer band wider than the wall (outside cells matter)") {
    const Mesh sphere = make_icosphere(6.0, 4);
    o.wall = 0.5;
    o.cells_per_wall = 2.0;
    o.band = true;
    o.outer_max = 1.2;
    o.ground_z = sphere.V.col(2).minCoeff();
    o.ground_tol = 0.05;
    check_against_brute_force(sphere, o);
  }
}

TEST_CASE("carvable cells: a box's inner and outer sets match its distance field cell by cell") {
  const Eigen::Vector3d lo(0.3, -0.2, 0.0), hi(10.3, 6.8, 4.0);
  const Mesh box = make_box(lo, hi);
  const TriangleBvh bvh(box.V, box.F);
  CarvableCellsOptions o;
  o.wall = 0.6;
  const CarvableCells cells = carvable_cells(box, bvh, o);
  REQUIRE(cells.ok);
  const NodeGrid& g = cells.grid;
  CHECK(g.spacing == doctest::Approx(0.4));
  // The inner reading keeps the contour's own node test, so its cells are ones the contour writes whole.
  CHECK(cells.margin == doctest::Approx(cavity_node_level(0.6, 0.4, o.margin_cells, bounding_box(box.V)) - 0.6));
  const double r = 0.5 * std::sqrt(3.0) * g.spacing;
  std::int64_t inner = 0, outer = 0;
  for (std::int64_t k = 0; k + 1 < g.nz; ++k)
    for (std::int64_t j = 0; j + 1 < g.ny; ++j)
      for (std::int64_t i = 0; i + 1 < g.nx; ++i) {
        const std::int64_t cell = g.index(i, j, k);
        bool whole = true;
        for (int c = 0; c < 8; ++c) {
          const Eigen::Vector3d p(g.x(i + (c & 1)), g.y(j + ((c >> 1) & 1)), g.z(k + ((c >> 2) & 1)));
          whole = whole && box_signed_distance(p, lo, hi) >= o.wall + cells.margin;
        }
        const bool may = whole || box_signed_distance(cells.centre(cell), lo, hi) >= o.wall - r;
        CHECK(contains(cells.inner, cell) == whole);
        CHECK(contains(cells.outer, cell) == may);
        inner += whole;
        outer += may;
      }
  CHECK(inner == static_cast<std::int64_t>(cells.inner.size()));
  CHECK(outer == static_cast<std::int64_t>(cells.outer.size()));
  CHECK(inner > 1000);
  CHECK(outer > inner);
  CHECK(std::is_sorted(cells.outer.begin(), cells.outer.end()));
  // The volumes bracket the box shrunk by the wall.
  const double shrunk = (10.0 - 1.2) * (7.0 - 1.2) * (4.0 - 1.2);
  CHECK(static_cast<double>(inner) * cells.cell_volume() < shrunk);
  CHECK(static_cast<double>(outer) * cells.cell_volume() > shrunk);
  CHECK(cells.band_inner.empty());
  // Without the node pass: no inner reading, the same outer and mid ones.
  o.strict = false;
  const CarvableCells centres_only = carvable_cells(box, bvh, o);
  REQUIRE(centres_only.ok);
  CHECK(centres_only.inner.empty());
  CHECK(centres_only.outer == cells.outer);
  CHECK(centres_only.mid == cells.mid);
  CHECK(!cells.mid.empty());
}

TEST_CASE("carvable cells: the outer band of a box, above the kept base, with the same answer on one thread") {
  const Eigen::Vector3d lo(0.0, 0.0, 0.0), hi(6.0, 5.0, 8.0);
  const Mesh box = make_box(lo, hi);
  const TriangleBvh bvh(box.V, box.F);
  CarvableCellsOptions o;
  o.wall = 0.5;
  o.band = true;
  o.outer_max = 1.0;
  o.ground_z = 0.0;
  o.ground_tol = 0.01;
  const CarvableCells cells = carvable_cells(box, bvh, o);
  REQUIRE(cells.ok);
  const NodeGrid& g = cells.grid;
  const double h = g.spacing;
  std::int64_t band = 0;
  for (std::int64_t k = 0; k + 1 < g.nz; ++k)
    for (std::int64_t j = 0; j + 1 < g.ny; ++j)
      for (std::int64_t i = 0; i + 1 < g.nx; ++i) {
        const std::int64_t cell = g.index(i, j, k);
        const Eigen::Vector3d c = cells.centre(cell);
        const double d = -box_signed_distance(c, lo, hi);
        const bool expected = d > 0.0 && d < o.outer_max && c.z() - 0.5 * h >= 2.0 * o.outer_max + o.ground_tol;
        CHECK(contains(cells.band_inner, cell) == expected);
        band += expected;
      }
  CHECK(band > 100);
  CHECK(cells.band_outer.size() > cells.band_inner.size());
  o.threads = 1;
  const CarvableCells serial = carvable_cells(box, bvh, o);
  CHECK(serial.inner == cells.inner);
  CHECK(serial.outer == cells.outer);
  CHECK(serial.band_inner == cells.band_inner);
  CHECK(serial.band_outer == cells.band_outer);
  o.strict = false;
  const CarvableCells centres_only = carvable_cells(box, bvh, o);
  CHECK(centres_only.outer == cells.outer);
  CHECK(centres_only.mid == cells.mid);
  CHECK(centres_only.band_inner == cells.band_inner);
  CHECK(centres_only.band_outer == cells.band_outer);
  CHECK(centres_only.skin_outer == cells.skin_outer);
}

TEST_CASE("carvable cells: cube integrals against the product of one-dimensional moments") {
  const Eigen::Vector3d c(1.5, -2.0, 0.25), origin(0.5, 0.5, -0.5);
  const double h = 0.3;
  const Vector10d v = cube_integrals(c, h, origin);
  // ∫ over [a − h/2, a + h/2] of 1, t, t²: h, h a, h (a² + h²/12).
  auto m0 = [&](double) { return h; };
  auto m1 = [&](double a) { return h * a; };
  auto m2 = [&](double a) { return h * (a * a + h * h / 12.0); };
  const Eigen::Vector3d p = c - origin;
  CHECK(v(kIntVolume) == doctest::Approx(m0(p.x()) * m0(p.y()) * m0(p.z())));
  CHECK(v(kIntY) == doctest::Approx(m0(p.x()) * m1(p.y()) * m0(p.z())));
  CHECK(v(kIntZZ) == doctest::Approx(m0(p.x()) * m0(p.y()) * m2(p.z())));
  CHECK(v(kIntZX) == doctest::Approx(m1(p.x()) * m0(p.y()) * m1(p.z())));
  CHECK(v(kIntXY) == doctest::Approx(m1(p.x()) * m1(p.y()) * m0(p.z())));
}

TEST_CASE("carvable cells: options are checked") {
  CarvableCellsOptions o;
  CHECK(!o.check().empty());  // no wall
  o.wall = 1.0;
  CHECK(o.check().empty());
  o.band = true;
  CHECK(!o.check().empty());  // no outer_max
}
