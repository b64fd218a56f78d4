// Triangle-triangle and segment-segment distances (geometry/triangle_distance.h) against closed
// forms (parallel triangles, skew edges) and against brute force: the least distance over a dense
// barycentric sampling of both triangles bounds the exact one from above, and from below within
// the sampling's spacing.
#include <doctest/doctest.h>

#include <cmath>

#include "geometry/triangle_distance.h"
#include "util/rng.h"

using namespace offsetopt;
using Eigen::Vector3d;

namespace {

Vector3d point_of(const Vector3d& a, const Vector3d& b, const Vector3d& c, int i, int j, int n) {
  return a + (static_cast<double>(i) / n) * (b - a) + (static_cast<double>(j) / n) * (c - a);
}

// Least distance between the sampled points, and the largest distance from any point of either
// triangle to its nearest sample (half a sampling cell's diameter, bounded by the longest edge / n).
double sampled_distance(const Vector3d& a0, const Vector3d& a1, const Vector3d& a2, const Vector3d& b0,
                        const Vector3d& b1, const Vector3d& b2, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const Vector3d p = point_of(a0, a1, a2, i, j, n);
      for (int k = 0; k <= n; ++k)
        for (int l = 0; k + l <= n; ++l) best = std::min(best, (p - point_of(b0, b1, b2, k, l, n)).norm());
    }
  return best;
}

double longest_edge(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  return std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
}

}  // namespace

TEST_CASE("triangle distance: closed forms") {
  // Parallel triangles 0.7 apart, one over the other's interior.
  CHECK(triangle_distance({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0.7}, {2, 1, 0.7}, {1, 2, 0.7}) ==
        doctest::Approx(0.7).epsilon(1e-14));
  // Skew edges: the x-axis segment and a segment along y at height 2, crossing over it.
  CHECK(segment_distance({-1, 0, 0}, {1, 0, 0}, {0.3, -1, 2}, {0.3, 1, 2}) == doctest::Approx(2.0).epsilon(1e-14));
  // Parallel segments side by side, overlapping in x.
  CHECK(segment_distance({0, 0, 0}, {2, 0, 0}, {1, 0.5, 0}, {3, 0.5, 0}) == doctest::Approx(0.5).epsilon(1e-14));
  // Collinear, apart by a gap of 1.5.
  CHECK(segment_distance({0, 0, 0}, {1, 0, 0}, {2.5, 0, 0}, {4, 0, 0}) == doctest::Approx(1.5).epsilon(1e-14));
  // Edge to edge: two triangles whose nearest features are a pair of crossing edges, 1 apart.
  CHECK(triangle_distance({-1, 0, 0}, {1, 0, 0}, {0, 0, -3}, {0, -1, 1}, {0, 1, 1}, {0, 0, 4}) ==
        doctest::Approx(1.0).epsilon(1e-14));
  // Crossing triangles are 0 apart.
  CHECK(triangle_distance({-1, -1, 0}, {2, -1, 0}, {-1, 2, 0}, {0, 0, -1}, {0.2, 0.1, 1}, {0.3, -0.2, 1}) == 0.0);
}

TEST_CASE("triangle distance: within the sampling's error of brute force, never above it") {
  Rng rng(20261125);
  const int n = 24;
  for (int trial = 0; trial < 60; ++trial) {
    Vector3d v[6];
    for (auto& p : v) p = Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    // Half the pairs pushed apart a little, so near-touching and separated cases both occur.
    if (trial % 2) for (int k = 3; k < 6; ++k) v[k].z() += 1.2;
    const double exact = triangle_distance(v[0], v[1], v[2], v[3], v[4], v[5]);
    const double sampled = sampled_distance(v[0], v[1], v[2], v[3], v[4], v[5], n);
    const double spacing = (longest_edge(v[0], v[1], v[2]) + longest_edge(v[3], v[4], v[5])) / n;
    CHECK(exact <= sampled + 1e-12);
    CHECK(exact >= sampled - spacing);
    CHECK(triangle_distance(v[3], v[4], v[5], v[0], v[1], v[2]) == doctest::Approx(exact).epsilon(1e-12));
  }
}
