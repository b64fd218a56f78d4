#include "geometry/convex_hull_2d.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "util/exact_expansion.h"

namespace offsetopt {

namespace {

double orient2d_exact(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  // (ax − cx)(by − cy) − (ay − cy)(bx − cx) with each difference kept as an exact pair.
  double acx, acx_e, bcy, bcy_e, acy, acy_e, bcx, bcx_e;
  two_sum(a.x(), -c.x(), acx, acx_e);
  two_sum(b.y(), -c.y(), bcy, bcy_e);
  two_sum(a.y(), -c.y(), acy, acy_e);
  two_sum(b.x(), -c.x(), bcx, bcx_e);
  const double left[2] = {acx, acx_e}, right_left[2] = {bcy, bcy_e};
  const double up[2] = {acy, acy_e}, right_up[2] = {bcx, bcx_e};
  std::array<double, 40> expansion{};
  std::size_t length = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double p, e;
      two_product(left[i], right_left[j], p, e);
      grow_expansion(expansion, length, e);
      grow_expansion(expansion, length, p);
      two_product(up[i], right_up[j], p, e);
      grow_expansion(expansion, length, -e);
      grow_expansion(expansion, length, -p);
    }
  for (std::size_t i = length; i-- > 0;)
    if (expansion[i] != 0.0) return expansion[i];
  return 0.0;
}

}  // namespace

double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y());
  const double right = (a.y() - c.y()) * (b.x() - c.x());
  const double det = left - right;
  // Shewchuk's bound for the plain evaluation: (3 + 16 eps) eps (|left| + |right|), eps = 2^-53.
  const double bound = 3.3306690738754716e-16 * (std::fabs(left) + std::fabs(right));
  if (std::fabs(det) > bound) return det;
  // Three points on one axis-parallel line are collinear (projections of grid-plane points).
  if ((a.x() == b.x() && a.x() == c.x()) || (a.y() == b.y() && a.y() == c.y())) return 0.0;
  return orient2d_exact(a, b, c);
}

std::vector<Eigen::Vector2d> convex_hull_2d(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    return p.x() < q.x() || (p.x() == q.x() && p.y() < q.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() <= 2) return points;
  std::vector<Eigen::Vector2d> hull;
  hull.reserve(2 * points.size());
  // Lower chain left to right, then upper chain right to left; pop on clockwise or collinear.
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (hull.size() >= 2 && orient2d(hull[hull.size() - 2], hull.back(), points[i]) <= 0.0) hull.pop_back();
    hull.push_back(points[i]);
  }
  const std::size_t lower_size = hull.size() + 1;
  for (std::size_t i = points.size() - 1; i-- > 0;) {
    while (hull.size() >= lower_size && orient2d(hull[hull.size() - 2], hull.back(), points[i]) <= 0.0) hull.pop_back();
    hull.push_back(points[i]);
  }
  hull.pop_back();  // the first point again
  return hull;
}

}  // namespace offsetopt
