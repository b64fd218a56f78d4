// Closest points against brute force over every face (and the point-triangle primitive against
// a dense sampling of the triangle); inscribed-ball radii against closed forms.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/inscribed_ball.h"
#include "mesh/primitives.h"
#include "util/rng.h"

using namespace offsetopt;

TEST_CASE("closest point on a triangle is no farther than any sample of the triangle") {
  Rng rng(11);
  for (int trial = 0; trial < 300; ++trial) {
    Eigen::Vector3d t[3];
    for (auto& p : t) p = Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Eigen::Vector3d p(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    const Eigen::Vector3d q = closest_point_on_triangle(p, t[0], t[1], t[2]);
    // q lies on the triangle: non-negative barycentrics summing to one, in its plane.
    const Eigen::Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
    CHECK(std::abs((q - t[0]).dot(n)) < 1e-12 * n.norm());
    const double w1 = (t[2] - q).cross(t[0] - q).dot(n) / n.squaredNorm();
    const double w2 = (t[0] - q).cross(t[1] - q).dot(n) / n.squaredNorm();
    CHECK(w1 >= -1e-12);
    CHECK(w2 >= -1e-12);
    CHECK(w1 + w2 <= 1 + 1e-12);
    // And it beats a 40 x 40 barycentric grid.
    double best = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; a + b <= 40; ++b) {
        const Eigen::Vector3d s = t[0] + (a / 40.0) * (t[1] - t[0]) + (b / 40.0) * (t[2] - t[0]);
        best = std::min(best, (s - p).norm());
      }
    CHECK((q - p).norm() <= best + 1e-12);
  }
}

TEST_CASE("BVH closest point agrees with brute force") {
  Mesh m = make_torus(1.0, 0.3, 40, 16);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V(i, 2) *= 1.0 + 0.5 * m.V(i, 0);
  const TriangleBvh bvh(m.V, m.F);
  Rng rng(12);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d p(rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5), rng.uniform(-0.8, 0.8));
    double best = std::numeric_limits<double>::infinity();
    for (int f = 0; f < m.F.rows(); ++f)
      best = std::min(best, (closest_point_on_triangle(p, bvh.corner(f, 0), bvh.corner(f, 1), bvh.corner(f, 2)) - p).norm());
    const ClosestPoint c = closest_point(bvh, p);
    REQUIRE(c.found);
    CHECK(c.distance == doctest::Approx(best).epsilon(1e-12));
    CHECK((c.point - p).norm() == doctest::Approx(best).epsilon(1e-12));
    // A search radius below the distance finds nothing; ignoring the face finds something no closer.
    CHECK_FALSE(closest_point(bvh, p, 0.99 * best).found);
    const ClosestPoint other = closest_point(bvh, p, std::numeric_limits<double>::infinity(), {c.face});
    CHECK(other.distance >= c.distance);
  }
}

TEST_CASE("inscribed balls: sphere radius, half the thickness of a box") {
  const double R = 1.5;
  const Mesh sphere = make_icosphere(R, 4);
  const TriangleBvh sphere_bvh(sphere.V, sphere.F);
  for (int i : {0, 17, 400}) {
    const Eigen::Vector3d x = sphere.V.row(i).transpose();
    const Eigen::Vector3d d = -x.normalized();
    const InscribedBall ball = inscribed_ball(sphere_bvh, x, d, 2 * R);
    CHECK(ball.radius == doctest::Approx(R).epsilon(0.02));
    CHECK(inscribed_radius_by_rays(sphere_bvh, x, d, 2 * R) == doctest::Approx(R).epsilon(0.02));
  }
  // Box 2 x 4 x 6, probed from the middle of a 4 x 6 face: the ball touches the opposite face,
  // radius 1. The start face is tangent to the ball at x, so it never shrinks it.
  const Mesh box = make_box({0, 0, 0}, {2, 4, 6});
  const TriangleBvh box_bvh(box.V, box.F);
  const Eigen::Vector3d on_big_face(0.0, 2.0, 3.0), inward(1, 0, 0);
  const InscribedBall big = inscribed_ball(box_bvh, on_big_face, inward, 10.0, {});
  CHECK(big.radius == doctest::Approx(1.0).epsilon(0.02));
  // The ray estimate is an upper bound; along the normal it meets the far face at 2: exactly 1.
  const double by_rays = inscribed_radius_by_rays(box_bvh, on_big_face, inward, 10.0);
  CHECK(by_rays == doctest::Approx(1.0).epsilon(1e-12));
  // From the middle of a 2 x 4 end face the sides at distance 1 limit the ball, not the far end
  // at 6; the rays see the sides only obliquely, so they bound it from above.
  const Eigen::Vector3d on_end_face(1.0, 2.0, 0.0), up(0, 0, 1);
  CHECK(inscribed_ball(box_bvh, on_end_face, up, 10.0).radius == doctest::Approx(1.0).epsilon(0.02));
  const double end_by_rays = inscribed_radius_by_rays(box_bvh, on_end_face, up, 3.0);
  CHECK(end_by_rays >= 0.98);
  CHECK(end_by_rays <= 1.6);
}
