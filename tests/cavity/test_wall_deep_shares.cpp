// The shares of the generous cells a void may hold (cavity/wall_deep_shares.h), against boxes whose
// region a wall deep is the box shrunk by the wall: cell by cell, each share is at least the
// cube's exact overlap with that region (an upper bound, never less), and summed they come within
// a layer a tenth of a wall thick of the exact volume, where whole cells overshoot by more than
// half a wall's.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "cavity/carvable_cells.h"
#include "cavity/wall_deep_shares.h"
#include "geometry/bvh.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

double overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

CarvableCells cells_of(const Mesh& mesh, const TriangleBvh& bvh, double wall) {
  CarvableCellsOptions o;
  o.wall = wall;
  const CarvableCells cells = carvable_cells(mesh, bvh, o);
  REQUIRE(cells.ok);
  return cells;
}

}  // namespace

TEST_CASE("wall_deep_shares: every share of a box's cells is at least the cube's part a wall deep, and the sum is close") {
  // Off the grid's lattice, so cells cut the shrunk box's faces anywhere.
  const Eigen::Vector3d lo(0.113, -0.271, 0.057), hi(10.113, 5.729, 4.057);
  const double wall = 0.5;
  const Mesh box = make_box(lo, hi);
  const TriangleBvh bvh(box.V, box.F);
  const CarvableCells cells = cells_of(box, bvh, wall);
  const Eigen::Vector3d deep_lo = lo + Eigen::Vector3d::Constant(wall), deep_hi = hi - Eigen::Vector3d::Constant(wall);
  const double h = cells.grid.spacing, v = h * h * h;
  for (int levels : {0, 1, 3}) {
    CAPTURE(levels);
    const WallDeepShares s = wall_deep_shares(cells, bvh, wall, levels, 2);
    REQUIRE(s.share.size() == cells.outer.size());
    CHECK(s.shell_cells > 0);
    CHECK(s.shell_cells < static_cast<std::int64_t>(cells.outer.size()));
    double sum = 0.0;
    int below = 0;
    for (std::size_t c = 0; c < cells.outer.size(); ++c) {
      const Eigen::Vector3d p = cells.grid.position(cells.outer[c]);
      const double exact = overlap(p.x(), p.x() + h, deep_lo.x(), deep_hi.x()) * overlap(p.y(), p.y() + h, deep_lo.y(), deep_hi.y()) *
                           overlap(p.z(), p.z() + h, deep_lo.z(), deep_hi.z());
      const double share = s.share[c];
      if (!(share >= 0.0 && share <= 1.0 && share * v >= exact - 1e-12 * v)) ++below;
      sum += share * v;
    }
    CHECK(below == 0);
    const double exact = (deep_hi - deep_lo).prod();
    const double area = 2.0 * ((deep_hi - deep_lo).x() * (deep_hi - deep_lo).y() + (deep_hi - deep_lo).y() * (deep_hi - deep_lo).z() +
                               (deep_hi - deep_lo).z() * (deep_hi - deep_lo).x());
    CHECK(sum >= exact);
    const double whole = v * static_cast<double>(cells.outer.size());
    CHECK(sum <= whole);
    // Three halvings: within a layer a tenth of a wall thick over the shrunk box (0.07 measured;
    // whole cells overshoot by 0.76 of a wall).
    if (levels == 3) {
      CHECK(sum <= exact + 0.1 * wall * area);
      CHECK(whole >= exact + 0.5 * wall * area);
    }
  }
}

TEST_CASE("wall_deep_shares: a turned box keeps its bound, and the same shares on one thread as on two") {
  // The box turned about a skew axis: its faces cross the cells at every angle.
  const double wall = 0.4;
  Mesh box = make_box(Eigen::Vector3d(-4, -3, -2), Eigen::Vector3d(4, 3, 2));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (Eigen::Index i = 0; i < box.V.rows(); ++i) box.V.row(i) = (R * box.V.row(i).transpose()).transpose();
  const TriangleBvh bvh(box.V, box.F);
  const CarvableCells cells = cells_of(box, bvh, wall);
  const WallDeepShares two = wall_deep_shares(cells, bvh, wall, 3, 2), one = wall_deep_shares(cells, bvh, wall, 3, 1);
  CHECK(two.share == one.share);
  const double h = cells.grid.spacing, v = h * h * h;
  double sum = 0.0;
  for (double share : two.share) sum += share * v;
  const double exact = (8 - 2 * wall) * (6 - 2 * wall) * (4 - 2 * wall);
  const double area = 2.0 * ((8 - 2 * wall) * (6 - 2 * wall) + (6 - 2 * wall) * (4 - 2 * wall) + (4 - 2 * wall) * (8 - 2 * wall));
  CHECK(sum >= exact);
  CHECK(sum <= exact + 0.1 * wall * area);
}
