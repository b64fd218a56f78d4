// A box standing on a strip at one end of its base, the closed form behind the reachability tests
// (tests/cavity, tests/optimize): the smallest centroid x any void reaches is that of carving the
// carvable box beyond the final centroid (a half-box cut by a plane).
#pragma once
#include "shape/goal.h"

namespace offsetopt::test {

// Box [0,a]×[0,b]×[0,c]; the carvable box is it shrunk by `shrink` on every side. The smallest
// centroid x any void reaches: carve {x > x*} of the carvable box, with x* the centroid itself.
inline double min_centroid_x(double a, double b, double c, double shrink) {
  const double V = a * b * c, area = (b - 2 * shrink) * (c - 2 * shrink), U = a - shrink;
  double x = 0.5 * a;
  for (int i = 0; i < 200; ++i) x = (V * 0.5 * a - area * 0.5 * (U * U - x * x)) / (V - area * (U - x));
  return x;
}

// Stand on the strip [0, width] × [0, b] by `margin`.
inline GoalSpec strip_goal(double width, double b, double margin) {
  GoalSpec g;
  g.kind = GoalKind::stand;
  g.support_polygon = {Eigen::Vector2d(0, 0), Eigen::Vector2d(width, 0), Eigen::Vector2d(width, b), Eigen::Vector2d(0, b)};
  g.margin = margin;
  return g;
}

}  // namespace offsetopt::test
