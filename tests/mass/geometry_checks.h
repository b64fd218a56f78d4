// Test-only geometry checks for the demo meshes, independent of the code under test: triangle
// intersections (edge-through-triangle with orientation signs, sweep over bounding boxes) and
// point-to-triangle distance (Ericson, "Real-Time Collision Detection", 5.1.5).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mesh/mesh.h"

namespace offsetopt::test {

inline double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Does segment pq cross the interior of triangle abc properly? Signs within a relative 1e-9 of
// zero count as touching, not crossing: the demo meshes have many exactly coplanar facets
// (revolution strips, flat caps) whose rounding noise must not read as crossings. Coplanar
// overlaps are therefore not detected, which only a fold-over could produce.
inline bool segment_crosses_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  auto sign = [](double value, double scale) { return value > 1e-9 * scale ? 1 : (value < -1e-9 * scale ? -1 : 0); };
  const double normal = (b - a).cross(c - a).norm();
  const int sp = sign(orient3d(a, b, c, p), normal * (p - a).norm());
  const int sq = sign(orient3d(a, b, c, q), normal * (q - a).norm());
  if (sp == 0 || sq == 0 || sp == sq) return false;
  const double pq = (q - p).norm();
  const int s1 = sign(orient3d(p, q, a, b), pq * (a - p).norm() * (b - p).norm());
  const int s2 = sign(orient3d(p, q, b, c), pq * (b - p).norm() * (c - p).norm());
  const int s3 = sign(orient3d(p, q, c, a), pq * (c - p).norm() * (a - p).norm());
  return s1 != 0 && s1 == s2 && s2 == s3;
}

struct TriangleSoup {
  std::vector<std::array<Eigen::Vector3d, 3>> corners;
  std::vector<std::array<int, 3>> ids;  // global vertex ids, to skip pairs that share a vertex
  std::vector<int> part;                // which mesh a triangle came from
};

inline void add_to_soup(TriangleSoup& soup, const Mesh& mesh, int part, int id_offset) {
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    soup.corners.push_back({mesh.V.row(mesh.F(f, 0)).transpose(), mesh.V.row(mesh.F(f, 1)).transpose(),
                            mesh.V.row(mesh.F(f, 2)).transpose()});
    soup.ids.push_back({mesh.F(f, 0) + id_offset, mesh.F(f, 1) + id_offset, mesh.F(f, 2) + id_offset});
    soup.part.push_back(part);
  }
}

// Number of pairs of triangles that share no vertex and cross each other. When `across_only`,
// only pairs from different parts count.
inline int count_crossing_pairs(const TriangleSoup& soup, bool across_only = false) {
  const std::size_t n = soup.corners.size();
  std::vector<Eigen::Vector3d> lo(n), hi(n);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = soup.corners[i][0].cwiseMin(soup.corners[i][1]).cwiseMin(soup.corners[i][2]);
    hi[i] = soup.corners[i][0].cwiseMax(soup.corners[i][1]).cwiseMax(soup.corners[i][2]);
    order[i] = i;
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo[a].x() < lo[b].x() || (lo[a].x() == lo[b].x() && a < b); });
  int crossings = 0;
  for (std::size_t oi = 0; oi < n; ++oi) {
    const std::size_t i = order[oi];
    for (std::size_t oj = oi + 1; oj < n && lo[order[oj]].x() <= hi[i].x(); ++oj) {
      const std::size_t j = order[oj];
      if (across_only && soup.part[i] == soup.part[j]) continue;
      if (lo[j].y() > hi[i].y() || hi[j].y() < lo[i].y() || lo[j].z() > hi[i].z() || hi[j].z() < lo[i].z()) continue;
      bool shared = false;
      for (int a : soup.ids[i])
        for (int b : soup.ids[j]) shared = shared || a == b;
      if (shared) continue;
      const auto& t = soup.corners[i];
      const auto& u = soup.corners[j];
      bool cross = false;
      for (int e = 0; e < 3 && !cross; ++e) {
        cross = segment_crosses_triangle(t[e], t[(e + 1) % 3], u[0], u[1], u[2]) ||
                segment_crosses_triangle(u[e], u[(e + 1) % 3], t[0], t[1], t[2]);
      }
      if (cross) ++crossings;
    }
  }
  return crossings;
}

inline int self_intersections(const Mesh& mesh) {
  TriangleSoup soup;
  add_to_soup(soup, mesh, 0, 0);
  return count_crossing_pairs(soup);
}

inline int crossings_between(const Mesh& a, const Mesh& b) {
  TriangleSoup soup;
  add_to_soup(soup, a, 0, 0);
  add_to_soup(soup, b, 1, static_cast<int>(a.V.rows()));
  return count_crossing_pairs(soup, true);
}

inline Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                 const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Smallest distance from any vertex of `inner` to the surface `outer` (brute force).
inline double min_vertex_distance(const Mesh& inner, const Mesh& outer) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < inner.V.rows(); ++i) {
    const Eigen::Vector3d p = inner.V.row(i).transpose();
    for (Eigen::Index f = 0; f < outer.F.rows(); ++f) {
      const Eigen::Vector3d a = outer.V.row(outer.F(f, 0)).transpose();
      const Eigen::Vector3d b = outer.V.row(outer.F(f, 1)).transpose();
      const Eigen::Vector3d c = outer.V.row(outer.F(f, 2)).transpose();
      const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
      // Skip triangles whose box is already farther than the best distance.
      const Eigen::Vector3d gap = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
      if (gap.squaredNorm() >= best * best) continue;
      best = std::min(best, (closest_point_on_triangle(p, a, b, c) - p).norm());
    }
  }
  return best;
}

// Generalised winding number of a closed oriented mesh around p (van Oosterom-Strackee solid
// angles): 1 inside, 0 outside.
inline double winding_number(const Mesh& mesh, const Eigen::Vector3d& p) {
  double total = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)).transpose() - p;
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1)).transpose() - p;
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2)).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * 3.141592653589793);
}

}  // namespace offsetopt::test
