// Moment-space reachability (cavity/reachability.h) against closed forms:
// - a box standing on a face whose support polygon is a strip at one end: the best any void can do
//   is to carve the carvable box beyond the final centroid (a half-box cut by a plane), whose
//   centroid solves x* = cx(x*) in closed form; the answer lies between the values for the box
//   shrunk by the grid's two error bounds;
// - the same box with a reachable strip: the occupancy the programme returns, integrated cell by
//   cell here, meets the margin and gives the lowest centre of mass it reports;
// - an unreachable strip: the certificate's quadric integrated over the outer cells proves it;
//   a near miss too, which one bound of the quadric per cube would leave unproved;
// - a generous reading that can remove every cell: its margin stays one a solid in the box can have;
// - a sphere floating: reachable at ρ = 0.8, unreachable at ρ = 0.05 (95% void with a wall).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../box_on_strip.h"
#include "cavity/reachability.h"
#include "geometry/bvh.h"
#include "mesh/primitives.h"

using namespace offsetopt;
using offsetopt::test::min_centroid_x;
using offsetopt::test::strip_goal;

namespace {

ReachabilityOptions options_for(double wall) {
  ReachabilityOptions o;
  o.wall = wall;
  o.ground_tol = 1e-3;
  return o;
}

// Out of reach, with a certificate that proves it.
void check_proved(const Reachability& r) {
  REQUIRE(r.ok);
  CHECK(!r.reachable);
  REQUIRE(r.certificate.present);
  CHECK(r.certificate.proves);
  CHECK(r.decided);
}

// The 10 × 6 × 4 box, wall 0.5, standing on a strip [0, width] × [0, 6] by a margin of 0.05: out of
// reach below a width of about 2.8 (the generous reading's best centroid).
Reachability box_on_strip(double width) {
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(10, 6, 4));
  const TriangleBvh bvh(box.V, box.F);
  return reachability(box, bvh, strip_goal(width, 6, 0.05), 0.0, Eigen::Vector3d(1, 3, 0), options_for(0.5));
}

}  // namespace

TEST_CASE("reachability: a box on a strip: the best margin is the half-box cut by a plane") {
  const double a = 10, b = 6, c = 4, wall = 0.5;
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(a, b, c));
  const TriangleBvh bvh(box.V, box.F);
  const Eigen::Vector3d origin(1.0, 0.5 * b, 0.0);
  for (double width : {4.6, 2.0}) {
    CAPTURE(width);
    const Reachability r = reachability(box, bvh, strip_goal(width, b, 0.05), 0.0, origin, options_for(wall));
    REQUIRE(r.ok);
    REQUIRE(r.best_margin);
    const double h = r.cells->grid.spacing, margin = r.cells->margin;
    // Inner cells cover the box shrunk by wall + margin + √3 h and lie in the one shrunk by wall + margin.
    const double worst = width - min_centroid_x(a, b, c, wall + margin + std::sqrt(3.0) * h);
    const double best = width - min_centroid_x(a, b, c, wall + margin);
    CHECK(*r.best_margin >= worst - 1e-9);
    CHECK(*r.best_margin <= best + 1e-9);
    CHECK(r.binding == "support edge 1");
    CHECK(r.reachable == (width > 4.0));
    CHECK(r.decided);
    if (!r.reachable) {
      REQUIRE(r.best_margin_upper);
      // Outer cells lie in the box shrunk by wall − √3 h: no void does better than that.
      CHECK(*r.best_margin_upper <= width - min_centroid_x(a, b, c, wall - std::sqrt(3.0) * h) + 1e-9);
      CHECK(*r.best_margin_upper >= *r.best_margin - 1e-9);
    }
  }
}

TEST_CASE("reachability: the optimal void, integrated cell by cell, meets the margin at the lowest centre of mass") {
  const double a = 10, b = 6, c = 4, wall = 0.5;
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(a, b, c));
  const TriangleBvh bvh(box.V, box.F);
  const double width = 5.2, margin = 0.2;
  const Reachability r = reachability(box, bvh, strip_goal(width, b, margin), 0.0, Eigen::Vector3d(1, 3, 0), options_for(wall));
  REQUIRE(r.reachable);
  REQUIRE(r.lowest_cz);
  REQUIRE(r.occupancy.size() == r.cells->inner.size());
  double m = a * b * c, mx = m * 0.5 * a, my = m * 0.5 * b, mz = m * 0.5 * c;
  const double v = r.cells->cell_volume();
  int fractional = 0;
  for (std::size_t i = 0; i < r.occupancy.size(); ++i) {
    const double u = r.occupancy[i];
    if (u > 1e-9 && u < 1 - 1e-9) ++fractional;
    const Eigen::Vector3d p = r.cells->centre(r.cells->inner[i]);
    m -= u * v;
    mx -= u * v * p.x();
    my -= u * v * p.y();
    mz -= u * v * p.z();
  }
  // Distance inside the strip (the right edge binds), and the height the programme reports.
  CHECK(width - mx / m >= margin - 1e-9);
  CHECK(mx / m >= margin);
  CHECK(mz / m == doctest::Approx(*r.lowest_cz).epsilon(1e-9));
  CHECK(*r.lowest_cz < 0.5 * c);
  // A vertex of the LP: at most as many fractional cells as rows.
  CHECK(fractional <= 4);
  CHECK(r.lps >= 2);
}

TEST_CASE("reachability: an unreachable stand is proved by its quadric integrated over the carvable cells") {
  const Reachability r = box_on_strip(2.0);
  check_proved(r);
  // Farkas: the rows met would make constant − ∫_void q >= 0; the best void is {q < 0} over the
  // outer cells, integrated exactly cell by cell here.
  const CarvableCells& cells = *r.cells;
  double best = r.certificate.constant;
  for (std::int64_t cell : cells.outer) {
    const double integral = r.certificate.quadric.dot(cube_integrals(cells.centre(cell), cells.grid.spacing, r.certificate.origin));
    if (integral < 0.0) best -= integral;
  }
  CHECK(best < 0.0);
  // The quadric prefers carving the far end: q is lower at x = 9 than at x = 1 (mid-height, mid-depth).
  auto q_at = [&](const Eigen::Vector3d& p) {
    return r.certificate.quadric.dot(cube_integrals(p, 1e-6, r.certificate.origin)) / 1e-18;
  };
  CHECK(q_at(Eigen::Vector3d(9, 3, 2)) < q_at(Eigen::Vector3d(1, 3, 2)));
}

TEST_CASE("reachability: a near miss is proved where one bound per cube would not prove it") {
  // The generous reading misses the strip by 0.11: a cube wholly inside the quadric's carving side
  // must be bounded by its own integral, not by v · (the quadric's extreme on it).
  const Reachability r = box_on_strip(2.7);
  check_proved(r);
  // The stand's rows read the volume and the first moments: q is linear, so its least value on a
  // cube is at a corner. A void keeping the wall lies in the outer cells; within each, it gains at
  // most ∫ max(0, −q), bounded here by splitting the cube into n³ and taking each part's corners.
  REQUIRE(r.certificate.quadric.tail<6>().isZero());
  const CarvableCells& cells = *r.cells;
  const double h = cells.grid.spacing;
  auto q = [&](const Eigen::Vector3d& p) {
    return r.certificate.quadric.head<4>().dot(Eigen::Vector4d(1.0, p.x() - r.certificate.origin.x(), p.y() - r.certificate.origin.y(),
                                                                p.z() - r.certificate.origin.z()));
  };
  auto bound = [&](int n) {
    const double part = h / n;
    double total = r.certificate.constant;
    for (std::int64_t cell : cells.outer) {
      const Eigen::Vector3d low = cells.centre(cell) - Eigen::Vector3d::Constant(0.5 * h);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < n; ++k) {
            double least = q(low + part * Eigen::Vector3d(i, j, k));
            for (int corner = 1; corner < 8; ++corner)
              least = std::min(least, q(low + part * Eigen::Vector3d(i + (corner & 1), j + ((corner >> 1) & 1), k + (corner >> 2))));
            if (least < 0.0) total -= least * part * part * part;
          }
    }
    return total;
  };
  CHECK(bound(1) > 0.0);  // one bound per cube: no proof
  CHECK(bound(4) < 0.0);  // the certificate holds for voids of any shape in the outer cells
}

TEST_CASE("reachability: with a band wider than the wall, the generous margin stays one a solid in the grid's box can have") {
  // outer_max 2 against a wall of 0.5: the generous reading may carve a cell and shave it too, so
  // its programme reaches solids of no mass, whose ratios are rounding noise (5·10¹³ before the
  // cap). The centre of mass of any solid lies in the grid's box, so no margin below the sphere
  // centre exceeds the centre's height over the box's bottom.
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(10, 6, 4));
  const TriangleBvh bvh(box.V, box.F);
  GoalSpec g;
  g.kind = GoalKind::roly_poly;
  g.axis_point = Eigen::Vector3d(5, 3, 0.5);
  g.epsilon = 0.05;
  ReachabilityOptions o = options_for(0.5);
  o.outer = true;
  o.outer_max = 2.0;
  const Reachability r = reachability(box, bvh, g, 0.0, Eigen::Vector3d(5, 3, 0), o);
  REQUIRE(r.ok);
  CHECK(!r.reachable);
  REQUIRE(r.best_margin);
  REQUIRE(r.outer_margin_found);
  const double cap = g.axis_point.z() - r.cells->grid.origin.z();
  CHECK(*r.outer_margin_found <= cap * (1.0 + 1e-12));
  CHECK(*r.outer_margin_found >= *r.best_margin);
}

TEST_CASE("reachability: a sphere floats at density 0.8 but not at 0.05 (the void cannot be 95% with the wall)") {
  const Mesh sphere = make_icosphere(10.0, 3);
  const TriangleBvh bvh(sphere.V, sphere.F);
  const double zmin = sphere.V.col(2).minCoeff();
  GoalSpec g;
  g.kind = GoalKind::floating;
  g.epsilon = 0.05;
  ReachabilityOptions o = options_for(1.0);
  g.fluid_density = 0.8;
  const Reachability light = reachability(sphere, bvh, g, zmin, Eigen::Vector3d(0, 0, zmin), o);
  REQUIRE(light.ok);
  CHECK(light.reachable);
  CHECK(light.decided);
  REQUIRE(light.best_margin);
  CHECK(*light.best_margin > 1.0);
  g.fluid_density = 0.05;
  const Reachability heavy = reachability(sphere, bvh, g, zmin, Eigen::Vector3d(0, 0, zmin), o);
  REQUIRE(heavy.ok);
  CHECK(!heavy.reachable);
  CHECK(heavy.certificate.proves);
  CHECK(heavy.decided);
  CHECK(heavy.carvable_volume_outer < 0.95 * 4.0 / 3.0 * 3.14159265358979 * 1000.0);
}

TEST_CASE("reachability: options are checked") {
  ReachabilityOptions o;
  CHECK(!o.check().empty());
  o.wall = 1.0;
  CHECK(o.check().empty());
  o.block = 0;
  CHECK(!o.check().empty());
}

TEST_CASE("reachability: a quadric about an origin, re-expanded about zero, has the same values everywhere") {
  Quadric q;
  q.origin = Eigen::Vector3d(12.5, -3.0, 40.25);
  q.coefficients << 0.7, -1.5, 2.25, 0.5, 1.0, -0.75, 0.3, 0.2, -0.6, 0.45;
  const Vector10d a = q.about_zero();
  auto value = [](const Vector10d& c, const Eigen::Vector3d& x) {
    return c(0) + c(1) * x.x() + c(2) * x.y() + c(3) * x.z() + c(4) * x.x() * x.x() + c(5) * x.y() * x.y() +
           c(6) * x.z() * x.z() + c(7) * x.x() * x.y() + c(8) * x.y() * x.z() + c(9) * x.z() * x.x();
  };
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(12.5, -3.0, 40.25), Eigen::Vector3d(-7, 4.5, 1.25),
                                  Eigen::Vector3d(30, 20, -10)}) {
    CAPTURE(p.transpose());
    const double expected = value(q.coefficients, p - q.origin);
    CHECK(value(a, p) == doctest::Approx(expected).epsilon(1e-12).scale(1.0 + std::fabs(expected)));
  }
}

TEST_CASE("reachability: a volume's ball starts at the writable cell farthest along the given line") {
  // An icosphere of radius 10 about the origin, wall 1: the writable cells' centres lie at least a
  // wall inside, so none is above z = 9; along +z through the centre, the farthest lies within
  // two cells of that height. Without the line the ball starts at the cell nearest the centroid
  // (by symmetry, within a cell of the centre). Either way it holds the target (occupancy sum).
  const Mesh sphere = make_icosphere(10.0, 3);
  const TriangleBvh bvh(sphere.V, sphere.F);
  GoalSpec g;
  g.kind = GoalKind::volume;
  g.target_volume = 50.0;
  ReachabilityOptions o = options_for(1.0);
  for (const bool along : {false, true}) {
    CAPTURE(along);
    if (along) o.volume_start = ReachabilityOptions::Line{Eigen::Vector3d(0.3, -0.2, 4.0), Eigen::Vector3d(0, 0, 2)};
    Reachability r = reachability(sphere, bvh, g, sphere.V.col(2).minCoeff(), Eigen::Vector3d::Zero(), o);
    REQUIRE(r.ok);
    REQUIRE(r.reachable);
    REQUIRE(r.find_optimum);
    r.find_optimum(r);
    REQUIRE(r.optimum);
    const double h = r.cells->grid.spacing;
    const Eigen::Vector3d c = r.optimum->origin;
    if (along) {
      CHECK(std::hypot(c.x() - 0.3, c.y() + 0.2) <= h * (1.0 + 1e-12));
      CHECK(c.z() <= 9.0);
      CHECK(c.z() >= 9.0 - 2.0 * h);
    } else {
      CHECK(c.norm() <= h);
    }
    double held = 0.0;
    for (double u : r.occupancy) held += u * r.cells->cell_volume();
    CHECK(held == doctest::Approx(50.0).epsilon(1e-9));
  }
}
