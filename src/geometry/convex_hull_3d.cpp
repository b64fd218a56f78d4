#include "geometry/convex_hull_3d.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <cstdint>

#include <Eigen/Geometry>

#include "util/disjoint_sets.h"
#include "util/exact_expansion.h"

namespace offsetopt {

namespace {

// grow_expansion (util/exact_expansion.h) dropping zero components: the expansion stays exact
// and short. Coplanar inputs (every call of a flat CAD face's fan) end here, and most of the
// 192 products below are zero because most coordinate differences are exact.
void grow_without_zeros(std::array<double, 200>& e, std::size_t& length, double term) {
  if (term == 0.0) return;
  double q = term;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < length; ++i) {
    double sum, error;
    two_sum(q, e[i], sum, error);
    if (error != 0.0) e[kept++] = error;
    q = sum;
  }
  if (q != 0.0) e[kept++] = q;
  length = kept;
}

double orient3d_exact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  // det [b − a; c − a; d − a], each difference an exact (value, error) pair, each of the 6 × 8
  // triple products an exact sum of 4 doubles.
  double u[3][2], v[3][2], w[3][2];
  for (int k = 0; k < 3; ++k) {
    two_sum(b[k], -a[k], u[k][0], u[k][1]);
    two_sum(c[k], -a[k], v[k][0], v[k][1]);
    two_sum(d[k], -a[k], w[k][0], w[k][1]);
  }
  // (row-u index, row-v index, row-w index, sign) of the Leibniz expansion.
  static const int terms[6][4] = {{0, 1, 2, 1}, {0, 2, 1, -1}, {1, 0, 2, -1}, {1, 2, 0, 1}, {2, 0, 1, 1}, {2, 1, 0, -1}};
  std::array<double, 200> expansion{};
  std::size_t length = 0;
  for (const auto& t : terms)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k) {
          const double x = u[t[0]][i], y = v[t[1]][j], z = w[t[2]][k];
          if (x == 0.0 || y == 0.0 || z == 0.0) continue;
          double p1, e1, p2, e2, p3, e3;
          two_product(x, y, p1, e1);
          two_product(p1, z, p2, e2);
          two_product(e1, z, p3, e3);
          const double sign = t[3];
          grow_without_zeros(expansion, length, sign * e3);
          grow_without_zeros(expansion, length, sign * e2);
          grow_without_zeros(expansion, length, sign * p3);
          grow_without_zeros(expansion, length, sign * p2);
        }
  // Nonoverlapping and sorted by magnitude: the last component carries the sign.
  return length == 0 ? 0.0 : expansion[length - 1];
}

struct HullFace {
  std::array<int, 3> v;          // point indices, counter-clockwise from outside
  std::array<int, 3> neighbor;   // face across edge v[i] -> v[(i + 1) % 3]
  std::vector<int> outside;      // points strictly above this face, not yet on the hull
  bool alive = true;
};

class Quickhull {
 public:
  explicit Quickhull(const std::vector<Eigen::Vector3d>& points) : p_(points) {}

  double above(const HullFace& f, int point) const { return orient3d(p_[f.v[0]], p_[f.v[1]], p_[f.v[2]], p_[point]); }

  // The starting tetrahedron: extreme points in x, then the farthest from their line, then the
  // farthest from that plane; first index on ties so the result is deterministic.
  ConvexHullStatus start(std::string& message) {
    const int n = static_cast<int>(p_.size());
    int lo = 0, hi = 0;
    for (int i = 1; i < n; ++i) {
      if (lexicographic_less(p_[i], p_[lo])) lo = i;
      if (lexicographic_less(p_[hi], p_[i])) hi = i;
    }
    if (n < 4 || p_[lo] == p_[hi]) {
      message = "fewer than 4 distinct points";
      return ConvexHullStatus::too_few_points;
    }
    int third = -1;
    double best = 0.0;
    const Eigen::Vector3d axis = p_[hi] - p_[lo];
    for (int i = 0; i < n; ++i) {
      const double d = axis.cross(p_[i] - p_[lo]).squaredNorm();
      if (d > best) best = d, third = i;
    }
    if (third < 0) {
      message = "all points are collinear";
      return ConvexHullStatus::flat;
    }
    int fourth = -1;
    best = 0.0;
    for (int i = 0; i < n; ++i) {
      const double d = std::fabs(orient3d(p_[lo], p_[hi], p_[third], p_[i]));
      if (d > best) best = d, fourth = i;
    }
    if (fourth < 0) {
      message = "all points are coplanar";
      return ConvexHullStatus::flat;
    }
    int a = lo, b = hi, c = third;
    if (orient3d(p_[a], p_[b], p_[c], p_[fourth]) > 0.0) std::swap(b, c);  // the fourth below abc
    const int d = fourth;
    // Faces of tetrahedron abcd, outward: abc, adb, bdc, cda.
    faces_.push_back({{a, b, c}, {1, 2, 3}, {}, true});
    faces_.push_back({{a, d, b}, {3, 2, 0}, {}, true});
    faces_.push_back({{b, d, c}, {1, 3, 0}, {}, true});
    faces_.push_back({{c, d, a}, {2, 1, 0}, {}, true});
    fix_neighbors(0);
    for (int i = 0; i < n; ++i) {
      if (i == a || i == b || i == c || i == d) continue;
      for (int f = 0; f < 4; ++f)
        if (above(faces_[f], i) > 0.0) {
          faces_[f].outside.push_back(i);
          break;
        }
    }
    return ConvexHullStatus::ok;
  }

  // Each new face's neighbors from shared edges (used for the starting tetrahedron only).
  void fix_neighbors(int first) {
    for (int f = first; f < static_cast<int>(faces_.size()); ++f)
      for (int e = 0; e < 3; ++e) {
        const int s = faces_[f].v[e], t = faces_[f].v[(e + 1) % 3];
        for (int g = first; g < static_cast<int>(faces_.size()); ++g)
          for (int h = 0; h < 3; ++h)
            if (faces_[g].v[h] == t && faces_[g].v[(h + 1) % 3] == s) faces_[f].neighbor[e] = g;
      }
  }

  bool run(std::string& message) {
    const long long cap = 8LL * static_cast<long long>(p_.size()) + 64;
    long long steps = 0;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (!faces_[f].alive || faces_[f].outside.empty()) continue;
      if (++steps > cap) {
        message = "convex hull: step cap reached";
        return false;
      }
      add_point(static_cast<int>(f));
    }
    return true;
  }

  std::vector<std::array<int, 3>> triangles(std::vector<std::array<int, 3>>* adjacency) const {
    std::vector<int> new_index(faces_.size(), -1);
    std::vector<std::array<int, 3>> out;
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (faces_[f].alive) {
        new_index[f] = static_cast<int>(out.size());
        out.push_back(faces_[f].v);
      }
    adjacency->clear();
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (faces_[f].alive)
        adjacency->push_back({new_index[faces_[f].neighbor[0]], new_index[faces_[f].neighbor[1]], new_index[faces_[f].neighbor[2]]});
    return out;
  }

 private:
  static bool lexicographic_less(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return a.x() < b.x() || (a.x() == b.x() && (a.y() < b.y() || (a.y() == b.y() && a.z() < b.z())));
  }

  void add_point(int start_face) {
    // The eye: the outside point farthest above the face (first on ties).
    const HullFace& start = faces_[start_face];
    int eye = start.outside[0];
    double best = above(start, eye);
    for (int q : start.outside) {
      const double h = above(start, q);
      if (h > best) best = h, eye = q;
    }
    // Faces the eye sees (strictly), found by flooding from the start face: with an exact
    // predicate they form one disk whose boundary is the horizon.
    std::vector<int> visible{start_face}, stack{start_face}, touched{start_face};
    std::vector<char>& mark = mark_;
    mark.resize(faces_.size(), 0);
    mark[start_face] = 1;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      for (int nb : faces_[f].neighbor) {
        if (mark[nb] != 0) continue;
        if (above(faces_[nb], eye) > 0.0) {
          mark[nb] = 1;
          touched.push_back(nb);
          visible.push_back(nb);
          stack.push_back(nb);
        } else {
          mark[nb] = 2;  // seen, not visible
          touched.push_back(nb);
        }
      }
    }
    // One new face per horizon edge, keeping the edge's direction.
    std::map<int, int> face_starting_at, face_ending_at;
    const int first_new = static_cast<int>(faces_.size());
    std::sort(visible.begin(), visible.end());
    for (int f : visible)
      for (int e = 0; e < 3; ++e) {
        const int nb = faces_[f].neighbor[e];
        if (mark[nb] == 1) continue;
        const int s = faces_[f].v[e], t = faces_[f].v[(e + 1) % 3];
        const int id = static_cast<int>(faces_.size());
        faces_.push_back({{s, t, eye}, {nb, -1, -1}, {}, true});
        for (int h = 0; h < 3; ++h)
          if (faces_[nb].v[h] == t && faces_[nb].v[(h + 1) % 3] == s) faces_[nb].neighbor[h] = id;
        face_starting_at[s] = id;
        face_ending_at[t] = id;
      }
    for (int f = first_new; f < static_cast<int>(faces_.size()); ++f) {
      faces_[f].neighbor[1] = face_starting_at.at(faces_[f].v[1]);
      faces_[f].neighbor[2] = face_ending_at.at(faces_[f].v[0]);
    }
    // Outside points of the removed faces go to the first new face they are above, or are
    // inside the grown hull.
    for (int f : visible) {
      faces_[f].alive = false;
      for (int q : faces_[f].outside) {
        if (q == eye) continue;
        for (int g = first_new; g < static_cast<int>(faces_.size()); ++g)
          if (above(faces_[g], q) > 0.0) {
            faces_[g].outside.push_back(q);
            break;
          }
      }
      std::vector<int>().swap(faces_[f].outside);
    }
    for (int f : touched) mark[f] = 0;
  }

  const std::vector<Eigen::Vector3d>& p_;
  std::vector<HullFace> faces_;
  std::vector<char> mark_;
};

}  // namespace

double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = b - a, v = c - a, w = d - a;
  const double det = u.x() * (v.y() * w.z() - v.z() * w.y()) - u.y() * (v.x() * w.z() - v.z() * w.x()) +
                     u.z() * (v.x() * w.y() - v.y() * w.x());
  const double permanent = std::fabs(u.x()) * (std::fabs(v.y() * w.z()) + std::fabs(v.z() * w.y())) +
                           std::fabs(u.y()) * (std::fabs(v.x() * w.z()) + std::fabs(v.z() * w.x())) +
                           std::fabs(u.z()) * (std::fabs(v.x() * w.y()) + std::fabs(v.y() * w.x()));
  // Shewchuk's bound for this evaluation is 7.8e-16 x permanent; 1e-14 leaves a wide margin.
  if (std::fabs(det) > 1e-14 * permanent) return det;
  // Four points on one axis-aligned plane are coplanar: contoured cavities put their vertices on
  // grid planes, and their exact zeros would otherwise all take the slow path.
  for (int k = 0; k < 3; ++k)
    if (a[k] == b[k] && a[k] == c[k] && a[k] == d[k]) return 0.0;
  return orient3d_exact(a, b, c, d);
}

ConvexHull3d convex_hull_3d(const std::vector<Eigen::Vector3d>& points, double coplanar_tolerance) {
  ConvexHull3d hull;
  Quickhull quickhull(points);
  hull.status = quickhull.start(hull.message);
  if (hull.status != ConvexHullStatus::ok) return hull;
  if (!quickhull.run(hull.message)) {
    hull.status = ConvexHullStatus::too_many_steps;
    return hull;
  }
  std::vector<std::array<int, 3>> adjacency;
  hull.triangles = quickhull.triangles(&adjacency);
  const int count = static_cast<int>(hull.triangles.size());
  std::vector<Eigen::Vector3d> normal(count);
  for (int t = 0; t < count; ++t) {
    const auto& v = hull.triangles[t];
    normal[t] = (points[v[1]] - points[v[0]]).cross(points[v[2]] - points[v[0]]);
  }
  auto has_plane = [&](int t) { return normal[t].squaredNorm() > 0.0; };
  auto distance_to_plane = [&](int t, int point) {
    return std::fabs(normal[t].dot(points[point] - points[hull.triangles[t][0]])) / normal[t].norm();
  };
  auto far_corner = [&](int t, int e, int u) {  // u's corner off the edge e of t
    for (int k = 0; k < 3; ++k)
      if (hull.triangles[u][k] != hull.triangles[t][e] && hull.triangles[u][k] != hull.triangles[t][(e + 1) % 3])
        return hull.triangles[u][k];
    return -1;
  };
  // Two adjacent triangles are one facet when each one's far corner lies within the tolerance of
  // the other's plane. Both, not either: a sliver along a hull edge (corners collinear up to
  // rounding) has a plane that is noise, and its far corner, on the edge, lies in both faces'
  // planes; "either" made it join both, and a sheared box's four long faces one facet.
  DisjointSets coplanar(static_cast<std::size_t>(count));
  std::vector<char> taken(static_cast<std::size_t>(count), 0);
  for (int t = 0; t < count; ++t)
    for (int e = 0; e < 3; ++e) {
      const int u = adjacency[t][e];
      if (u < t || !has_plane(t) || !has_plane(u)) continue;
      if (distance_to_plane(t, far_corner(t, e, u)) <= coplanar_tolerance &&
          distance_to_plane(u, hull.triangles[t][(e + 2) % 3]) <= coplanar_tolerance) {
        coplanar.unite(static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(u));
        taken[t] = taken[u] = 1;
      }
    }
  // A triangle no neighbour took (such a sliver, or one of no area) joins the first neighbour whose
  // plane holds its three corners: one facet, never a bridge between two.
  std::vector<int> join(static_cast<std::size_t>(count), -1);
  for (int t = 0; t < count; ++t) {
    if (taken[t]) continue;
    for (int e = 0; e < 3 && join[t] < 0; ++e) {
      const int u = adjacency[t][e];
      if (!has_plane(u)) continue;
      bool holds = true;
      for (int k = 0; k < 3; ++k) holds = holds && distance_to_plane(u, hull.triangles[t][k]) <= coplanar_tolerance;
      if (holds) join[t] = u;
    }
  }
  for (int t = 0; t < count; ++t)
    if (join[t] >= 0) coplanar.unite(static_cast<std::uint32_t>(t), static_cast<std::uint32_t>(join[t]));
  std::map<int, int> facet_of_root;
  for (int t = 0; t < count; ++t) {
    const int root = static_cast<int>(coplanar.find(static_cast<std::uint32_t>(t)));
    auto it = facet_of_root.find(root);
    if (it == facet_of_root.end()) {
      it = facet_of_root.emplace(root, static_cast<int>(hull.facets.size())).first;
      hull.facets.emplace_back();
    }
    ConvexHullFacet& facet = hull.facets[it->second];
    facet.triangles.push_back(t);
    facet.normal += normal[t];
    facet.area += 0.5 * normal[t].norm();
    for (int k = 0; k < 3; ++k) facet.vertices.push_back(hull.triangles[t][k]);
  }
  for (ConvexHullFacet& facet : hull.facets) {
    std::sort(facet.vertices.begin(), facet.vertices.end());
    facet.vertices.erase(std::unique(facet.vertices.begin(), facet.vertices.end()), facet.vertices.end());
    const double length = facet.normal.norm();
    if (length > 0.0) facet.normal /= length;
  }
  return hull;
}

}  // namespace offsetopt
