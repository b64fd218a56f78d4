#include "geometry/mesh_defects.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <utility>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/exact_triangle_intersection.h"
#include "geometry/faces_intersect_exact.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

bool usable(const Mesh& mesh) {
  if (!mesh.V.allFinite()) return false;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= mesh.V.rows()) return false;
  return true;
}

// Vertex indices sorted by position (x, y, z), ties by index: equal positions are adjacent.
std::vector<int> by_position(const Vertices& V) {
  std::vector<int> order(static_cast<std::size_t>(V.rows()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&V](int a, int b) {
    for (int k = 0; k < 3; ++k)
      if (V(a, k) != V(b, k)) return V(a, k) < V(b, k);
    return a < b;
  });
  return order;
}

bool same_position(const Vertices& V, int a, int b) {
  return V(a, 0) == V(b, 0) && V(a, 1) == V(b, 1) && V(a, 2) == V(b, 2);
}

// The smallest vertex index at each vertex's position, from by_position's order.
std::vector<int> canonical_vertices(const Vertices& V, const std::vector<int>& order) {
  std::vector<int> canonical(order.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && same_position(V, order[i], order[j])) ++j;
    for (std::size_t k = i; k < j; ++k) canonical[static_cast<std::size_t>(order[k])] = order[i];
    i = j;
  }
  return canonical;
}

// A corner a face has only on one of its edges (a T-junction): the vertex and the face's edge
// (numbered by the opposite corner) it lies on.
struct VirtualCorner {
  int vertex;
  int edge;
};

constexpr std::size_t kMaxVirtualCorners = 64;  // per face; T-junction chains are short
constexpr int kMaxPropagationRounds = 16;
constexpr std::size_t kMaxPinchGroup = 256;  // vertices at one position checked pair by pair

class PairRule {
 public:
  explicit PairRule(const Mesh& mesh) : mesh_(mesh), canonical_(canonical_vertices(mesh.V, by_position(mesh.V))) {
    const Eigen::Index nf = mesh.F.rows();
    corners_.resize(static_cast<std::size_t>(nf));
    collinear_.assign(static_cast<std::size_t>(nf), 0);
    sliver_.assign(static_cast<std::size_t>(nf), 0);
    virtual_.resize(static_cast<std::size_t>(nf));
    for (Eigen::Index f = 0; f < nf; ++f) {
      auto& c = corners_[static_cast<std::size_t>(f)];
      for (int k = 0; k < 3; ++k) c[static_cast<std::size_t>(k)] = canonical_[static_cast<std::size_t>(mesh.F(f, k))];
      const bool distinct = c[0] != c[1] && c[1] != c[2] && c[0] != c[2];
      const bool collinear = collinear_exact(corner(f, 0), corner(f, 1), corner(f, 2));
      collinear_[static_cast<std::size_t>(f)] = collinear;
      sliver_[static_cast<std::size_t>(f)] = collinear && distinct;
    }
    link_t_junctions();
  }

  // No plane: not tested (CGAL reports such a face by itself, as a pair (f, f)).
  bool collinear(int f) const { return collinear_[static_cast<std::size_t>(f)] != 0; }

  bool intersect(int f, int g) const {
    const auto& cf = corners_[static_cast<std::size_t>(f)];
    const auto& cg = corners_[static_cast<std::size_t>(g)];
    const Eigen::Vector3d pf[3] = {corner(f, 0), corner(f, 1), corner(f, 2)};
    const Eigen::Vector3d pg[3] = {corner(g, 0), corner(g, 1), corner(g, 2)};
    if (!faces_intersect_exact(pf, cf.data(), pg, cg.data())) return false;
    if (virtual_[static_cast<std::size_t>(f)].empty() && virtual_[static_cast<std::size_t>(g)].empty()) return true;
    return !joined_at_t_junction(f, g);
  }

 private:
  // A pair the exact rule counts, but whose contact is only where a zero-area face closes a
  // T-junction between them: the junction's middle corner is a corner of one face and lies on an
  // edge of the other, so the two touch there by construction (as faces sharing a corner do).
  // With that corner counted as shared, the rule of faces_intersect_exact.h applies again.
  bool joined_at_t_junction(int f, int g) const {
    const auto& cf = corners_[static_cast<std::size_t>(f)];
    const auto& cg = corners_[static_cast<std::size_t>(g)];
    // Shared corners: (corner of f or -1, corner of g or -1, edge it lies on when virtual).
    struct Shared {
      int vertex, in_f, in_g, edge_of_f, edge_of_g;
    };
    std::array<Shared, 6> shared{};
    int count = 0;
    bool any_virtual = false;
    auto note = [&](int vertex, int in_f, int in_g, int edge_of_f, int edge_of_g) {
      for (int s = 0; s < count; ++s)
        if (shared[static_cast<std::size_t>(s)].vertex == vertex) return;
      shared[static_cast<std::size_t>(count++)] = {vertex, in_f, in_g, edge_of_f, edge_of_g};
      any_virtual = any_virtual || in_f < 0 || in_g < 0;
    };
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (cf[static_cast<std::size_t>(i)] == cg[static_cast<std::size_t>(j)]) note(cf[static_cast<std::size_t>(i)], i, j, -1, -1);
    for (const VirtualCorner& v : virtual_[static_cast<std::size_t>(g)])
      for (int i = 0; i < 3; ++i)
        if (cf[static_cast<std::size_t>(i)] == v.vertex) note(v.vertex, i, -1, -1, v.edge);
    for (const VirtualCorner& v : virtual_[static_cast<std::size_t>(f)])
      for (int j = 0; j < 3; ++j)
        if (cg[static_cast<std::size_t>(j)] == v.vertex) note(v.vertex, -1, j, v.edge, -1);
    if (!any_virtual || count >= 3) return false;
    const Eigen::Vector3d p1 = corner(f, 0), q1 = corner(f, 1), r1 = corner(f, 2);
    const Eigen::Vector3d p2 = corner(g, 0), q2 = corner(g, 1), r2 = corner(g, 2);
    if (count == 2) {
      // Both touch along the segment between the two shared points, which lies on an edge of
      // each: they overlap only when coplanar and folded onto one side of it.
      const Eigen::Vector3d u = mesh_.V.row(shared[0].vertex).transpose(), w = mesh_.V.row(shared[1].vertex).transpose();
      const Eigen::Vector3d& off_f = !collinear_exact(u, w, p1) ? p1 : !collinear_exact(u, w, q1) ? q1 : r1;
      const Eigen::Vector3d& off_g = !collinear_exact(u, w, p2) ? p2 : !collinear_exact(u, w, q2) ? q2 : r2;
      const int ids[3] = {0, 1, 2}, other[3] = {0, 1, 3};
      const Eigen::Vector3d a[3] = {u, w, off_f}, b[3] = {u, w, off_g};
      return !faces_intersect_exact(a, ids, b, other);
    }
    const Shared& s = shared[0];
    bool hit = false;
    // The edge of each face opposite the shared corner, or, where the corner lies on an edge of
    // the face, the face's other two edges.
    if (s.in_f >= 0) {
      hit = hit || segment_meets_triangle_exact(corner(f, (s.in_f + 1) % 3), corner(f, (s.in_f + 2) % 3), p2, q2, r2);
    } else {
      hit = hit || segment_meets_triangle_exact(corner(f, s.edge_of_f), corner(f, (s.edge_of_f + 1) % 3), p2, q2, r2) ||
            segment_meets_triangle_exact(corner(f, s.edge_of_f), corner(f, (s.edge_of_f + 2) % 3), p2, q2, r2);
    }
    if (s.in_g >= 0) {
      hit = hit || segment_meets_triangle_exact(corner(g, (s.in_g + 1) % 3), corner(g, (s.in_g + 2) % 3), p1, q1, r1);
    } else {
      hit = hit || segment_meets_triangle_exact(corner(g, s.edge_of_g), corner(g, (s.edge_of_g + 1) % 3), p1, q1, r1) ||
            segment_meets_triangle_exact(corner(g, s.edge_of_g), corner(g, (s.edge_of_g + 2) % 3), p1, q1, r1);
    }
    return !hit;
  }

  Eigen::Vector3d corner(Eigen::Index f, int k) const { return mesh_.V.row(mesh_.F(f, k)).transpose(); }

  // The middle corner of each zero-area face becomes a virtual corner of the faces across the
  // edge it lies on; a zero-area face passes its own virtual corners on the same way.
  void link_t_junctions() {
    struct EdgeFace {
      int lo, hi, face, edge;
      bool operator<(const EdgeFace& o) const {
        return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : face != o.face ? face < o.face : edge < o.edge;
      }
    };
    std::vector<int> slivers;
    for (std::size_t f = 0; f < sliver_.size(); ++f)
      if (sliver_[f]) slivers.push_back(static_cast<int>(f));
    if (slivers.empty()) return;
    std::vector<EdgeFace> edges;
    edges.reserve(3 * corners_.size());
    for (std::size_t f = 0; f < corners_.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = corners_[f][static_cast<std::size_t>((k + 1) % 3)], w = corners_[f][static_cast<std::size_t>((k + 2) % 3)];
        edges.push_back({std::min(u, w), std::max(u, w), static_cast<int>(f), k});
      }
    std::sort(edges.begin(), edges.end());
    for (int round = 0; round < kMaxPropagationRounds; ++round) {
      bool changed = false;
      for (const int s : slivers) {
        // The middle corner is opposite the longest edge.
        int middle = 0;
        double longest = -1;
        for (int k = 0; k < 3; ++k) {
          const double length = (corner(s, (k + 1) % 3) - corner(s, (k + 2) % 3)).squaredNorm();
          if (length > longest) {
            longest = length;
            middle = k;
          }
        }
        const auto& c = corners_[static_cast<std::size_t>(s)];
        const int u = c[static_cast<std::size_t>((middle + 1) % 3)], w = c[static_cast<std::size_t>((middle + 2) % 3)];
        std::vector<int> carried = {c[static_cast<std::size_t>(middle)]};
        for (const VirtualCorner& v : virtual_[static_cast<std::size_t>(s)]) carried.push_back(v.vertex);
        const EdgeFace key{std::min(u, w), std::max(u, w), -1, -1};
        for (auto it = std::lower_bound(edges.begin(), edges.end(), key); it != edges.end() && it->lo == key.lo && it->hi == key.hi;
             ++it) {
          if (it->face == s) continue;
          auto& list = virtual_[static_cast<std::size_t>(it->face)];
          for (const int vertex : carried) {
            bool present = false;
            for (const VirtualCorner& v : list) present = present || v.vertex == vertex;
            for (int k = 0; k < 3; ++k) present = present || corners_[static_cast<std::size_t>(it->face)][static_cast<std::size_t>(k)] == vertex;
            if (present || list.size() >= kMaxVirtualCorners) continue;
            list.push_back({vertex, it->edge});
            changed = true;
          }
        }
      }
      if (!changed) break;
    }
  }

  const Mesh& mesh_;
  std::vector<int> canonical_;
  std::vector<std::array<int, 3>> corners_;
  std::vector<char> collinear_, sliver_;
  std::vector<std::vector<VirtualCorner>> virtual_;
};

}  // namespace

namespace {

// The search below the node pairs `start`: the pairs found (counted up to `cap`), the smallest
// pair, and the candidates visited (up to max_candidates, then stopped).
SelfIntersectionReport search_pairs(const TriangleBvh& bvh, const PairRule& rule, std::vector<std::pair<int, int>> start,
                                    std::size_t cap, long long max_candidates) {
  SelfIntersectionReport out;
  std::pair<int, int> first{-1, -1};
  long long candidates = 0;
  auto visit = [&](int f, int g) {
    if (++candidates > max_candidates) {
      out.work_cap_reached = true;
      out.truncated = true;
      return false;
    }
    if (rule.collinear(f) || rule.collinear(g)) return true;
    if (!bvh.face_box(f).overlaps(bvh.face_box(g))) return true;
    if (!rule.intersect(f, g)) return true;
    const std::pair<int, int> pair{std::min(f, g), std::max(f, g)};
    if (out.pairs == 0 || pair < first) first = pair;
    ++out.pairs;
    if (static_cast<std::size_t>(out.pairs) >= cap) {
      out.truncated = true;
      return false;
    }
    return true;
  };
  traverse_face_pairs(bvh, bvh, true, std::move(start), visit);
  out.first_face = first.first;
  out.second_face = first.second;
  out.candidate_pairs = std::min(candidates, max_candidates);
  return out;
}

}  // namespace

SelfIntersectionReport find_self_intersections(const Mesh& mesh, std::size_t cap, int threads) {
  SelfIntersectionReport out;
  if (mesh.F.rows() == 0 || cap == 0 || !usable(mesh)) return out;
  const PairRule rule(mesh);
  long long collinear_faces = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) collinear_faces += rule.collinear(static_cast<int>(f)) ? 1 : 0;
  const TriangleBvh bvh(mesh.V, mesh.F);
  const long long max_candidates =
      std::max(kMinSelfIntersectionCandidates, kSelfIntersectionCandidatesPerFace * static_cast<long long>(mesh.F.rows()));
  // Two threads: the root's right subtree against itself on one, the rest on the other. The caps
  // count over the whole search, so when the two parts together reach one, the search is made
  // again in one piece, where it stops where it always did.
  const BvhNode& root = bvh.nodes().front();
  if (threads > 1 && !root.is_leaf()) {
    std::future<SelfIntersectionReport> right = start_task(true, [&bvh, &rule, &root, cap, max_candidates]() {
      return search_pairs(bvh, rule, {{root.right, root.right}}, cap, max_candidates);
    });
    const SelfIntersectionReport left = search_pairs(bvh, rule, {{root.left, root.right}, {root.left, root.left}}, cap, max_candidates);
    const SelfIntersectionReport other = right.get();
    if (!left.truncated && !other.truncated && left.candidate_pairs + other.candidate_pairs <= max_candidates &&
        static_cast<std::size_t>(left.pairs + other.pairs) < cap) {
      out.pairs = left.pairs + other.pairs;
      out.candidate_pairs = left.candidate_pairs + other.candidate_pairs;
      const bool take_other =
          other.pairs > 0 && (left.pairs == 0 || std::make_pair(other.first_face, other.second_face) <
                                                     std::make_pair(left.first_face, left.second_face));
      out.first_face = take_other ? other.first_face : left.first_face;
      out.second_face = take_other ? other.second_face : left.second_face;
      out.collinear_faces = collinear_faces;
      return out;
    }
  }
  out = search_pairs(bvh, rule, {{0, 0}}, cap, max_candidates);
  out.collinear_faces = collinear_faces;
  return out;
}

PinchReport find_pinches(const Mesh& mesh) {
  PinchReport out;
  if (mesh.F.rows() == 0 || !usable(mesh)) return out;
  const Eigen::Index nv = mesh.V.rows();
  std::vector<char> referenced(static_cast<std::size_t>(nv), 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) referenced[static_cast<std::size_t>(mesh.F(f, k))] = 1;
  // One sort by position serves both the canonical vertices and the groups below.
  const std::vector<int> order = by_position(mesh.V);
  const std::vector<int> canonical = canonical_vertices(mesh.V, order);
  // Edges joining two vertices at one position (zero length): such a pair is not a pinch.
  std::vector<std::pair<int, int>> joined;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      if (u != w && canonical[static_cast<std::size_t>(u)] == canonical[static_cast<std::size_t>(w)])
        joined.emplace_back(std::min(u, w), std::max(u, w));
    }
  std::sort(joined.begin(), joined.end());
  std::pair<int, int> first{-1, -1};
  std::vector<int> group;
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && same_position(mesh.V, order[i], order[j])) ++j;
    group.clear();
    for (std::size_t k = i; k < j; ++k)
      if (referenced[static_cast<std::size_t>(order[k])]) group.push_back(order[k]);  // ascending
    if (group.size() > kMaxPinchGroup) {
      // Thousands of vertices at one point (a collapsed file): counted, not paired one by one.
      const long long k = static_cast<long long>(group.size());
      const std::pair<int, int> pair{group[0], group[1]};
      if (out.pairs == 0 || pair < first) first = pair;
      out.pairs += k * (k - 1) / 2;
      i = j;
      continue;
    }
    for (std::size_t a = 0; a < group.size(); ++a)
      for (std::size_t b = a + 1; b < group.size(); ++b) {
        const std::pair<int, int> pair{group[a], group[b]};
        if (std::binary_search(joined.begin(), joined.end(), pair)) continue;
        if (out.pairs == 0 || pair < first) first = pair;
        ++out.pairs;
      }
    i = j;
  }
  out.first_vertex = first.first;
  out.second_vertex = first.second;
  return out;
}

}  // namespace offsetopt
