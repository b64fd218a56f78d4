// Axis-aligned bounding box and the slab test a BVH traversal needs. Boxes are closed
// ([lo, hi] per axis); an empty box has lo = +inf, hi = -inf so `extend` works from it.
#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <utility>

namespace offsetopt {

struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  void extend(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool empty() const { return !(lo.x() <= hi.x() && lo.y() <= hi.y() && lo.z() <= hi.z()); }
  bool overlaps(const Aabb& b) const {
    return lo.x() <= b.hi.x() && b.lo.x() <= hi.x() && lo.y() <= b.hi.y() && b.lo.y() <= hi.y() &&
           lo.z() <= b.hi.z() && b.lo.z() <= hi.z();
  }
  bool contains(const Eigen::Vector3d& p) const {
    return lo.x() <= p.x() && p.x() <= hi.x() && lo.y() <= p.y() && p.y() <= hi.y() && lo.z() <= p.z() &&
           p.z() <= hi.z();
  }
  // Whether the closed segment p-q lies strictly beyond the box along one axis: then they share
  // no point, decided by comparisons alone.
  bool apart_from_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
    for (int a = 0; a < 3; ++a)
      if (std::max(p[a], q[a]) < lo[a] || std::min(p[a], q[a]) > hi[a]) return true;
    return false;
  }
  Eigen::Vector3d center() const { return 0.5 * (lo + hi); }
  // Squared distance from p to the box (0 inside): the bound of a nearest-face walk.
  double squared_distance(const Eigen::Vector3d& p) const {
    double d = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double excess = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > hi[a] ? p[a] - hi[a] : 0.0);
      d += excess * excess;
    }
    return d;
  }
  // Index of the longest side (the lowest index on ties, so splits are reproducible).
  int longest_axis() const {
    const Eigen::Vector3d e = hi - lo;
    return e.x() >= e.y() ? (e.x() >= e.z() ? 0 : 2) : (e.y() >= e.z() ? 1 : 2);
  }
  // Grows the box by `margin` on every side (used to make box tests conservative).
  Aabb inflated(double margin) const {
    Aabb b = *this;
    b.lo.array() -= margin;
    b.hi.array() += margin;
    return b;
  }
};

// The box of the rows of an n×3 matrix of points (a mesh's V); empty when there is none.
template <class Points>
Aabb bounding_box(const Points& points) {
  Aabb box;
  for (Eigen::Index i = 0; i < points.rows(); ++i) box.extend(points.row(i).transpose());
  return box;
}

// Parameter interval [t_enter, t_exit] of the ray origin + t * direction inside `box`, clipped to
// [t_min, t_max]; false when it is empty. `inverse_direction` is 1/direction componentwise
// (+-inf for a zero component). The comparisons are written so a NaN from 0 * inf (origin on a
// slab plane of a zero-direction axis) keeps the interval instead of rejecting it: conservative.
inline bool ray_box_interval(const Eigen::Vector3d& origin, const Eigen::Vector3d& inverse_direction, const Aabb& box,
                             double t_min, double t_max, double& t_enter, double& t_exit) {
  double lo = t_min, hi = t_max;
  for (int a = 0; a < 3; ++a) {
    double t0 = (box.lo[a] - origin[a]) * inverse_direction[a];
    double t1 = (box.hi[a] - origin[a]) * inverse_direction[a];
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > lo) lo = t0;  // NaN compares false: interval kept
    if (t1 < hi) hi = t1;
  }
  t_enter = lo;
  t_exit = hi;
  return lo <= hi;
}

}  // namespace offsetopt
