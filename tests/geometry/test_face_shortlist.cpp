// FaceShortlist against closest_point itself: the same face, point and distance to the last bit at
// every node of grids whose 2³ blocks straddle the surface, with radii that cover every answer (the
// list must then answer alone) and radii that cannot (it must then still agree).
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/face_shortlist.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

// Every node of an n³ grid from `lo` with spacing h, by 2³ blocks; the list of each block is
// gathered around its centre with radius cover(centre) or `tight`.
void check_grid(const Mesh& mesh, const Eigen::Vector3d& lo, double h, int n, double max_distance) {
  const TriangleBvh bvh(mesh.V, mesh.F);
  const double half_diagonal = 0.5 * std::sqrt(3.0) * h;
  long answered = 0, asked = 0, fell_back = 0;
  for (int bk = 0; bk < n; bk += 2)
    for (int bj = 0; bj < n; bj += 2)
      for (int bi = 0; bi < n; bi += 2) {
        const Eigen::Vector3d centre = lo + h * Eigen::Vector3d(bi + 0.5, bj + 0.5, bk + 0.5);
        // Generous: the centre's own distance (capped) plus twice the half diagonal bounds every
        // node's answer; tight: a radius too small for most answers.
        const ClosestPoint at_centre = closest_point(bvh, centre, max_distance);
        const double bound = std::min(at_centre.distance, max_distance) + 2.0 * half_diagonal;
        for (const double radius : {bound * 1.001, 0.5 * half_diagonal}) {
          if (!std::isfinite(radius)) continue;
          FaceShortlist near;
          near.gather(bvh, centre, radius);
          const bool generous = radius > half_diagonal;
          int hint = -1;
          for (int c = 0; c < 8; ++c) {
            const Eigen::Vector3d p = lo + h * Eigen::Vector3d(bi + (c & 1), bj + ((c >> 1) & 1), bk + ((c >> 2) & 1));
            const ClosestPoint want = closest_point(bvh, p, max_distance);
            const long before = near.fallbacks;
            const ClosestPoint got = near.nearest(bvh, p, max_distance, hint);
            ++asked;
            if (near.fallbacks == before) ++answered;
            else ++fell_back;
            // The list answered, not the tree (unless it held too many faces to keep).
            if (generous && !near.overflowed()) CHECK(near.fallbacks == before);
            CHECK(got.found == want.found);
            CHECK(got.face == want.face);
            CHECK(got.point == want.point);
            CHECK((got.distance == want.distance || (!got.found && !want.found)));
            if (got.found) hint = got.face;
          }
        }
      }
  CHECK(answered > asked / 3);
  CHECK(fell_back > 0);
}

}  // namespace

TEST_CASE("face shortlist: the nearest face of torus nodes, uncapped and capped") {
  const Mesh torus = make_torus(1.0, 0.3, 40, 16);
  check_grid(torus, Eigen::Vector3d(-1.41, -1.37, -0.43), 0.11, 26, std::numeric_limits<double>::infinity());
  check_grid(torus, Eigen::Vector3d(-1.41, -1.37, -0.43), 0.11, 26, 0.2);
}

TEST_CASE("face shortlist: ties between coplanar faces of a box go to the lowest index") {
  // Nodes on the box's mirror planes and diagonals are equally near several faces.
  const Mesh box = make_box({0, 0, 0}, {2, 2, 2});
  check_grid(box, Eigen::Vector3d(-0.5, -0.5, -0.5), 0.25, 12, std::numeric_limits<double>::infinity());
  check_grid(box, Eigen::Vector3d(-0.5, -0.5, -0.5), 0.25, 12, 0.6);
}

TEST_CASE("face shortlist: a sphere's nodes inside and out") {
  const Mesh sphere = make_icosphere(1.0, 3);
  check_grid(sphere, Eigen::Vector3d(-1.3, -1.2, -1.25), 0.1, 26, std::numeric_limits<double>::infinity());
  check_grid(sphere, Eigen::Vector3d(-1.3, -1.2, -1.25), 0.1, 26, 0.15);
}

TEST_CASE("face shortlist: a region with more than kMaxFaces faces is left to closest_point") {
  // An icosphere of 5,120 faces gathered whole: the list keeps none, and every answer is the
  // tree's, to the last bit.
  const Mesh sphere = make_icosphere(1.0, 4);
  REQUIRE(static_cast<std::size_t>(sphere.F.rows()) > FaceShortlist::kMaxFaces);
  const TriangleBvh bvh(sphere.V, sphere.F);
  FaceShortlist near;
  near.gather(bvh, Eigen::Vector3d::Zero(), 3.0);
  CHECK(near.overflowed());
  CHECK(near.size() == 0);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.9, 0.0, 0.1), Eigen::Vector3d(1.5, -0.2, 0.4)}) {
    const long before = near.fallbacks;
    const ClosestPoint want = closest_point(bvh, p), got = near.nearest(bvh, p);
    CHECK(near.fallbacks == before + 1);
    CHECK(got.face == want.face);
    CHECK(got.point == want.point);
    CHECK(got.distance == want.distance);
  }
  near.gather(bvh, Eigen::Vector3d(1.0, 0.0, 0.0), 0.1);  // a small region: kept
  CHECK(!near.overflowed());
  CHECK(near.size() > 0);
  CHECK(near.size() <= FaceShortlist::kMaxFaces);
}
