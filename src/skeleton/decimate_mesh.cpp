#include "skeleton/decimate_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Geometry>

namespace offsetopt {

namespace {

// Symmetric 4x4 plane quadric, upper triangle: a² ab ac ad b² bc bd c² cd d².
using Quadric = std::array<double, 10>;

double quadric_at(const Quadric& q, const Eigen::Vector3d& p) {
  const double x = p.x(), y = p.y(), z = p.z();
  return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + 2 * q[3] * x + q[4] * y * y + 2 * q[5] * y * z +
         2 * q[6] * y + q[7] * z * z + 2 * q[8] * z + q[9];
}

struct Candidate {
  double cost;
  int from, to;  // collapse `from` into `to`
  int half_edge;  // 3 f + c: the edge from corner c of face f to the next corner
};

// The cheapest first; ties by vertex indices (a total order: the edges are distinct).
struct Cheaper {
  bool operator()(const Candidate& a, const Candidate& b) const {
    if (a.cost != b.cost) return a.cost < b.cost;
    if (a.from != b.from) return a.from < b.from;
    return a.to < b.to;
  }
};

// A round walks the cheapest 1/kWalkedShare of the edges.
constexpr std::size_t kWalkedShare = 4;
constexpr unsigned kMaxRounds = 10000;

class Decimator {
 public:
  Decimator(const Vertices& V, const Faces& F, const DecimateOptions& options)
      : V_(V), options_(options), faces_(static_cast<std::size_t>(F.rows())), alive_face_(faces_.size(), 1) {
    const std::size_t n = static_cast<std::size_t>(V.rows());
    faces_of_.resize(n);
    quadric_.assign(n, Quadric{});
    blocked_.assign(n, 0);
    merged_.assign(n, 0);
    mark_.assign(n, 0);
    refused_.assign(3 * faces_.size(), 0);
    edge_cost_.assign(3 * faces_.size(), 0.0);
    cost_round_.assign(3 * faces_.size(), 0);
    forward_.assign(3 * faces_.size(), 0);
    alive_vertex_.assign(n, 1);
    locked_.assign(n, 0);
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      for (int c = 0; c < 3; ++c) faces_[f][c] = F(static_cast<Eigen::Index>(f), c);
      for (int c = 0; c < 3; ++c) faces_of_[static_cast<std::size_t>(faces_[f][c])].push_back(static_cast<int>(f));
      const Eigen::Vector3d a = V.row(faces_[f][0]), b = V.row(faces_[f][1]), c = V.row(faces_[f][2]);
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double norm = cross.norm();
      if (!(norm > 0.0)) continue;
      const Eigen::Vector3d normal = cross / norm;
      const double area = 0.5 * norm;
      const double p[4] = {normal.x(), normal.y(), normal.z(), -normal.dot(a)};
      Quadric q;
      int e = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i; j < 4; ++j) q[static_cast<std::size_t>(e++)] = area * p[i] * p[j];
      for (int corner = 0; corner < 3; ++corner) {
        Quadric& target = quadric_[static_cast<std::size_t>(faces_[f][corner])];
        for (std::size_t k = 0; k < 10; ++k) target[k] += q[k];
      }
    }
    lock_boundary();
    alive_count_ = static_cast<int>(n);
  }

  int alive_count() const { return alive_count_; }

  // Rounds of independent collapses: the round's edges, each in its cheaper direction, are sorted
  // by cost and walked from the cheapest; a collapse blocks the one-ring it leaves around its
  // target for the rest of the round, so every edge taken still has the cost it was sorted by
  // (its ends' quadrics are unchanged). Only the cheapest share of the edges is walked in a round
  // (the order stays close to one global heap's, which cost 17 s at 10^6 vertices for its cache
  // misses); a round that takes nothing walks all of them, and one that still takes nothing ends.
  void run(int target) {
    std::vector<int> live_faces(faces_.size());
    for (std::size_t f = 0; f < faces_.size(); ++f) live_faces[f] = static_cast<int>(f);
    std::vector<Candidate> edges;
    bool walk_all = false;
    for (unsigned round = 1; alive_count_ > target && round <= kMaxRounds; ++round) {
      live_faces.erase(std::remove_if(live_faces.begin(), live_faces.end(),
                                      [this](int f) { return !alive_face_[static_cast<std::size_t>(f)]; }),
                       live_faces.end());
      edges.clear();
      for (int f : live_faces)
        for (int c = 0; c < 3; ++c) {
          const int a = faces_[static_cast<std::size_t>(f)][c], b = faces_[static_cast<std::size_t>(f)][(c + 1) % 3];
          if (a < b) add_edge(a, b, 3 * f + c, round, edges);
        }
      if (edges.empty()) break;
      const std::size_t walked = walk_all ? edges.size() : std::max<std::size_t>(1, edges.size() / kWalkedShare);
      std::nth_element(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(walked - 1), edges.end(), Cheaper());
      std::sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(walked), Cheaper());
      int taken = 0;
      for (std::size_t e = 0; e < walked && alive_count_ > target; ++e) {
        const Candidate& c = edges[e];
        if (blocked_[static_cast<std::size_t>(c.from)] == round || blocked_[static_cast<std::size_t>(c.to)] == round) continue;
        if (allowed(c.from, c.to)) {
          collapse(c.from, c.to, round);
        } else if (allowed(c.to, c.from)) {
          collapse(c.to, c.from, round);
        } else {
          refused_[static_cast<std::size_t>(c.half_edge)] = round;
          continue;
        }
        ++taken;
      }
      if (taken == 0 && walk_all) break;
      walk_all = taken == 0;
    }
  }

  DecimatedMesh result() const {
    DecimatedMesh out;
    const std::size_t n = alive_vertex_.size();
    out.coarse_vertex.assign(n, -1);
    for (std::size_t i = 0; i < n; ++i)
      if (alive_vertex_[i]) {
        out.coarse_vertex[i] = static_cast<int>(out.input_vertex.size());
        out.input_vertex.push_back(static_cast<int>(i));
      }
    out.mesh.V.resize(static_cast<Eigen::Index>(out.input_vertex.size()), 3);
    for (std::size_t k = 0; k < out.input_vertex.size(); ++k)
      out.mesh.V.row(static_cast<Eigen::Index>(k)) = V_.row(out.input_vertex[k]);
    Eigen::Index faces = 0;
    for (char alive : alive_face_) faces += alive ? 1 : 0;
    out.mesh.F.resize(faces, 3);
    Eigen::Index row = 0;
    for (std::size_t f = 0; f < faces_.size(); ++f) {
      if (!alive_face_[f]) continue;
      for (int c = 0; c < 3; ++c) out.mesh.F(row, c) = out.coarse_vertex[static_cast<std::size_t>(faces_[f][c])];
      ++row;
    }
    return out;
  }

 private:
  // Vertices on an edge without exactly two faces never move.
  void lock_boundary() {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(3 * faces_.size());
    for (const auto& face : faces_)
      for (int c = 0; c < 3; ++c) edges.emplace_back(std::min(face[c], face[(c + 1) % 3]), std::max(face[c], face[(c + 1) % 3]));
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
      std::size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i != 2) {
        locked_[static_cast<std::size_t>(edges[i].first)] = 1;
        locked_[static_cast<std::size_t>(edges[i].second)] = 1;
      }
      i = j;
    }
  }

  double cost(int from, int to) const {
    Quadric sum = quadric_[static_cast<std::size_t>(from)];
    const Quadric& other = quadric_[static_cast<std::size_t>(to)];
    for (std::size_t k = 0; k < 10; ++k) sum[k] += other[k];
    return quadric_at(sum, V_.row(to).transpose());
  }

  // The cheaper direction of the edge a-b. An edge refused in both directions in round r is left
  // out until a collapse changes the ring of one of its ends (blocked_ then reaches r): allowed()
  // reads nothing else, and at 10^6 vertices re-testing them was 5.5 tests per collapse. Its cost
  // is kept from the round it was computed in until a collapse merges into one of its ends (the
  // only way their quadrics change; a half-edge whose corner was the removed vertex now ends at
  // the target): reading two quadrics and two positions of scattered vertices for every edge in
  // every round was most of the decimation on a scan whose vertex numbers follow no order (the
  // refined armadillo at 10^6 vertices).
  void add_edge(int a, int b, int half_edge, unsigned round, std::vector<Candidate>& edges) {
    const std::size_t he = static_cast<std::size_t>(half_edge);
    if (locked_[static_cast<std::size_t>(a)] && locked_[static_cast<std::size_t>(b)]) return;
    const unsigned refused = refused_[he];
    if (refused != 0 && blocked_[static_cast<std::size_t>(a)] < refused && blocked_[static_cast<std::size_t>(b)] < refused) return;
    const unsigned known = cost_round_[he];
    if (known == 0 || merged_[static_cast<std::size_t>(a)] >= known || merged_[static_cast<std::size_t>(b)] >= known) {
      const double ab = locked_[static_cast<std::size_t>(a)] ? HUGE_VAL : cost(a, b);
      const double ba = locked_[static_cast<std::size_t>(b)] ? HUGE_VAL : cost(b, a);
      const bool forward = ab < ba || (ab == ba && a < b);
      edge_cost_[he] = forward ? ab : ba;
      forward_[he] = forward;
      cost_round_[he] = round;
    }
    const bool forward = forward_[he] != 0;
    edges.push_back({edge_cost_[he], forward ? a : b, forward ? b : a, half_edge});
  }

  // The alive faces of v.
  void alive_faces(int v, std::vector<int>& faces) const {
    faces.clear();
    for (int f : faces_of_[static_cast<std::size_t>(v)])
      if (alive_face_[static_cast<std::size_t>(f)]) faces.push_back(f);
  }

  // The link condition by marks (no sorting: this is the decimation's innermost test). Counts the
  // distinct neighbours of each end and the ones they share, u and v excluded.
  bool link_condition(int from, int to) {
    if (mark_base_ > std::numeric_limits<unsigned>::max() - 4) {
      std::fill(mark_.begin(), mark_.end(), 0u);
      mark_base_ = 0;
    }
    const unsigned of_from = mark_base_ + 1, of_to = mark_base_ + 2, of_both = mark_base_ + 3;
    mark_base_ += 3;
    int from_degree = 0, to_degree = 0, shared = 0;
    bool adjacent = false;
    for (int f : from_faces_)
      for (int w : faces_[static_cast<std::size_t>(f)]) {
        if (w == from) continue;
        unsigned& m = mark_[static_cast<std::size_t>(w)];
        if (m == of_from) continue;
        m = of_from;
        ++from_degree;
        adjacent = adjacent || w == to;
      }
    if (!adjacent) return false;
    for (int f : to_faces_)
      for (int w : faces_[static_cast<std::size_t>(f)]) {
        if (w == to || w == from) continue;
        unsigned& m = mark_[static_cast<std::size_t>(w)];
        if (m == of_to || m == of_both) continue;
        ++to_degree;
        if (m == of_from) {
          ++shared;
          m = of_both;
        } else {
          m = of_to;
        }
      }
    ++to_degree;  // `from` itself
    if (shared != 2) return false;
    // A closed mesh of four vertices (a tetrahedron) cannot lose another one.
    return from_degree >= 4 || to_degree >= 4;
  }

  static double compactness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& cross) {
    cross = (b - a).cross(c - a);
    const double squares = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    return squares > 0.0 ? 2.0 * std::sqrt(3.0) * cross.norm() / squares : 0.0;
  }

  bool allowed(int from, int to) {
    if (locked_[static_cast<std::size_t>(from)]) return false;
    alive_faces(from, from_faces_);
    alive_faces(to, to_faces_);
    int edge_faces = 0;
    for (int f : from_faces_) {
      const auto& face = faces_[static_cast<std::size_t>(f)];
      if (face[0] == to || face[1] == to || face[2] == to) ++edge_faces;
    }
    if (edge_faces != 2 || !link_condition(from, to)) return false;
    const Eigen::Vector3d target = V_.row(to).transpose();
    for (int f : from_faces_) {
      const auto& face = faces_[static_cast<std::size_t>(f)];
      if (face[0] == to || face[1] == to || face[2] == to) continue;
      Eigen::Vector3d before[3], after[3];
      for (int c = 0; c < 3; ++c) {
        before[c] = V_.row(face[c]).transpose();
        after[c] = face[c] == from ? target : before[c];
      }
      Eigen::Vector3d n_before, n_after;
      const double q_before = compactness(before[0], before[1], before[2], n_before);
      const double q_after = compactness(after[0], after[1], after[2], n_after);
      const double lengths = n_before.norm() * n_after.norm();
      if (!(lengths > 0.0) || n_before.dot(n_after) < options_.min_normal_cosine * lengths) return false;
      if (q_after < options_.min_compactness && q_after < q_before) return false;
    }
    return true;
  }

  void collapse(int from, int to, unsigned round) {
    const std::size_t u = static_cast<std::size_t>(from), v = static_cast<std::size_t>(to);
    // from_faces_ and to_faces_ are the alive rings allowed() just gathered.
    std::vector<int> merged;
    merged.reserve(from_faces_.size() + to_faces_.size());
    for (int f : to_faces_) {
      const auto& face = faces_[static_cast<std::size_t>(f)];
      if (face[0] == from || face[1] == from || face[2] == from) alive_face_[static_cast<std::size_t>(f)] = 0;
      else merged.push_back(f);
    }
    for (int f : from_faces_) {
      auto& face = faces_[static_cast<std::size_t>(f)];
      if (!alive_face_[static_cast<std::size_t>(f)]) continue;
      for (int c = 0; c < 3; ++c)
        if (face[c] == from) face[c] = to;
      merged.push_back(f);
    }
    std::sort(merged.begin(), merged.end());
    faces_of_[v] = std::move(merged);
    std::vector<int>().swap(faces_of_[u]);
    alive_vertex_[u] = 0;
    --alive_count_;
    for (std::size_t k = 0; k < 10; ++k) quadric_[v][k] += quadric_[u][k];
    blocked_[u] = round;
    merged_[v] = round;
    for (int f : faces_of_[v])
      for (int w : faces_[static_cast<std::size_t>(f)]) blocked_[static_cast<std::size_t>(w)] = round;
  }

  const Vertices& V_;
  DecimateOptions options_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<char> alive_face_;
  std::vector<std::vector<int>> faces_of_;
  std::vector<Quadric> quadric_;
  std::vector<unsigned> blocked_;  // the round in which a collapse last changed the vertex's ring
  std::vector<unsigned> merged_;   // the round in which a collapse last merged into the vertex
  std::vector<unsigned> refused_;  // per half-edge: the round its edge was last refused, or 0
  std::vector<double> edge_cost_;  // per half-edge: its edge's cost in the cheaper direction ...
  std::vector<unsigned> cost_round_;  // ... computed at the start of this round (0: not yet) ...
  std::vector<char> forward_;      // ... which is from its first end to its second
  std::vector<char> alive_vertex_, locked_;
  int alive_count_ = 0;
  std::vector<int> from_faces_, to_faces_;
  std::vector<unsigned> mark_;  // link_condition's marks, above mark_base_ in the current call
  unsigned mark_base_ = 0;
};

}  // namespace

DecimatedMesh decimate_mesh(const Vertices& V, const Faces& F, int target_vertices, const DecimateOptions& options) {
  Decimator decimator(V, F, options);
  decimator.run(std::max(target_vertices, 4));
  return decimator.result();
}

}  // namespace offsetopt
