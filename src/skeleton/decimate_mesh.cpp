#include "skeleton/decimate_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <iterator>
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
  int from, to;              // collapse `from` into `to`
  unsigned from_stamp, to_stamp;
};

// The cheapest first; ties by vertex indices.
struct Later {
  bool operator()(const Candidate& a, const Candidate& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    if (a.from != b.from) return a.from > b.from;
    return a.to > b.to;
  }
};

class Decimator {
 public:
  Decimator(const Vertices& V, const Faces& F, const DecimateOptions& options)
      : V_(V), options_(options), faces_(static_cast<std::size_t>(F.rows())), alive_face_(faces_.size(), 1) {
    const std::size_t n = static_cast<std::size_t>(V.rows());
    faces_of_.resize(n);
    quadric_.assign(n, Quadric{});
    stamp_.assign(n, 0);
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

  void run(int target) {
    for (std::size_t f = 0; f < faces_.size(); ++f)
      for (int c = 0; c < 3; ++c) {
        const int a = faces_[f][c], b = faces_[f][(c + 1) % 3];
        if (a < b) push_edge(a, b);
      }
    while (alive_count_ > target && !queue_.empty()) {
      const Candidate top = queue_.top();
      queue_.pop();
      if (!current(top)) continue;
      if (allowed(top.from, top.to)) {
        collapse(top.from, top.to);
      } else if (allowed(top.to, top.from)) {
        collapse(top.to, top.from);
      }
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

  // The cheaper direction of the edge a-b (the other is tried when it is refused).
  void push_edge(int a, int b) {
    if (locked_[static_cast<std::size_t>(a)] && locked_[static_cast<std::size_t>(b)]) return;
    const double ab = locked_[static_cast<std::size_t>(a)] ? HUGE_VAL : cost(a, b);
    const double ba = locked_[static_cast<std::size_t>(b)] ? HUGE_VAL : cost(b, a);
    const bool forward = ab < ba || (ab == ba && a < b);
    const int from = forward ? a : b, to = forward ? b : a;
    queue_.push({forward ? ab : ba, from, to, stamp_[static_cast<std::size_t>(from)], stamp_[static_cast<std::size_t>(to)]});
  }

  bool current(const Candidate& c) const {
    const std::size_t from = static_cast<std::size_t>(c.from), to = static_cast<std::size_t>(c.to);
    return alive_vertex_[from] && alive_vertex_[to] && stamp_[from] == c.from_stamp && stamp_[to] == c.to_stamp;
  }

  // The alive faces of v, and its neighbours (sorted, unique).
  void ring(int v, std::vector<int>& faces, std::vector<int>& neighbours) const {
    faces.clear();
    neighbours.clear();
    for (int f : faces_of_[static_cast<std::size_t>(v)]) {
      if (!alive_face_[static_cast<std::size_t>(f)]) continue;
      faces.push_back(f);
      for (int c = 0; c < 3; ++c)
        if (faces_[static_cast<std::size_t>(f)][c] != v) neighbours.push_back(faces_[static_cast<std::size_t>(f)][c]);
    }
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  }

  static double compactness(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Vector3d& cross) {
    cross = (b - a).cross(c - a);
    const double squares = (b - a).squaredNorm() + (c - b).squaredNorm() + (a - c).squaredNorm();
    return squares > 0.0 ? 2.0 * std::sqrt(3.0) * cross.norm() / squares : 0.0;
  }

  bool allowed(int from, int to) {
    if (locked_[static_cast<std::size_t>(from)]) return false;
    ring(from, from_faces_, from_ring_);
    ring(to, to_faces_, to_ring_);
    if (!std::binary_search(from_ring_.begin(), from_ring_.end(), to)) return false;
    shared_.clear();
    std::set_intersection(from_ring_.begin(), from_ring_.end(), to_ring_.begin(), to_ring_.end(), std::back_inserter(shared_));
    int edge_faces = 0;
    for (int f : from_faces_) {
      const auto& face = faces_[static_cast<std::size_t>(f)];
      if (face[0] == to || face[1] == to || face[2] == to) ++edge_faces;
    }
    if (edge_faces != 2 || shared_.size() != 2) return false;
    // A closed mesh of four vertices (a tetrahedron) cannot lose another one.
    if (from_ring_.size() < 4 && to_ring_.size() < 4) return false;
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

  void collapse(int from, int to) {
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
    ++stamp_[v];
    ring(to, to_faces_, to_ring_);
    for (int w : to_ring_) push_edge(std::min(to, w), std::max(to, w));
  }

  const Vertices& V_;
  DecimateOptions options_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<char> alive_face_;
  std::vector<std::vector<int>> faces_of_;
  std::vector<Quadric> quadric_;
  std::vector<unsigned> stamp_;
  std::vector<char> alive_vertex_, locked_;
  int alive_count_ = 0;
  std::priority_queue<Candidate, std::vector<Candidate>, Later> queue_;
  std::vector<int> from_faces_, to_faces_, from_ring_, to_ring_, shared_;
};

}  // namespace

DecimatedMesh decimate_mesh(const Vertices& V, const Faces& F, int target_vertices, const DecimateOptions& options) {
  Decimator decimator(V, F, options);
  decimator.run(std::max(target_vertices, 4));
  return decimator.result();
}

}  // namespace offsetopt
