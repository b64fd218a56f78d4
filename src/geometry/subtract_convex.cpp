#include "geometry/subtract_convex.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include <Eigen/Geometry>

#include "geometry/aabb.h"
#include "geometry/bvh.h"
#include "geometry/exact_triangle_intersection.h"
#include "geometry/point_in_solid.h"
#include "geometry/triangulate_polygons.h"

namespace offsetopt {
namespace {

using Vec3 = Eigen::Vector3d;
using EdgeKey = std::pair<int, int>;  // (lower, higher) vertex index

// A new vertex on an edge, at parameter t from the edge's lower-numbered end; `enters`: going from
// that end to the other, the edge passes into the other body here.
struct Crossing {
  double t = 0.0;
  int vertex = -1;
  bool enters = false;
};

// Part of a face's intersection with the other body, from `start` to `end` along d = n_f × n_g.
struct Chord {
  int start = -1, end = -1;
};

struct Degenerate {
  std::string why;
};

// Exact orientation sign; zero means the inputs are not in general position.
int sign_of(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const int s = orient3d_sign(a, b, c, d);
  if (s == 0) throw Degenerate{"four points coplanar"};
  return s;
}

Aabb box_of(const Vec3& a, const Vec3& b, const Vec3& c) {
  Aabb box;
  box.lo = a.cwiseMin(b).cwiseMin(c);
  box.hi = a.cwiseMax(b).cwiseMax(c);
  return box;
}

bool boxes_meet(const Aabb& a, const Aabb& b) {
  return (a.lo.array() <= b.hi.array()).all() && (b.lo.array() <= a.hi.array()).all();
}

// Two bodies A (the solid, vertices 0..) and B (the cutter); the output's vertices are A's, then
// B's, then the crossings.
class Subtractor {
 public:
  Subtractor(const Mesh& solid, const Mesh& cutter) : a_(solid), b_(cutter) {
    a_count_ = static_cast<int>(solid.V.rows());
    points_.reserve(static_cast<std::size_t>(solid.V.rows() + cutter.V.rows()));
    for (Eigen::Index i = 0; i < solid.V.rows(); ++i) points_.push_back(solid.V.row(i).transpose());
    for (Eigen::Index i = 0; i < cutter.V.rows(); ++i) points_.push_back(cutter.V.row(i).transpose());
  }

  SubtractResult run() {
    SubtractResult result;
    find_chords();
    result.touched = !chords_a_.empty();
    classify_cutter_vertices();
    check_edges(edges_a_, [&](int v) { return inside_cutter(v); });
    check_edges(edges_b_, [&](int v) { return inside_b_[static_cast<std::size_t>(v - a_count_)] != 0; });
    std::vector<std::array<int, 3>> faces;
    std::vector<int> source;
    for (int f = 0; f < static_cast<int>(a_.F.rows()); ++f) {
      const std::array<int, 3> corners{a_.F(f, 0), a_.F(f, 1), a_.F(f, 2)};
      const auto chords = chords_a_.find(f);
      if (chords == chords_a_.end()) {
        const bool candidate = boxes_meet(box_of(point(corners[0]), point(corners[1]), point(corners[2])), cutter_box_);
        int inside = 0;
        if (candidate)
          for (int v : corners) inside += inside_cutter(v) ? 1 : 0;
        if (inside == 3) {
          ++result.removed_solid_faces;
          continue;
        }
        if (inside != 0) throw Degenerate{"a solid face partly inside the cutter without a crossing"};
        faces.push_back(corners);
        source.push_back(f);
        continue;
      }
      ++result.cut_solid_faces;
      const auto pieces = face_pieces(corners, chords->second, edges_a_, [&](int v) { return !inside_cutter(v); });
      for (const auto& t : pieces) {
        faces.push_back(t);
        source.push_back(-1);
      }
    }
    for (int g = 0; g < static_cast<int>(b_.F.rows()); ++g) {
      const std::array<int, 3> corners{b_.F(g, 0) + a_count_, b_.F(g, 1) + a_count_, b_.F(g, 2) + a_count_};
      auto keep = [&](int v) { return inside_b_[static_cast<std::size_t>(v - a_count_)] != 0; };
      std::vector<std::array<int, 3>> pieces;
      const auto chords = chords_b_.find(g);
      if (chords == chords_b_.end()) {
        int inside = 0;
        for (int v : corners) inside += keep(v) ? 1 : 0;
        if (inside == 0) continue;
        if (inside != 3) throw Degenerate{"a cutter triangle partly inside the solid without a crossing"};
        pieces.push_back(corners);
      } else {
        pieces = face_pieces(corners, chords->second, edges_b_, [&](int v) { return v >= a_count_ ? keep(v) : true; });
      }
      ++result.cutter_faces_kept;
      for (const auto& t : pieces) {
        faces.push_back({t[0], t[2], t[1]});  // the cutter's part bounds the removed region: reversed
        source.push_back(-1);
      }
    }
    result.new_vertices = static_cast<int>(points_.size()) - a_count_ - static_cast<int>(b_.V.rows());
    compact(faces, source, result);
    return result;
  }

 private:
  const Vec3& point(int v) const { return points_[static_cast<std::size_t>(v)]; }
  Vec3 a_corner(int f, int k) const { return a_.V.row(a_.F(f, k)).transpose(); }
  Vec3 b_corner(int g, int k) const { return b_.V.row(b_.F(g, k)).transpose(); }

  // A solid vertex is inside the convex cutter when it is on the inner side of every triangle's
  // plane; on no positive side but on some plane: not in general position.
  bool inside_cutter(int v) {
    auto& known = inside_a_[v];
    if (known != 0) return known > 0;
    bool zero = false;
    for (int g = 0; g < static_cast<int>(b_.F.rows()); ++g) {
      const int s = orient3d_sign(b_corner(g, 0), b_corner(g, 1), b_corner(g, 2), point(v));
      if (s > 0) {
        known = -1;
        return false;
      }
      zero = zero || s == 0;
    }
    if (zero) throw Degenerate{"a solid vertex on a cutter plane"};
    known = 1;
    return true;
  }

  void classify_cutter_vertices() {
    inside_b_.assign(static_cast<std::size_t>(b_.V.rows()), 0);
    const TriangleBvh bvh(a_.V, a_.F);
    for (Eigen::Index i = 0; i < b_.V.rows(); ++i) inside_b_[static_cast<std::size_t>(i)] = point_in_solid(bvh, b_.V.row(i).transpose()) ? 1 : 0;
  }

  // The crossing of edge (lo, hi) of one body with the plane of a triangle of the other, made once.
  int crossing_vertex(std::map<std::tuple<int, int, int>, int>& made, const EdgeKey& edge, int triangle,
                      const Vec3& p0, const Vec3& p1, const Vec3& p2, bool enters, std::map<EdgeKey, std::vector<Crossing>>& lists) {
    const auto key = std::make_tuple(edge.first, edge.second, triangle);
    const auto found = made.find(key);
    if (found != made.end()) return found->second;
    const Vec3 n = (p1 - p0).cross(p2 - p0);
    const Vec3& lo = point(edge.first);
    const Vec3& hi = point(edge.second);
    const double d_lo = n.dot(lo - p0), d_hi = n.dot(hi - p0);
    double t = d_lo / (d_lo - d_hi);
    t = std::min(1.0, std::max(0.0, t));
    const int id = static_cast<int>(points_.size());
    points_.push_back(lo + t * (hi - lo));
    made.emplace(key, id);
    lists[edge].push_back({t, id, enters});
    return id;
  }

  // For every solid face f and cutter triangle g that meet: the segment f ∩ g, its ends as shared
  // symbolic vertices, recorded on both faces.
  void find_chords() {
    cutter_box_.lo = b_.V.colwise().minCoeff().transpose();
    cutter_box_.hi = b_.V.colwise().maxCoeff().transpose();
    std::vector<Aabb> cutter_boxes;
    for (int g = 0; g < static_cast<int>(b_.F.rows()); ++g) cutter_boxes.push_back(box_of(b_corner(g, 0), b_corner(g, 1), b_corner(g, 2)));
    for (int f = 0; f < static_cast<int>(a_.F.rows()); ++f) {
      const std::array<Vec3, 3> fp{a_corner(f, 0), a_corner(f, 1), a_corner(f, 2)};
      const Aabb fbox = box_of(fp[0], fp[1], fp[2]);
      if (!boxes_meet(fbox, cutter_box_)) continue;
      for (int g = 0; g < static_cast<int>(b_.F.rows()); ++g) {
        if (!boxes_meet(fbox, cutter_boxes[static_cast<std::size_t>(g)])) continue;
        pair_chord(f, fp, g);
      }
    }
  }

  void pair_chord(int f, const std::array<Vec3, 3>& fp, int g) {
    const std::array<Vec3, 3> gp{b_corner(g, 0), b_corner(g, 1), b_corner(g, 2)};
    std::array<int, 3> sf{}, sg{};  // f's corners against g's plane, g's corners against f's plane
    for (int k = 0; k < 3; ++k) sf[k] = sign_of(gp[0], gp[1], gp[2], fp[k]);
    if (sf[0] == sf[1] && sf[1] == sf[2]) return;
    for (int k = 0; k < 3; ++k) sg[k] = sign_of(fp[0], fp[1], fp[2], gp[k]);
    if (sg[0] == sg[1] && sg[1] == sg[2]) return;
    struct End {
      int vertex;
      bool first;  // the segment's start along d
    };
    std::vector<End> ends;
    // Edges of f through g: the X vertices. Along d, d enters f through the edge whose head lies on
    // g's positive side.
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      if (sf[k] == sf[k1]) continue;
      if (!segment_through(fp[k], fp[k1], gp)) continue;
      const int a = a_.F(f, k), b = a_.F(f, k1);
      const EdgeKey edge{std::min(a, b), std::max(a, b)};
      const bool lo_outside = (edge.first == a ? sf[k] : sf[k1]) > 0;
      const int id = crossing_vertex(made_a_, edge, g, gp[0], gp[1], gp[2], lo_outside, edges_a_);
      ends.push_back({id, sf[k1] > 0});
    }
    // Edges of g through f: the Y vertices. Along d, d enters g through the edge whose tail lies on
    // f's positive side.
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      if (sg[k] == sg[k1]) continue;
      if (!segment_through(gp[k], gp[k1], fp)) continue;
      const int a = b_.F(g, k) + a_count_, b = b_.F(g, k1) + a_count_;
      const EdgeKey edge{std::min(a, b), std::max(a, b)};
      const bool lo_in_front = (edge.first == a ? sg[k] : sg[k1]) > 0;  // in front of f: outside the solid
      const int id = crossing_vertex(made_b_, edge, f, fp[0], fp[1], fp[2], lo_in_front, edges_b_);
      ends.push_back({id, sg[k] > 0});
    }
    if (ends.empty()) return;
    if (ends.size() != 2 || ends[0].first == ends[1].first) throw Degenerate{"a face pair meets in other than one segment"};
    const Chord chord = ends[0].first ? Chord{ends[0].vertex, ends[1].vertex} : Chord{ends[1].vertex, ends[0].vertex};
    chords_a_[f].push_back(chord);
    chords_b_[g].push_back(chord);
  }

  // The open segment p-q passes through the interior of triangle t (its ends on opposite sides).
  static bool segment_through(const Vec3& p, const Vec3& q, const std::array<Vec3, 3>& t) {
    const int s0 = sign_of(p, q, t[0], t[1]);
    const int s1 = sign_of(p, q, t[1], t[2]);
    const int s2 = sign_of(p, q, t[2], t[0]);
    return s0 == s1 && s1 == s2;
  }

  // Along every crossed edge the crossings must alternate in and out, consistent with its ends,
  // and be far enough apart for their floating-point order to be the true one.
  template <class Inside>
  void check_edges(std::map<EdgeKey, std::vector<Crossing>>& lists, Inside inside) {
    for (auto& [edge, list] : lists) {
      std::sort(list.begin(), list.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
      bool in = inside(edge.first);
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (i > 0 && !(list[i].t - list[i - 1].t > 1e-9)) throw Degenerate{"two crossings of one edge too close to order"};
        if (list[i].enters == in) throw Degenerate{"crossings along an edge do not alternate"};
        in = !in;
      }
      if (in != inside(edge.second)) throw Degenerate{"an edge's crossings disagree with its ends"};
    }
  }

  // The part of a face kept (`kept(v)` for its corners), bounded by its edges' kept pieces and the
  // chords reversed (the kept side is left of −d in either body), triangulated.
  template <class Kept>
  std::vector<std::array<int, 3>> face_pieces(const std::array<int, 3>& corners, const std::vector<Chord>& chords,
                                              const std::map<EdgeKey, std::vector<Crossing>>& lists, Kept kept) {
    std::map<int, int> next;
    auto add = [&](int from, int to) {
      if (!next.emplace(from, to).second) throw Degenerate{"two boundary pieces leave one vertex"};
    };
    for (int k = 0; k < 3; ++k) {
      const int a = corners[k], b = corners[(k + 1) % 3];
      const EdgeKey edge{std::min(a, b), std::max(a, b)};
      const auto found = lists.find(edge);
      // Copy-constructed, not assigned: GCC 12 warns (-Wnonnull) on assigning into an empty vector.
      std::vector<Crossing> along = found != lists.end() ? found->second : std::vector<Crossing>();
      if (edge.first != a) std::reverse(along.begin(), along.end());
      int current = a;
      bool keep = kept(a);
      for (const Crossing& c : along) {
        if (keep) add(current, c.vertex);
        keep = !keep;
        current = c.vertex;
      }
      if (keep) add(current, b);
    }
    for (const Chord& c : chords) add(c.end, c.start);

    const Vec3 normal = (point(corners[1]) - point(corners[0])).cross(point(corners[2]) - point(corners[0]));
    int axis = 0;
    for (int i = 1; i < 3; ++i)
      if (std::fabs(normal(i)) > std::fabs(normal(axis))) axis = i;
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    if (normal(axis) < 0.0) std::swap(u, v);
    std::vector<std::vector<Eigen::Vector2d>> loops;
    std::vector<int> ids;
    std::map<int, int> unused = next;
    while (!unused.empty()) {
      const int first = unused.begin()->first;
      std::vector<Eigen::Vector2d> loop;
      int at = first;
      for (std::size_t steps = 0;; ++steps) {
        const auto it = unused.find(at);
        if (it == unused.end() || steps > next.size()) throw Degenerate{"a face's boundary does not close"};
        loop.emplace_back(point(at)(u), point(at)(v));
        ids.push_back(at);
        at = it->second;
        unused.erase(it);
        if (at == first) break;
      }
      loops.push_back(std::move(loop));
    }
    const PolygonTriangulation t = triangulate_polygons(loops);
    if (t.status != TriangulationStatus::ok) throw Degenerate{"a cut face could not be triangulated: " + t.message};
    std::vector<std::array<int, 3>> out;
    for (const auto& tri : t.triangles)
      out.push_back({ids[static_cast<std::size_t>(tri[0])], ids[static_cast<std::size_t>(tri[1])], ids[static_cast<std::size_t>(tri[2])]});
    return out;
  }

  void compact(const std::vector<std::array<int, 3>>& faces, std::vector<int>& source, SubtractResult& result) {
    std::vector<int> index(points_.size(), -1);
    int count = 0;
    for (const auto& t : faces)
      for (int v : t)
        if (index[static_cast<std::size_t>(v)] < 0) index[static_cast<std::size_t>(v)] = 0;
    for (std::size_t i = 0; i < index.size(); ++i)
      if (index[i] == 0) index[i] = count++;
    result.mesh.V.resize(count, 3);
    for (std::size_t i = 0; i < index.size(); ++i)
      if (index[i] >= 0) result.mesh.V.row(index[i]) = points_[i].transpose();
    result.mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (int c = 0; c < 3; ++c) result.mesh.F(static_cast<Eigen::Index>(f), c) = index[static_cast<std::size_t>(faces[f][static_cast<std::size_t>(c)])];
    result.source_face = std::move(source);
  }

  const Mesh& a_;
  const Mesh& b_;
  int a_count_ = 0;
  std::vector<Vec3> points_;
  Aabb cutter_box_;
  std::map<int, signed char> inside_a_;  // solid vertex: 1 inside the cutter, -1 outside
  std::vector<char> inside_b_;           // cutter vertex inside the solid
  std::map<std::tuple<int, int, int>, int> made_a_, made_b_;
  std::map<EdgeKey, std::vector<Crossing>> edges_a_, edges_b_;
  std::map<int, std::vector<Chord>> chords_a_, chords_b_;
};

}  // namespace

SubtractResult subtract_convex(const Mesh& solid, const Mesh& cutter) {
  SubtractResult result;
  if (solid.F.rows() == 0 || cutter.F.rows() < 4) {
    result.status = SubtractStatus::bad_input;
    result.message = "the solid or the cutter has no faces";
    return result;
  }
  try {
    Subtractor s(solid, cutter);
    result = s.run();
  } catch (const Degenerate& d) {
    result = SubtractResult();
    result.status = SubtractStatus::degenerate;
    result.message = d.why;
  }
  return result;
}

}  // namespace offsetopt
