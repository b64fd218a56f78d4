#include "geometry/triangulate_polygons.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "geometry/convex_hull_2d.h"

namespace offsetopt {

namespace {

struct Node {
  int index;  // global point index
  Eigen::Vector2d p;
  int prev, next;  // positions in the node pool
};

// Crossing-number test; `p` is assumed off the boundary (the loops are disjoint).
bool inside_loop(const std::vector<Eigen::Vector2d>& loop, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Eigen::Vector2d& a = loop[j];
    const Eigen::Vector2d& b = loop[i];
    if ((a.y() > p.y()) == (b.y() > p.y())) continue;
    const double o = orient2d(a, b, p);
    if (b.y() > a.y() ? o > 0.0 : o < 0.0) inside = !inside;
  }
  return inside;
}

class EarClipper {
 public:
  // Appends a closed ring; returns the position of its first node.
  int add_ring(const std::vector<Eigen::Vector2d>& loop, int first_index) {
    const int start = static_cast<int>(nodes_.size());
    const int n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i)
      nodes_.push_back({first_index + i, loop[i], start + (i + n - 1) % n, start + (i + 1) % n});
    return start;
  }

  // Joins the hole ring starting at `hole` into the ring containing `outer` through a bridge
  // from the hole's rightmost point to a vertex it sees along +x. False when none is found.
  bool bridge(int outer, int hole) {
    int m = hole;
    for (int q = nodes_[hole].next; q != hole; q = nodes_[q].next)
      if (nodes_[q].p.x() > nodes_[m].p.x()) m = q;
    const Eigen::Vector2d M = nodes_[m].p;
    // The nearest boundary point hit by the ray from M along +x: the boundary to the right of a
    // hole runs upwards (counter-clockwise outer boundary, clockwise holes already joined).
    double hit_x = std::numeric_limits<double>::infinity();
    int target = -1;
    int q = outer;
    do {
      const Node& a = nodes_[q];
      const Node& b = nodes_[a.next];
      if (a.p.y() <= M.y() && M.y() <= b.p.y() && a.p.y() != b.p.y()) {
        const double x = a.p.x() + (M.y() - a.p.y()) * (b.p.x() - a.p.x()) / (b.p.y() - a.p.y());
        if (x >= M.x() && x < hit_x) {
          hit_x = x;
          target = a.p.x() > b.p.x() ? q : a.next;
        }
      }
      q = a.next;
    } while (q != outer);
    if (target < 0) return false;
    // A vertex inside the triangle (M, hit, target) would block the bridge: take the one seen
    // at the smallest angle from the ray instead (then the closest).
    if (hit_x != nodes_[target].p.x() || M.y() != nodes_[target].p.y()) {
      const Eigen::Vector2d hit(hit_x, M.y());
      const Eigen::Vector2d T = nodes_[target].p;
      double best_tan = std::fabs(T.y() - M.y()) / (T.x() - M.x());
      q = outer;
      do {
        const Node& c = nodes_[q];
        if (q != target && c.p.x() > M.x() && c.p.x() <= T.x() && in_closed_triangle_either_way(M, hit, T, c.p) &&
            sees_inside(q, M)) {
          const double tan = std::fabs(c.p.y() - M.y()) / (c.p.x() - M.x());
          if (tan < best_tan || (tan == best_tan && c.p.x() < nodes_[target].p.x())) {
            best_tan = tan;
            target = q;
          }
        }
        q = c.next;
      } while (q != outer);
    }
    // target -> M -> hole ... -> M' -> target' -> old successor of target.
    const int m_copy = static_cast<int>(nodes_.size());
    nodes_.push_back(nodes_[m]);
    const int t_copy = static_cast<int>(nodes_.size());
    nodes_.push_back(nodes_[target]);
    const int after_target = nodes_[target].next;
    const int before_m = nodes_[m].prev;
    nodes_[target].next = m;
    nodes_[m].prev = target;
    nodes_[before_m].next = m_copy;
    nodes_[m_copy].prev = before_m;
    nodes_[m_copy].next = t_copy;
    nodes_[t_copy].prev = m_copy;
    nodes_[t_copy].next = after_target;
    nodes_[after_target].prev = t_copy;
    return true;
  }

  TriangulationStatus clip(int start, std::vector<std::array<int, 3>>& triangles) {
    int count = 1;
    for (int q = nodes_[start].next; q != start; q = nodes_[q].next) ++count;
    long long steps = 0;
    const long long cap = 4LL * count * count + 64;
    int node = start, stop = start;
    // Slivers first refused: a point nearly on the line of its neighbours (a planar quad's
    // diagonal crossing the cut) would make an ear of almost no area; any ear is taken only
    // when a whole turn finds no well-shaped one.
    bool well_shaped_only = true;
    while (count > 3) {
      if (++steps > cap) return TriangulationStatus::too_many_steps;
      const int a = nodes_[node].prev, c = nodes_[node].next;
      if (is_ear(node) && (!well_shaped_only || well_shaped(node))) {
        well_shaped_only = true;
        triangles.push_back({nodes_[a].index, nodes_[node].index, nodes_[c].index});
        nodes_[a].next = c;
        nodes_[c].prev = a;
        --count;
        node = stop = c;
        continue;
      }
      node = c;
      if (node == stop) {
        if (!well_shaped_only) return TriangulationStatus::no_ear;
        well_shaped_only = false;
      }
    }
    const int a = nodes_[node].prev, c = nodes_[node].next;
    if (!(orient2d(nodes_[a].p, nodes_[node].p, nodes_[c].p) > 0.0)) return TriangulationStatus::no_ear;
    triangles.push_back({nodes_[a].index, nodes_[node].index, nodes_[c].index});
    return TriangulationStatus::ok;
  }

 private:
  static bool in_closed_triangle_either_way(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                            const Eigen::Vector2d& p) {
    const double o1 = orient2d(a, b, p), o2 = orient2d(b, c, p), o3 = orient2d(c, a, p);
    return (o1 >= 0.0 && o2 >= 0.0 && o3 >= 0.0) || (o1 <= 0.0 && o2 <= 0.0 && o3 <= 0.0);
  }

  static bool in_closed_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                                 const Eigen::Vector2d& p) {
    return orient2d(a, b, p) >= 0.0 && orient2d(b, c, p) >= 0.0 && orient2d(c, a, p) >= 0.0;
  }

  // Whether the direction from node q to `target` starts into the polygon's interior (on the
  // left of the counter-clockwise boundary) at q.
  bool sees_inside(int q, const Eigen::Vector2d& target) const {
    const Eigen::Vector2d& a = nodes_[nodes_[q].prev].p;
    const Eigen::Vector2d& p = nodes_[q].p;
    const Eigen::Vector2d& b = nodes_[nodes_[q].next].p;
    if (orient2d(a, p, b) > 0.0) return orient2d(a, p, target) > 0.0 && orient2d(p, b, target) > 0.0;
    return orient2d(a, p, target) > 0.0 || orient2d(p, b, target) > 0.0;
  }

  // Twice the area at least 1e-6 times the longest side squared.
  bool well_shaped(int node) const {
    const Eigen::Vector2d& a = nodes_[nodes_[node].prev].p;
    const Eigen::Vector2d& b = nodes_[node].p;
    const Eigen::Vector2d& c = nodes_[nodes_[node].next].p;
    const double longest = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    return orient2d(a, b, c) >= 1e-6 * longest;
  }

  bool is_ear(int node) const {
    const Node& b = nodes_[node];
    const Node& a = nodes_[b.prev];
    const Node& c = nodes_[b.next];
    if (!(orient2d(a.p, b.p, c.p) > 0.0)) return false;
    const double lo_x = std::min({a.p.x(), b.p.x(), c.p.x()}), hi_x = std::max({a.p.x(), b.p.x(), c.p.x()});
    const double lo_y = std::min({a.p.y(), b.p.y(), c.p.y()}), hi_y = std::max({a.p.y(), b.p.y(), c.p.y()});
    // Only a vertex that is not strictly convex can lie in an ear candidate of a simple polygon.
    for (int q = c.next; q != b.prev; q = nodes_[q].next) {
      const Node& r = nodes_[q];
      if (r.index == a.index || r.index == b.index || r.index == c.index) continue;
      if (r.p.x() < lo_x || r.p.x() > hi_x || r.p.y() < lo_y || r.p.y() > hi_y) continue;
      if (orient2d(nodes_[r.prev].p, r.p, nodes_[r.next].p) > 0.0) continue;
      if (in_closed_triangle(a.p, b.p, c.p, r.p)) return false;
    }
    return true;
  }

  std::vector<Node> nodes_;
};

// Positive when d lies inside the circle through the counter-clockwise triangle a, b, c, with a
// margin relative to the terms' size: nearly cocircular points (a cut through a round part)
// are left alone instead of flipped back and forth.
bool clearly_in_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const Eigen::Vector2d p = a - d, q = b - d, r = c - d;
  const double pp = p.squaredNorm(), qq = q.squaredNorm(), rr = r.squaredNorm();
  const double t1 = pp * (q.x() * r.y() - q.y() * r.x());
  const double t2 = qq * (r.x() * p.y() - r.y() * p.x());
  const double t3 = rr * (p.x() * q.y() - p.y() * q.x());
  const double scale = pp * (std::fabs(q.x() * r.y()) + std::fabs(q.y() * r.x())) +
                       qq * (std::fabs(r.x() * p.y()) + std::fabs(r.y() * p.x())) +
                       rr * (std::fabs(p.x() * q.y()) + std::fabs(p.y() * q.x()));
  return t1 + t2 + t3 > 1e-9 * scale;
}

// Lawson's edge flips towards the constrained Delaunay triangulation (Lawson 1977): ear
// clipping alone may leave a sliver over three nearly collinear cut points, which a flip to the
// other diagonal of its (convex) quad removes. Loop edges have one triangle and never flip.
void improve_by_flips(const std::vector<Eigen::Vector2d>& points, std::vector<std::array<int, 3>>& triangles,
                      std::size_t first) {
  std::map<std::pair<int, int>, int> triangle_of_edge;  // directed edge -> triangle
  for (std::size_t t = first; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) triangle_of_edge[{triangles[t][k], triangles[t][(k + 1) % 3]}] = static_cast<int>(t);
  std::vector<std::pair<int, int>> stack;
  for (const auto& item : triangle_of_edge)
    if (item.first.first < item.first.second && triangle_of_edge.count({item.first.second, item.first.first}))
      stack.push_back(item.first);
  const std::size_t cap = 50 * (triangles.size() - first) + 1000;
  for (std::size_t flips = 0; !stack.empty() && flips < cap;) {
    const auto [u, v] = stack.back();
    stack.pop_back();
    const auto e1 = triangle_of_edge.find({u, v}), e2 = triangle_of_edge.find({v, u});
    if (e1 == triangle_of_edge.end() || e2 == triangle_of_edge.end()) continue;
    const int t1 = e1->second, t2 = e2->second;
    auto third = [&](int t, int a, int b) {
      for (int k = 0; k < 3; ++k)
        if (triangles[t][k] != a && triangles[t][k] != b) return triangles[t][k];
      return -1;
    };
    const int w1 = third(t1, u, v), w2 = third(t2, u, v);
    if (w1 < 0 || w2 < 0 || w1 == w2) continue;
    if (!clearly_in_circle(points[u], points[v], points[w1], points[w2])) continue;
    if (!(orient2d(points[w1], points[u], points[w2]) > 0.0 && orient2d(points[w2], points[v], points[w1]) > 0.0)) continue;
    if (triangle_of_edge.count({w1, w2}) || triangle_of_edge.count({w2, w1})) continue;  // would duplicate an edge
    for (int t : {t1, t2})
      for (int k = 0; k < 3; ++k) triangle_of_edge.erase({triangles[t][k], triangles[t][(k + 1) % 3]});
    triangles[t1] = {w1, u, w2};
    triangles[t2] = {w2, v, w1};
    for (int t : {t1, t2})
      for (int k = 0; k < 3; ++k) triangle_of_edge[{triangles[t][k], triangles[t][(k + 1) % 3]}] = t;
    for (const auto& [a, b] : {std::make_pair(u, w1), std::make_pair(w1, v), std::make_pair(v, w2), std::make_pair(w2, u)})
      stack.emplace_back(std::min(a, b), std::max(a, b));
    ++flips;
  }
}

}  // namespace

double twice_signed_area(const std::vector<Eigen::Vector2d>& loop) {
  double sum = 0.0;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    sum += loop[j].x() * loop[i].y() - loop[i].x() * loop[j].y();
  return sum;
}

PolygonTriangulation triangulate_polygons(const std::vector<std::vector<Eigen::Vector2d>>& loops) {
  PolygonTriangulation result;
  const int n = static_cast<int>(loops.size());
  std::vector<double> area(n);
  std::vector<int> first(n + 1, 0);
  for (int i = 0; i < n; ++i) {
    first[i + 1] = first[i] + static_cast<int>(loops[i].size());
    area[i] = loops[i].size() >= 3 ? 0.5 * twice_signed_area(loops[i]) : 0.0;
    if (area[i] == 0.0) {
      result.status = TriangulationStatus::degenerate_loop;
      result.message = "loop " + std::to_string(i) + " encloses no area";
      return result;
    }
  }
  std::vector<Eigen::Vector2d> all_points;
  for (const auto& loop : loops) all_points.insert(all_points.end(), loop.begin(), loop.end());
  // Each hole belongs to the smallest outer boundary around it.
  std::vector<std::vector<int>> holes_of(n);
  for (int h = 0; h < n; ++h) {
    if (area[h] > 0.0) {
      ++result.outer_loops;
      continue;
    }
    ++result.holes;
    int owner = -1;
    for (int o = 0; o < n; ++o)
      if (area[o] > 0.0 && inside_loop(loops[o], loops[h][0]) && (owner < 0 || area[o] < area[owner])) owner = o;
    if (owner < 0) {
      result.status = TriangulationStatus::unenclosed_hole;
      result.message = "hole loop " + std::to_string(h) + " lies in no outer loop";
      return result;
    }
    holes_of[owner].push_back(h);
  }
  for (int o = 0; o < n; ++o) {
    if (area[o] < 0.0) continue;
    EarClipper clipper;
    const int start = clipper.add_ring(loops[o], first[o]);
    // Rightmost holes first, so each bridge crosses no hole still to be joined.
    std::vector<int>& holes = holes_of[o];
    auto max_x = [&](int h) {
      double x = loops[h][0].x();
      for (const auto& p : loops[h]) x = std::max(x, p.x());
      return x;
    };
    std::stable_sort(holes.begin(), holes.end(), [&](int a, int b) { return max_x(a) > max_x(b); });
    for (int h : holes) {
      const int ring = clipper.add_ring(loops[h], first[h]);
      if (!clipper.bridge(start, ring)) {
        result.status = TriangulationStatus::unenclosed_hole;
        result.message = "hole loop " + std::to_string(h) + " could not be joined to its boundary";
        return result;
      }
    }
    const std::size_t first_triangle = result.triangles.size();
    const TriangulationStatus status = clipper.clip(start, result.triangles);
    if (status != TriangulationStatus::ok) {
      result.status = status;
      result.message = "loop " + std::to_string(o) + (status == TriangulationStatus::no_ear ? ": no ear left to clip (the loops cross or touch)" : ": step cap reached");
      return result;
    }
    improve_by_flips(all_points, result.triangles, first_triangle);
  }
  return result;
}

}  // namespace offsetopt
