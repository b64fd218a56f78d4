// Poses (issue 13): the 3-D convex hull against its defining property (every point on or below
// every hull plane, Euler's formula) and a sheared, sampled box's six facets against their analytic
// areas, the exact up-axis permutations and the sqrt-only rotation to −z (the stable pose is tested
// in tests/mass/test_stable_pose.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "../sheared_box_points.h"
#include "geometry/convex_hull_3d.h"
#include "geometry/pose.h"
#include "mesh/primitives.h"
#include "util/det_math.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

std::vector<Eigen::Vector3d> points_of(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> points;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points.emplace_back(mesh.V.row(i).transpose());
  return points;
}

void check_hull(const std::vector<Eigen::Vector3d>& points, const ConvexHull3d& hull) {
  REQUIRE(hull.status == ConvexHullStatus::ok);
  // Closed convex polyhedron with triangular faces: F = 2V − 4 over its vertices.
  std::vector<char> used(points.size(), 0);
  for (const auto& t : hull.triangles)
    for (int v : t) used[v] = 1;
  long long vertices = 0;
  for (char u : used) vertices += u;
  CHECK(static_cast<long long>(hull.triangles.size()) == 2 * vertices - 4);
  long long violations = 0;
  for (const auto& t : hull.triangles)
    for (std::size_t i = 0; i < points.size(); ++i)
      if (orient3d(points[t[0]], points[t[1]], points[t[2]], points[i]) > 0.0) ++violations;
  CHECK(violations == 0);
}

}  // namespace

TEST_CASE("convex_hull_3d: random points, a sphere and a box with interior and duplicate points") {
  Rng rng(13);
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 2000; ++i) cloud.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  check_hull(cloud, convex_hull_3d(cloud, 0.0));

  const std::vector<Eigen::Vector3d> sphere = points_of(make_icosphere(2.0, 3));
  const ConvexHull3d sphere_hull = convex_hull_3d(sphere, 0.0);
  check_hull(sphere, sphere_hull);
  CHECK(sphere_hull.triangles.size() == 2 * sphere.size() - 4);  // every point is a hull vertex

  std::vector<Eigen::Vector3d> box = points_of(make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 2, 1)));
  box.push_back(Eigen::Vector3d(1, 1, 0.5));  // interior
  box.push_back(box[3]);                       // duplicate
  box.push_back(Eigen::Vector3d(2, 1, 1));     // on the top face
  const ConvexHull3d box_hull = convex_hull_3d(box, 1e-12);
  REQUIRE(box_hull.status == ConvexHullStatus::ok);
  REQUIRE(box_hull.facets.size() == 6);
  double area = 0.0;
  for (const auto& facet : box_hull.facets) {
    area += facet.area;
    CHECK(facet.normal.cwiseAbs().maxCoeff() == doctest::Approx(1.0).epsilon(1e-15));
  }
  CHECK(area == doctest::Approx(2 * (8 + 4 + 2)).epsilon(1e-14));

  // A 6 x 6 x 6 grid: most points are coplanar or collinear with hull faces and edges.
  std::vector<Eigen::Vector3d> grid;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) grid.emplace_back(0.1 * i, 0.1 * j, 0.1 * k);
  const ConvexHull3d grid_hull = convex_hull_3d(grid, 0.0);
  check_hull(grid, grid_hull);
  CHECK(grid_hull.facets.size() == 6);
  double grid_area = 0.0;
  for (const auto& facet : grid_hull.facets) grid_area += facet.area;
  CHECK(grid_area == doctest::Approx(6 * 0.25).epsilon(1e-14));

  std::vector<Eigen::Vector3d> flat{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  CHECK(convex_hull_3d(flat, 0.0).status == ConvexHullStatus::flat);
}

TEST_CASE("orient3d: exact sign where the plain determinant is rounded away") {
  // Points on a plane through a point far from the origin: exactly coplanar in binary.
  const Eigen::Vector3d a(1e8, 1e8, 1e8), b(1e8 + 1, 1e8, 1e8), c(1e8, 1e8 + 1, 1e8);
  CHECK(orient3d(a, b, c, Eigen::Vector3d(1e8 + 0.5, 1e8 + 0.25, 1e8)) == 0.0);
  const double tiny = std::nextafter(1e8, 2e8);  // one ulp above the plane z = 1e8
  CHECK(orient3d(a, b, c, Eigen::Vector3d(1e8 + 3, 1e8 + 7, tiny)) > 0.0);
  CHECK(orient3d(a, c, b, Eigen::Vector3d(1e8 + 3, 1e8 + 7, tiny)) < 0.0);
}

TEST_CASE("up_axis_permutation: proper rotations taking the named axis to +z, exactly invertible") {
  const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  const Eigen::Vector3d axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int i = 0; i < 6; ++i) {
    AxisPermutation p;
    REQUIRE(up_axis_permutation(names[i], p));
    CHECK(p.matrix().determinant() == 1.0);
    CHECK(p.matrix() * axes[i] == Eigen::Vector3d(0, 0, 1));
    CHECK(p.apply(axes[i]) == Eigen::Vector3d(0, 0, 1));
    CHECK(p.inverse().matrix() == p.matrix().transpose());
    const Eigen::Vector3d x(0.1, -0.0, 3e-300);
    const Eigen::Vector3d back = p.inverse().apply(p.apply(x));
    CHECK(back == x);
    CHECK(std::signbit(back.y()));  // the sign of zero survives the round trip
  }
  AxisPermutation p;
  CHECK(up_axis_permutation("y", p));
  CHECK(p.apply(Eigen::Vector3d(1, 2, 3)) == Eigen::Vector3d(1, -3, 2));  // Blender's y-up
  CHECK_FALSE(up_axis_permutation("w", p));
  CHECK_FALSE(up_axis_permutation("+xy", p));
}

TEST_CASE("rotation_to_minus_z: orthonormal, proper, and takes the vector to −z") {
  const Eigen::Vector3d dirs[] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0.3, -0.4, 0.866}, {1e-9, 0, 1}, {-2, 5, -1}};
  for (const auto& d : dirs) {
    const Eigen::Matrix3d R = rotation_to_minus_z(d);
    CHECK((R * R.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
    CHECK(R.determinant() == doctest::Approx(1.0).epsilon(1e-15));
    CHECK((R * d.normalized() - Eigen::Vector3d(0, 0, -1)).norm() < 1e-15);
  }
}

// The sheared box of tests/sheared_box_points.h: the slivers along its hull edges have planes that
// are noise. Each face must stay one facet with its own area: 20 (the parallelograms), 2·√164
// (the sheared rectangles), 4 (the ends). Before, a sliver on an edge joined both faces it
// touches, and four faces came out as one facet of area 91.2.
TEST_CASE("convex_hull_3d: a sheared, finely sampled box has its six faces as six facets") {
  const std::vector<Eigen::Vector3d> points = test::sheared_box_points();
  const double diagonal = std::sqrt(2.0 * 2.0 + 10.0 * 10.0 + 10.0 * 10.0);
  const ConvexHull3d hull = convex_hull_3d(points, 1e-9 * diagonal);
  check_hull(points, hull);
  REQUIRE(hull.facets.size() == 6);
  std::vector<double> areas;
  for (const auto& facet : hull.facets) areas.push_back(facet.area);
  std::sort(areas.begin(), areas.end());
  const double slanted = 2.0 * std::sqrt(164.0);
  CHECK(areas[0] == doctest::Approx(4.0).epsilon(1e-12));
  CHECK(areas[1] == doctest::Approx(4.0).epsilon(1e-12));
  CHECK(areas[2] == doctest::Approx(20.0).epsilon(1e-12));
  CHECK(areas[3] == doctest::Approx(20.0).epsilon(1e-12));
  CHECK(areas[4] == doctest::Approx(slanted).epsilon(1e-12));
  CHECK(areas[5] == doctest::Approx(slanted).epsilon(1e-12));
}
