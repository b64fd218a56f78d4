// Support polygon, centre-of-mass margin and tipping angle against hand-computed values, and the
// exact orientation predicate and convex hull they stand on.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/convex_hull_2d.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass_test_helpers.h"
#include "mesh/primitives.h"

using namespace offsetopt;
using namespace offsetopt::test;

namespace {

Stability stability_of(const Mesh& mesh, const StabilityOptions& options = {}) {
  const Vector10d P = mass_properties(mesh);
  return compute_stability(mesh, P.segment<3>(kCx), options);
}

double degrees(double radians) { return radians * 180.0 / kPi; }

}  // namespace

TEST_CASE("a box standing on a face: margins and tipping angle are analytic") {
  const Mesh box = make_box({0, 0, 0}, {2, 3, 4});
  const Stability s = stability_of(box);
  CHECK(s.contact_vertex_count == 4);
  REQUIRE(s.support_polygon.size() == 4);
  CHECK(s.ground_z == 0.0);
  CHECK(s.ground_tol == doctest::Approx(1e-3 * std::sqrt(29.0)).epsilon(1e-15));
  CHECK(s.support_polygon[0] == Eigen::Vector2d(0, 0));  // lexicographically smallest first, CCW
  CHECK(s.support_polygon[1] == Eigen::Vector2d(2, 0));
  CHECK(s.support_polygon[2] == Eigen::Vector2d(2, 3));
  CHECK(s.support_polygon[3] == Eigen::Vector2d(0, 3));
  CHECK(s.com_margin == doctest::Approx(1.0).epsilon(1e-14));  // half the short side
  CHECK(s.tipping_angle_deg == doctest::Approx(degrees(std::atan2(1.0, 2.0))).epsilon(1e-13));
  CHECK((s.tipping_edge == 1 || s.tipping_edge == 3));  // about a long edge (x = 2 or x = 0)
  CHECK(s.stands);
}

TEST_CASE("a box sheared so its centre of mass is outside the base falls") {
  Mesh box = make_box({0, 0, 0}, {2, 3, 4});
  box.V.col(0) += 1.0 * box.V.col(2);  // x += z: centre of mass at x = 1 + 2 = 3, base [0, 2]
  const Stability s = stability_of(box);
  CHECK(s.contact_vertex_count == 4);
  CHECK(s.support_polygon.size() == 4);
  CHECK(s.com_margin == doctest::Approx(-1.0).epsilon(1e-13));
  CHECK(s.tipping_angle_deg == doctest::Approx(degrees(std::atan2(-1.0, 2.0))).epsilon(1e-13));
  CHECK(s.tipping_edge == 1);  // the edge x = 2, from (2, 0) to (2, 3)
  CHECK_FALSE(s.stands);
}

TEST_CASE("a tilted box resting on an edge: a segment contact never stands") {
  const Eigen::Vector3d sides(1.0, 2.0, 3.0);
  const Mesh box = transformed(make_box(Eigen::Vector3d::Zero(), sides), rotation_from_angles(0.0, 0.3, 0.0), Eigen::Vector3d::Zero());
  Mesh resting = box;
  resting.V.col(2).array() -= box.V.col(2).minCoeff();
  const Stability s = stability_of(resting);
  CHECK(s.contact_vertex_count == 2);
  REQUIRE(s.support_polygon.size() == 2);
  const Vector10d P = mass_properties(resting);
  const double distance = std::fabs(P(kCx) - s.support_polygon[0].x());  // the edge runs along y
  CHECK(distance > 0.01);
  CHECK(s.com_margin == doctest::Approx(-distance).epsilon(1e-12));
  CHECK(s.tipping_angle_deg == doctest::Approx(degrees(std::atan2(-distance, P(kCz)))).epsilon(1e-12));
  CHECK_FALSE(s.stands);
}

TEST_CASE("a cylinder on its cap: margin is the radius, tipping angle atan(r / h_c)") {
  const double r = 1.5, height = 5.0;
  const int n = 256;
  const Mesh cylinder = make_cylinder(r, 0.0, height, n, 4, 3);
  const Stability s = stability_of(cylinder);
  CHECK(s.contact_vertex_count == 1 + 3 * n);  // centre pole and three cap rings
  CHECK(s.support_polygon.size() == static_cast<std::size_t>(n));
  // The support polygon is the inscribed n-gon: its apothem r cos(pi / n) is the exact margin.
  const double apothem = r * std::cos(kPi / n);
  CHECK(s.com_margin == doctest::Approx(apothem).epsilon(1e-12));
  CHECK(s.tipping_angle_deg == doctest::Approx(degrees(std::atan(apothem / (0.5 * height)))).epsilon(1e-12));
  CHECK(std::fabs(s.tipping_angle_deg - degrees(std::atan(r / (0.5 * height)))) < 2e-3);
  CHECK(s.stands);
}

TEST_CASE("a single contact point: zero-area polygon, margin minus the distance") {
  Mesh cone = make_revolution({{0.0, 0.0}, {1.0, 1.0}, {0.0, 2.0}}, 32);  // double cone on its tip
  cone.V.col(0) += 0.1 * cone.V.col(2);  // centre of mass at (0.1, 0, 1), tip at the origin
  const Stability s = stability_of(cone);
  CHECK(s.contact_vertex_count == 1);
  REQUIRE(s.support_polygon.size() == 1);
  CHECK(s.support_polygon[0] == Eigen::Vector2d(0, 0));
  CHECK(s.com_margin == doctest::Approx(-0.1).epsilon(1e-13));
  CHECK(s.tipping_angle_deg == doctest::Approx(degrees(std::atan2(-0.1, 1.0))).epsilon(1e-13));
  CHECK(s.tipping_edge == -1);
  CHECK_FALSE(s.stands);

  // Exactly balanced on the point still does not stand (margin 0).
  Stability balanced;
  support_polygon_margins({Eigen::Vector2d(1, 2)}, Eigen::Vector2d(1, 2), 3.0, balanced);
  CHECK(balanced.com_margin == 0.0);
  CHECK(balanced.tipping_angle_deg == 0.0);
  CHECK_FALSE(balanced.stands);
}

TEST_CASE("ground tolerance selects the contact set") {
  Mesh box = make_box({0, 0, 0}, {2, 2, 2});
  box.V(1, 2) = 0.05;  // lift one bottom corner a little: (2, 0, 0) -> (2, 0, 0.05)
  StabilityOptions tight;
  tight.ground_tol = 0.01;
  CHECK(stability_of(box, tight).contact_vertex_count == 3);
  StabilityOptions loose;
  loose.ground_tol = 0.1;
  CHECK(stability_of(box, loose).contact_vertex_count == 4);
  StabilityOptions bad;
  bad.ground_tol = std::nan("");
  CHECK(bad.check() == "ground_tol must be finite");
  CHECK_THROWS_AS(stability_of(box, bad), std::invalid_argument);
}

TEST_CASE("orient2d has the exact sign, also for nearly collinear points") {
  // Coordinates on a 2^-40 grid inside [0, 1024): the determinant is an exact 128-bit integer.
  Rng rng(31);
  const double unit = 0x1.0p-40;
  auto grid = [&](double v) { return std::floor(v / unit) * unit; };
  auto exact_sign = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
    auto n = [&](double v) { return static_cast<__int128>(static_cast<long long>(v / unit)); };
    const __int128 det = (n(a.x()) - n(c.x())) * (n(b.y()) - n(c.y())) - (n(a.y()) - n(c.y())) * (n(b.x()) - n(c.x()));
    return det > 0 ? 1 : (det < 0 ? -1 : 0);
  };
  int disagreements = 0, zeros = 0, filter_misses = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector2d a(grid(rng.uniform(0, 1000)), grid(rng.uniform(0, 1000)));
    // b and c on one grid line through a (c = a + k d exactly), c nudged by at most one cell.
    const Eigen::Vector2d d(grid(rng.uniform(-1, 1)), grid(rng.uniform(-1, 1)));
    const Eigen::Vector2d b = a + static_cast<double>(rng.below(500)) * d;
    Eigen::Vector2d c = a + static_cast<double>(rng.below(500)) * d;
    c.x() += unit * static_cast<double>(static_cast<int>(rng.below(3)) - 1);
    const int expected = exact_sign(a, b, c);
    const double got = orient2d(a, b, c);
    const int sign = got > 0 ? 1 : (got < 0 ? -1 : 0);
    if (sign != expected) ++disagreements;
    if (expected == 0) ++zeros;
    const double naive = (a.x() - c.x()) * (b.y() - c.y()) - (a.y() - c.y()) * (b.x() - c.x());
    if ((naive > 0 ? 1 : (naive < 0 ? -1 : 0)) != expected) ++filter_misses;
  }
  MESSAGE("orient2d: " << zeros << " exactly collinear cases, naive formula wrong in " << filter_misses);
  CHECK(disagreements == 0);
  CHECK(zeros > 100);
  CHECK(filter_misses > 0);  // the cases are hard enough that the plain formula fails
}

TEST_CASE("convex hull: order, degenerate inputs, collinear points and random clouds") {
  std::vector<Eigen::Vector2d> square;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j) square.emplace_back(i, j);  // boundary has collinear points
  const auto hull = convex_hull_2d(square);
  REQUIRE(hull.size() == 4);
  CHECK(hull[0] == Eigen::Vector2d(0, 0));
  CHECK(hull[1] == Eigen::Vector2d(4, 0));
  CHECK(hull[2] == Eigen::Vector2d(4, 4));
  CHECK(hull[3] == Eigen::Vector2d(0, 4));

  CHECK(convex_hull_2d({}).empty());
  CHECK(convex_hull_2d({{1, 1}, {1, 1}, {1, 1}}).size() == 1);
  const auto segment = convex_hull_2d({{2, 2}, {0, 0}, {1, 1}, {3, 3}, {1, 1}});
  REQUIRE(segment.size() == 2);
  CHECK(segment[0] == Eigen::Vector2d(0, 0));
  CHECK(segment[1] == Eigen::Vector2d(3, 3));

  Rng rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Eigen::Vector2d> points;
    const int n = 3 + static_cast<int>(rng.below(200));
    for (int i = 0; i < n; ++i) {
      if (trial % 2 == 0) {
        points.emplace_back(rng.uniform(-1, 1), rng.uniform(-1, 1));
      } else {  // points on the line y = x / 3 as doubles round it: nearly collinear
        const double x = rng.uniform(-1, 1);
        points.emplace_back(x, x / 3.0);
      }
    }
    const auto h = convex_hull_2d(points);
    REQUIRE(h.size() >= 2);
    const std::size_t m = h.size();
    for (std::size_t i = 0; m >= 3 && i < m; ++i) CHECK(orient2d(h[i], h[(i + 1) % m], h[(i + 2) % m]) > 0.0);
    for (const auto& p : points) {
      CHECK(std::find(points.begin(), points.end(), h[0]) != points.end());
      for (std::size_t i = 0; m >= 3 && i < m; ++i) CHECK(orient2d(h[i], h[(i + 1) % m], p) >= 0.0);
    }
  }
}
