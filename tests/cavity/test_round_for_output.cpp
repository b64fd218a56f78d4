// Rounding to an output's precision (cavity/round_for_output.h) on a configuration where plain
// float32 rounding folds a CAD wall: four faces of a vertical wall of an OpenSCAD part (vertices
// on one plane, a 0.002-high step next to a 10-long sliver), turned 0.6 rad about z so x and y are
// no longer float32 numbers. CGAL (tools/validity) finds no pair in the double file and 3 pairs in
// the whole part written as float32 STL. Expectations: the unrounded faces meet nowhere but along
// their edges, the nearest-float ones fold (a brute-force search over every pair with the exact
// rule), and the repaired ones are float32 numbers within kRoundingSearchUlps of the nearest, with
// no pair.
#include <doctest/doctest.h>

#include <cmath>

#include "cavity/round_for_output.h"
#include "geometry/faces_intersect_exact.h"

using namespace offsetopt;
using V3 = Eigen::Vector3d;

namespace {

Mesh cad_wall() {
  Mesh m;
  const V3 v[6] = {V3(29.47691575357318, 28.969935880313464, 2.6080000400543213),
                   V3(37.72670174814972, 34.543642436098644, 2.73799991607666),
                   V3(37.70750341080201, 34.57170456799044, 2.805999994277954),
                   V3(37.693951896667166, 34.59151276127811, 2.6080000400543213),
                   V3(37.693951896667166, 34.59151276127811, 2.609999895095825),
                   V3(37.663460989863765, 34.63608119617538, 2.7980000972747803)};
  m.V.resize(6, 3);
  for (int i = 0; i < 6; ++i) m.V.row(i) = v[i].transpose();
  m.F.resize(4, 3);
  m.F << 4, 3, 0, 1, 4, 0, 2, 3, 4, 2, 5, 3;
  return m;
}

// Pairs of faces that meet other than where they join, every pair tried.
int brute_force_pairs(const Mesh& m) {
  int pairs = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (Eigen::Index g = f + 1; g < m.F.rows(); ++g) {
      const V3 a[3] = {m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(), m.V.row(m.F(f, 2)).transpose()};
      const V3 b[3] = {m.V.row(m.F(g, 0)).transpose(), m.V.row(m.F(g, 1)).transpose(), m.V.row(m.F(g, 2)).transpose()};
      const int ia[3] = {m.F(f, 0), m.F(f, 1), m.F(f, 2)}, ib[3] = {m.F(g, 0), m.F(g, 1), m.F(g, 2)};
      pairs += faces_intersect_exact(a, ia, b, ib) ? 1 : 0;
    }
  return pairs;
}

}  // namespace

TEST_CASE("a CAD wall that nearest-float rounding folds is re-rounded to float32 points without a pair") {
  const Mesh wall = cad_wall();
  CHECK(brute_force_pairs(wall) == 0);
  Mesh nearest = wall;
  for (Eigen::Index i = 0; i < nearest.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) nearest.V(i, c) = static_cast<float>(nearest.V(i, c));
  REQUIRE(brute_force_pairs(nearest) > 0);

  const Mesh empty{Vertices(0, 3), Faces(0, 3)};
  const RoundedForOutput r = round_for_output(wall, empty, {}, StoredPrecision::float32);
  CHECK(r.outer_new_pairs == 0);
  CHECK(r.vertices_moved >= 1);
  CHECK(brute_force_pairs(r.outer) == 0);
  for (Eigen::Index i = 0; i < wall.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double x = r.outer.V(i, c);
      CHECK(static_cast<double>(static_cast<float>(x)) == x);  // a float32 number
      const double ulp = std::ldexp(1.0, std::ilogb(static_cast<float>(wall.V(i, c))) - 23);
      CHECK(std::fabs(x - nearest.V(i, c)) <= kRoundingSearchUlps * ulp);
    }
  CHECK(r.outer.F == wall.F);
}

TEST_CASE("exact precision leaves the meshes as they are, and the wall margin is 0 there and covers the moves in float32") {
  const Mesh wall = cad_wall();
  const Mesh empty{Vertices(0, 3), Faces(0, 3)};
  const RoundedForOutput r = round_for_output(wall, empty, {}, StoredPrecision::exact);
  CHECK(r.outer.V == wall.V);
  CHECK(rounding_wall_margin(100.0, StoredPrecision::exact) == 0.0);
  // Both ends move by at most (1/2 + kRoundingSearchUlps) ulps per coordinate: 2^-23 * 128 is
  // the ulp bound below 128 (float ulps of numbers in [64, 128) are 2^-17).
  const double per_coordinate = (0.5 + kRoundingSearchUlps) * std::ldexp(1.0, -17);
  CHECK(rounding_wall_margin(100.0, StoredPrecision::float32) >= 2.0 * std::sqrt(3.0) * per_coordinate);
}
