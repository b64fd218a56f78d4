#include "meshio/triangulate_obj_face.h"

#include <cmath>

namespace offsetopt {

namespace {

struct Point2 {
  double u, v;
};

// Twice the signed area of (a, b, c): positive when counter-clockwise.
double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

bool same(const Point2& a, const Point2& b) { return a.u == b.u && a.v == b.v; }

void fan(int n, std::vector<int>& triangles) {
  triangles.clear();
  for (int i = 1; i + 1 < n; ++i) triangles.insert(triangles.end(), {0, i, i + 1});
}

}  // namespace

PolygonTriangulationStatus triangulate_obj_face(const std::vector<Eigen::Vector3d>& points, std::vector<int>& triangles,
                                                long long& budget) {
  const int n = static_cast<int>(points.size());
  triangles.clear();
  if (n <= 3) {
    fan(n, triangles);
    return PolygonTriangulationStatus::fan;
  }
  // Newell's normal, about the first corner (smaller numbers, less rounding).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = points[static_cast<std::size_t>(i)] - points[0];
    const Eigen::Vector3d b = points[static_cast<std::size_t>((i + 1) % n)] - points[0];
    normal.x() += (a.y() - b.y()) * (a.z() + b.z());
    normal.y() += (a.z() - b.z()) * (a.x() + b.x());
    normal.z() += (a.x() - b.x()) * (a.y() + b.y());
  }
  if (!normal.allFinite() || normal.isZero(0.0)) {
    fan(n, triangles);
    return PolygonTriangulationStatus::fan;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::fabs(normal[k]) > std::fabs(normal[axis])) axis = k;
  // (axis + 1, axis + 2) is a right-handed pair around the axis; mirrored when the normal points
  // the other way, so the projected outline is counter-clockwise.
  const int iu = (axis + 1) % 3, iv = (axis + 2) % 3;
  const double mirror = normal[axis] < 0.0 ? -1.0 : 1.0;
  std::vector<Point2> p(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    p[static_cast<std::size_t>(i)] = {mirror * (points[static_cast<std::size_t>(i)][iu] - points[0][iu]),
                                      points[static_cast<std::size_t>(i)][iv] - points[0][iv]};

  std::vector<int> prev(static_cast<std::size_t>(n)), next(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    prev[static_cast<std::size_t>(i)] = (i + n - 1) % n;
    next[static_cast<std::size_t>(i)] = (i + 1) % n;
  }
  auto corner_orient = [&](int i) {
    return orient(p[static_cast<std::size_t>(prev[static_cast<std::size_t>(i)])], p[static_cast<std::size_t>(i)],
                  p[static_cast<std::size_t>(next[static_cast<std::size_t>(i)])]);
  };
  bool any_reflex = false;
  for (int i = 0; i < n && !any_reflex; ++i) any_reflex = corner_orient(i) < 0.0;
  if (!any_reflex) {
    fan(n, triangles);
    return PolygonTriangulationStatus::fan;
  }

  auto is_ear = [&](int i) {
    if (!(corner_orient(i) > 0.0)) return false;
    const int a = prev[static_cast<std::size_t>(i)], c = next[static_cast<std::size_t>(i)];
    const Point2 &pa = p[static_cast<std::size_t>(a)], &pb = p[static_cast<std::size_t>(i)], &pc = p[static_cast<std::size_t>(c)];
    for (int j = next[static_cast<std::size_t>(c)]; j != a; j = next[static_cast<std::size_t>(j)]) {
      --budget;
      const Point2& q = p[static_cast<std::size_t>(j)];
      if (same(q, pa) || same(q, pb) || same(q, pc)) continue;
      if (orient(pa, pb, q) >= 0.0 && orient(pb, pc, q) >= 0.0 && orient(pc, pa, q) >= 0.0) return false;
    }
    return true;
  };

  triangles.reserve(static_cast<std::size_t>(3 * (n - 2)));
  int remaining = n, current = 0, since_ear = 0;
  while (remaining > 3) {
    if (budget < 0) {
      triangles.clear();
      return PolygonTriangulationStatus::budget_exhausted;
    }
    bool clip = is_ear(current);
    if (!clip && since_ear >= remaining) {
      // A full turn without an ear (self-intersecting outline): clip the first corner that is
      // not reflex, or this one, so the polygon still gives n - 2 triangles.
      int j = current;
      for (int k = 0; k < remaining && corner_orient(j) < 0.0; ++k) j = next[static_cast<std::size_t>(j)];
      current = j;
      clip = true;
    }
    if (!clip) {
      current = next[static_cast<std::size_t>(current)];
      ++since_ear;
      continue;
    }
    const int a = prev[static_cast<std::size_t>(current)], c = next[static_cast<std::size_t>(current)];
    triangles.insert(triangles.end(), {a, current, c});
    next[static_cast<std::size_t>(a)] = c;
    prev[static_cast<std::size_t>(c)] = a;
    --remaining;
    current = a;  // its corner changed: test it first
    since_ear = 0;
  }
  triangles.insert(triangles.end(), {prev[static_cast<std::size_t>(current)], current, next[static_cast<std::size_t>(current)]});
  return PolygonTriangulationStatus::ear_clipping;
}

}  // namespace offsetopt
