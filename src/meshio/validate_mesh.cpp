#include "meshio/validate_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include "meshio/read_raw_mesh.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    for (std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<std::uint32_t>(i);
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  // The smaller root wins, so the result does not depend on the order of unions.
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) parent_[b] = a;
    else parent_[a] = b;
  }

 private:
  std::vector<std::uint32_t> parent_;
};

// Neumaier's compensated sum: the volume of a large fine mesh is a sum of many small terms.
class CompensatedSum {
 public:
  void add(double x) {
    const double t = sum_ + x;
    if (std::fabs(sum_) >= std::fabs(x)) compensation_ += (sum_ - t) + x;
    else compensation_ += (x - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0, compensation_ = 0;
};

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Sorts `items` by `less`, a strict total order whose first key is bucket(item) in
// [0, buckets): a counting sort on the bucket, then std::sort inside each (small) bucket. The
// result is the same as std::sort's, in linear time for mesh-sized buckets.
template <typename T, typename Bucket, typename Less>
void bucket_sort(std::vector<T>& items, std::size_t buckets, Bucket bucket, Less less) {
  std::vector<std::size_t> start(buckets + 1, 0);
  for (const T& x : items) ++start[static_cast<std::size_t>(bucket(x)) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  std::vector<T> sorted(items.size());
  for (const T& x : items) sorted[fill[static_cast<std::size_t>(bucket(x))]++] = x;
  for (std::size_t b = 0; b < buckets; ++b)
    if (start[b + 1] - start[b] > 1)
      std::sort(sorted.begin() + static_cast<std::ptrdiff_t>(start[b]), sorted.begin() + static_cast<std::ptrdiff_t>(start[b + 1]), less);
  items.swap(sorted);
}

struct HalfEdge {
  int lo, hi;    // undirected edge, lo < hi
  int face;
  bool forward;  // traversed lo -> hi
};

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Vec3& p) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  bool contains(const Vec3& p) const {
    for (int k = 0; k < 3; ++k)
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
    return true;
  }
  double diagonal() const {
    const Vec3 d = sub(hi, lo);
    return std::sqrt(dot(d, d));
  }
};

enum class RayHit { kMiss, kHit, kAmbiguous };

// Möller-Trumbore; kAmbiguous when the ray passes within a relative 1e-9 of an edge or the
// origin lies (nearly) on the triangle, where the parity count cannot be trusted.
RayHit cast(const Vec3& origin, const Vec3& direction, const Vec3& a, const Vec3& b, const Vec3& c, double length_scale) {
  const Vec3 e1 = sub(b, a), e2 = sub(c, a);
  const Vec3 p = cross(direction, e2);
  const double det = dot(e1, p);
  const double scale = std::sqrt(dot(e1, e1) * dot(e2, e2));
  if (!(std::fabs(det) > 1e-12 * scale)) return RayHit::kMiss;  // parallel (grazing hits are vanishingly rare)
  const Vec3 t_vec = sub(origin, a);
  const double u = dot(t_vec, p) / det;
  const double eps = 1e-9;
  if (u < -eps || u > 1 + eps) return RayHit::kMiss;
  const Vec3 q = cross(t_vec, e1);
  const double v = dot(direction, q) / det;
  if (v < -eps || u + v > 1 + eps) return RayHit::kMiss;
  const double t = dot(e2, q) / det;
  if (t < -eps * length_scale) return RayHit::kMiss;
  if (u < eps || v < eps || u + v > 1 - eps || t < eps * length_scale) return RayHit::kAmbiguous;
  return RayHit::kHit;
}

Vec3 row(const Mesh& mesh, int v) { return {mesh.V(v, 0), mesh.V(v, 1), mesh.V(v, 2)}; }

// Number of shells among `faces_of` (other than `self`) that contain `point`, by ray parity.
int nesting_depth(const Mesh& mesh, const Vec3& point, int self, const std::vector<std::vector<int>>& faces_of,
                  const std::vector<Box>& boxes) {
  static const Vec3 kDirections[3] = {{0.3183098861837907, 0.5772156649015329, 0.7517464825841436},
                                      {-0.6, 0.48, 0.64},
                                      {0.48, -0.64, 0.6}};
  int depth = 0;
  for (std::size_t shell = 0; shell < faces_of.size(); ++shell) {
    if (static_cast<int>(shell) == self || !boxes[shell].contains(point)) continue;
    const double length_scale = boxes[shell].diagonal();
    int crossings = 0;
    for (const Vec3& direction : kDirections) {
      crossings = 0;
      bool ambiguous = false;
      for (const int f : faces_of[shell]) {
        const RayHit hit = cast(point, direction, row(mesh, mesh.F(f, 0)), row(mesh, mesh.F(f, 1)),
                                row(mesh, mesh.F(f, 2)), length_scale);
        if (hit == RayHit::kAmbiguous) {
          ambiguous = true;
          break;
        }
        if (hit == RayHit::kHit) ++crossings;
      }
      if (!ambiguous) break;
    }
    if (crossings % 2 == 1) ++depth;
  }
  return depth;
}

constexpr int kMaxShellsForNesting = 10000;
// Ray-triangle tests the nesting check may spend (a few seconds at most). Its cost is the sum,
// over the shells, of the faces of every other shell whose box contains the shell's test point:
// up to #shells x #F, so a file of 10,000 nested shells inside one large one took minutes.
constexpr long long kMaxNestingTriangleTests = 100000000;

}  // namespace

const Defect* MeshValidation::find(DefectKind kind) const {
  for (const Defect& d : defects)
    if (d.kind == kind) return &d;
  return nullptr;
}

MeshValidation validate_mesh(const Mesh& mesh) {
  MeshValidation out;
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
  out.vertices = nv;
  out.faces = nf;
  auto add = [&out](const Defect& d) {
    if (d.count > 0) out.defects.push_back(d);
  };

  if (nf == 0) {
    Defect d;
    d.kind = DefectKind::kEmptyMesh;
    d.count = 1;
    d.bound = nv;
    out.defects.push_back(d);
    out.unreferenced_vertices = nv;
    out.first_unreferenced = nv > 0 ? 0 : -1;
    return out;
  }

  // Coordinates.
  Defect non_finite{DefectKind::kNonFiniteCoordinate}, too_large{DefectKind::kCoordinateTooLarge};
  std::vector<char> bad_vertex(static_cast<std::size_t>(nv), 0);
  auto note_vertex = [&bad_vertex](Defect& d, long long v, double x) {
    if (d.count == 0) {
      d.vertex = v;
      d.value = x;
    }
    ++d.count;
    bad_vertex[static_cast<std::size_t>(v)] = 1;
  };
  for (long long v = 0; v < nv; ++v) {
    int worst = -1;  // first non-finite coordinate, else first too large one
    for (int k = 0; k < 3 && worst < 0; ++k)
      if (!std::isfinite(mesh.V(v, k))) worst = k;
    if (worst >= 0) {
      note_vertex(non_finite, v, mesh.V(v, worst));
      continue;
    }
    for (int k = 0; k < 3 && worst < 0; ++k)
      if (std::fabs(mesh.V(v, k)) > kMaxCoordinate) worst = k;
    if (worst >= 0) note_vertex(too_large, v, mesh.V(v, worst));
  }
  add(non_finite);
  add(too_large);
  const bool coordinates_ok = non_finite.count == 0 && too_large.count == 0;

  // Indices.
  Defect out_of_range{DefectKind::kIndexOutOfRange};
  out_of_range.bound = nv;
  for (long long f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.F(f, k);
      if (i >= 0 && i < nv) continue;
      if (out_of_range.count == 0) {
        out_of_range.face = f;
        out_of_range.value = i;
      }
      ++out_of_range.count;
      break;
    }
  }
  if (out_of_range.count > 0) {
    add(out_of_range);
    return out;  // nothing below can index V safely
  }

  // Unreferenced vertices (a note).
  std::vector<char> referenced(static_cast<std::size_t>(nv), 0);
  for (long long f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) referenced[static_cast<std::size_t>(mesh.F(f, k))] = 1;
  for (long long v = 0; v < nv; ++v)
    if (!referenced[static_cast<std::size_t>(v)]) {
      if (out.unreferenced_vertices == 0) out.first_unreferenced = v;
      ++out.unreferenced_vertices;
    }

  // Degenerate faces.
  Defect degenerate{DefectKind::kDegenerateFace};
  for (long long f = 0; f < nf; ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    bool repeated = a == b || b == c || a == c;
    bool zero_area = false;
    if (!repeated && !bad_vertex[static_cast<std::size_t>(a)] && !bad_vertex[static_cast<std::size_t>(b)] &&
        !bad_vertex[static_cast<std::size_t>(c)]) {
      const Vec3 pa = row(mesh, a);
      const Vec3 n = cross(sub(row(mesh, b), pa), sub(row(mesh, c), pa));
      zero_area = n[0] == 0 && n[1] == 0 && n[2] == 0;
    }
    if (zero_area) {
      // Three distinct collinear corners (CAD exports): a valid part of a closed surface that
      // adds nothing to any volume integral; a note, not a defect.
      if (out.zero_area_faces == 0) out.first_zero_area_face = f;
      ++out.zero_area_faces;
      continue;
    }
    if (!repeated) continue;
    ++out.repeated_vertex_faces;
    out.droppable_faces.push_back(f);
    if (degenerate.count == 0) {
      degenerate.face = f;
      degenerate.value = 0;
    }
    ++degenerate.count;
  }
  add(degenerate);

  // Duplicate faces: sort by the sorted vertex triple.
  {
    std::vector<std::array<int, 4>> keys(static_cast<std::size_t>(nf));
    for (long long f = 0; f < nf; ++f) {
      std::array<int, 3> t = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
      std::sort(t.begin(), t.end());
      keys[static_cast<std::size_t>(f)] = {t[0], t[1], t[2], static_cast<int>(f)};
    }
    bucket_sort(keys, static_cast<std::size_t>(nv), [](const std::array<int, 4>& k) { return k[0]; },
                std::less<std::array<int, 4>>());
    auto same_cycle = [&mesh](long long f, long long g) {
      for (int r = 0; r < 3; ++r)
        if (mesh.F(g, 0) == mesh.F(f, r) && mesh.F(g, 1) == mesh.F(f, (r + 1) % 3) && mesh.F(g, 2) == mesh.F(f, (r + 2) % 3))
          return true;
      return false;
    };
    Defect duplicate{DefectKind::kDuplicateFace};
    // `first` starts the run of equal triples (walking back from each copy was quadratic in
    // the number of copies: minutes for 200,000 copies of one face).
    std::size_t first = 0;
    for (std::size_t i = 1; i < keys.size(); ++i) {
      if (keys[i][0] != keys[i - 1][0] || keys[i][1] != keys[i - 1][1] || keys[i][2] != keys[i - 1][2]) {
        first = i;
        continue;
      }
      const long long original = keys[first][3], copy = keys[i][3];
      const bool same = same_cycle(original, copy);
      if (same) {
        ++out.same_orientation_duplicates;
        out.droppable_faces.push_back(copy);
      }
      if (duplicate.count == 0 || copy < duplicate.face) {
        duplicate.face = copy;
        duplicate.other_face = original;
        duplicate.value = same ? 1 : -1;
      }
      ++duplicate.count;
    }
    add(duplicate);
    std::sort(out.droppable_faces.begin(), out.droppable_faces.end());
    out.droppable_faces.erase(std::unique(out.droppable_faces.begin(), out.droppable_faces.end()), out.droppable_faces.end());
  }

  // Edges.
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(static_cast<std::size_t>(3 * nf));
  for (long long f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = mesh.F(f, k), w = mesh.F(f, (k + 1) % 3);
      if (u == w) continue;
      half_edges.push_back({std::min(u, w), std::max(u, w), static_cast<int>(f), u < w});
    }
  bucket_sort(half_edges, static_cast<std::size_t>(nv), [](const HalfEdge& e) { return e.lo; },
              [](const HalfEdge& a, const HalfEdge& b) {
                if (a.lo != b.lo) return a.lo < b.lo;
                if (a.hi != b.hi) return a.hi < b.hi;
                if (a.face != b.face) return a.face < b.face;
                return a.forward < b.forward;
              });
  Defect boundary{DefectKind::kBoundaryEdge}, non_manifold_edge{DefectKind::kNonManifoldEdge},
      inconsistent{DefectKind::kInconsistentOrientation};
  auto note_edge = [](Defect& d, const HalfEdge& e, long long face, long long other, double value) {
    if (d.count == 0 || face < d.face) {
      d.face = face;
      d.other_face = other;
      d.edge_from = e.lo;
      d.edge_to = e.hi;
      d.value = value;
    }
    ++d.count;
  };
  DisjointSets corners(static_cast<std::size_t>(3 * nf));
  auto corner_of = [&mesh](int face, int vertex) {
    int k = 0;
    while (k < 2 && mesh.F(face, k) != vertex) ++k;
    return static_cast<std::uint32_t>(3 * face + k);
  };
  long long edge_count = 0;
  for (std::size_t i = 0; i < half_edges.size();) {
    std::size_t j = i + 1;
    while (j < half_edges.size() && half_edges[j].lo == half_edges[i].lo && half_edges[j].hi == half_edges[i].hi) ++j;
    ++edge_count;
    const HalfEdge& e = half_edges[i];
    const std::size_t n = j - i;
    if (n == 1) {
      note_edge(boundary, e, e.face, -1, 1);
    } else if (n > 2) {
      note_edge(non_manifold_edge, e, e.face, half_edges[i + 1].face, static_cast<double>(n));
    } else if (half_edges[i].forward == half_edges[i + 1].forward) {
      note_edge(inconsistent, e, e.face, half_edges[i + 1].face, 2);
    }
    for (std::size_t k = i + 1; k < j; ++k) {
      corners.unite(corner_of(half_edges[i].face, e.lo), corner_of(half_edges[k].face, e.lo));
      corners.unite(corner_of(half_edges[i].face, e.hi), corner_of(half_edges[k].face, e.hi));
    }
    i = j;
  }
  std::vector<HalfEdge>().swap(half_edges);
  out.edges = edge_count;
  add(boundary);
  add(non_manifold_edge);

  // Non-manifold vertices: the corners around a vertex, joined across shared edges, must form
  // one fan. Corners grouped by vertex with a counting sort.
  {
    std::vector<std::uint32_t> start(static_cast<std::size_t>(nv) + 1, 0);
    for (long long c = 0; c < 3 * nf; ++c) ++start[static_cast<std::size_t>(mesh.F(c / 3, c % 3)) + 1];
    for (long long v = 0; v < nv; ++v) start[static_cast<std::size_t>(v) + 1] += start[static_cast<std::size_t>(v)];
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), roots(static_cast<std::size_t>(3 * nf));
    for (long long c = 0; c < 3 * nf; ++c) {
      const std::size_t v = static_cast<std::size_t>(mesh.F(c / 3, c % 3));
      // A face that repeats a vertex counts once at it: through its first corner there.
      roots[fill[v]++] = corners.find(corner_of(static_cast<int>(c / 3), static_cast<int>(v)));
    }
    Defect pinched{DefectKind::kNonManifoldVertex};
    for (long long v = 0; v < nv; ++v) {
      auto begin = roots.begin() + start[static_cast<std::size_t>(v)], end = roots.begin() + start[static_cast<std::size_t>(v) + 1];
      if (end - begin < 2) continue;
      std::sort(begin, end);
      const long long fans = std::unique(begin, end) - begin;
      if (fans < 2) continue;
      if (pinched.count == 0) {
        pinched.vertex = v;
        pinched.value = static_cast<double>(fans);
      }
      ++pinched.count;
    }
    add(pinched);
  }
  add(inconsistent);

  // Components: faces sharing a vertex, numbered in order of their first face.
  std::vector<std::vector<int>> faces_of;
  {
    DisjointSets vertex_sets(static_cast<std::size_t>(nv));
    for (long long f = 0; f < nf; ++f) {
      vertex_sets.unite(static_cast<std::uint32_t>(mesh.F(f, 0)), static_cast<std::uint32_t>(mesh.F(f, 1)));
      vertex_sets.unite(static_cast<std::uint32_t>(mesh.F(f, 0)), static_cast<std::uint32_t>(mesh.F(f, 2)));
    }
    std::vector<int> id_of_root(static_cast<std::size_t>(nv), -1);
    out.face_component.resize(static_cast<std::size_t>(nf));
    for (long long f = 0; f < nf; ++f) {
      const std::uint32_t root = vertex_sets.find(static_cast<std::uint32_t>(mesh.F(f, 0)));
      if (id_of_root[root] < 0) {
        id_of_root[root] = static_cast<int>(faces_of.size());
        faces_of.emplace_back();
      }
      out.face_component[static_cast<std::size_t>(f)] = id_of_root[root];
      faces_of[static_cast<std::size_t>(id_of_root[root])].push_back(static_cast<int>(f));
    }
    out.components = static_cast<int>(faces_of.size());
  }

  const bool closed_manifold = boundary.count == 0 && non_manifold_edge.count == 0;
  if (closed_manifold && !out.find(DefectKind::kNonManifoldVertex)) {
    long long referenced_count = nv - out.unreferenced_vertices;
    out.euler_characteristic = referenced_count - edge_count + nf;
    const long long twice_genus = 2LL * out.components - out.euler_characteristic;
    if (twice_genus >= 0 && twice_genus % 2 == 0) out.genus = twice_genus / 2;
  } else if (edge_count >= 0) {
    out.euler_characteristic = (nv - out.unreferenced_vertices) - edge_count + nf;
  }

  // Volumes per shell, nesting, and the sign each shell's volume must have.
  if (closed_manifold && inconsistent.count == 0 && coordinates_ok) {
    const int shells = out.components;
    std::vector<Box> boxes(static_cast<std::size_t>(shells));
    Box all;
    for (long long f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const Vec3 p = row(mesh, mesh.F(f, k));
        boxes[static_cast<std::size_t>(out.face_component[static_cast<std::size_t>(f)])].add(p);
        all.add(p);
      }
    const Vec3 centre = {0.5 * (all.lo[0] + all.hi[0]), 0.5 * (all.lo[1] + all.hi[1]), 0.5 * (all.lo[2] + all.hi[2])};
    out.component_volume.assign(static_cast<std::size_t>(shells), 0.0);
    CompensatedSum total;
    for (int s = 0; s < shells; ++s) {
      CompensatedSum sum;
      for (const int f : faces_of[static_cast<std::size_t>(s)]) {
        const Vec3 a = sub(row(mesh, mesh.F(f, 0)), centre), b = sub(row(mesh, mesh.F(f, 1)), centre),
                   c = sub(row(mesh, mesh.F(f, 2)), centre);
        sum.add(dot(a, cross(b, c)));  // six times the tetrahedron's volume; divided once below
      }
      out.component_volume[static_cast<std::size_t>(s)] = sum.value() / 6.0;
      total.add(sum.value());
    }
    out.volume = total.value() / 6.0;
    out.volume_computed = true;
    out.component_depth.assign(static_cast<std::size_t>(shells), 0);
    bool nesting_checked = shells == 1;
    if (shells > 1 && shells <= kMaxShellsForNesting) {
      std::vector<Vec3> points(static_cast<std::size_t>(shells));
      for (int s = 0; s < shells; ++s) {
        // A point of this shell: the centroid of its largest face, safely inside that face.
        int best = faces_of[static_cast<std::size_t>(s)][0];
        double best_area = -1;
        for (const int f : faces_of[static_cast<std::size_t>(s)]) {
          const Vec3 a = row(mesh, mesh.F(f, 0));
          const Vec3 n = cross(sub(row(mesh, mesh.F(f, 1)), a), sub(row(mesh, mesh.F(f, 2)), a));
          const double area = dot(n, n);
          if (area > best_area) {
            best_area = area;
            best = f;
          }
        }
        Vec3& point = points[static_cast<std::size_t>(s)];
        point = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
          const Vec3 p = row(mesh, mesh.F(best, k));
          for (int i = 0; i < 3; ++i) point[i] += p[i] / 3.0;
        }
      }
      // Beyond the budget the nesting is left unchecked, as beyond kMaxShellsForNesting.
      long long tests = 0;
      for (int s = 0; s < shells && tests <= kMaxNestingTriangleTests; ++s)
        for (int t = 0; t < shells; ++t)
          if (t != s && boxes[static_cast<std::size_t>(t)].contains(points[static_cast<std::size_t>(s)]))
            tests += static_cast<long long>(faces_of[static_cast<std::size_t>(t)].size());
      nesting_checked = tests <= kMaxNestingTriangleTests;
      if (nesting_checked)
        for (int s = 0; s < shells; ++s)
          out.component_depth[static_cast<std::size_t>(s)] =
              nesting_depth(mesh, points[static_cast<std::size_t>(s)], s, faces_of, boxes);
    }
    Defect zero{DefectKind::kZeroVolume}, inverted{DefectKind::kInsideOut};
    // A volume is zero when it is round-off of the coordinates in a box of this diagonal.
    const auto is_zero_volume = [](double volume, double diagonal) {
      return std::fabs(volume) <= 1e-12 * diagonal * diagonal * diagonal;
    };
    for (int s = 0; s < shells; ++s) {
      const double volume = out.component_volume[static_cast<std::size_t>(s)];
      const double diagonal = boxes[static_cast<std::size_t>(s)].diagonal();
      const long long first_face = faces_of[static_cast<std::size_t>(s)][0];
      const bool is_zero = is_zero_volume(volume, diagonal);
      const bool wrong_sign = (volume > 0) != (out.component_depth[static_cast<std::size_t>(s)] % 2 == 0);
      if (!is_zero && !wrong_sign) continue;
      Defect& d = is_zero ? zero : inverted;
      if (d.count == 0) {
        d.face = first_face;
        d.value = volume;
        d.bound = nesting_checked ? out.component_depth[static_cast<std::size_t>(s)] : -1;  // -1: unknown
      }
      ++d.count;
    }
    add(zero);
    add(inverted);
    // Every shell faces the right way (or every one the wrong way, which loading fixes by flipping
    // all faces), yet the total is not positive: a cavity encloses more than the part around it,
    // which only shells that cross each other can do. Nesting is decided at one point per shell,
    // so such shells pass the checks above and would reach the optimiser as a solid of negative
    // mass.
    const bool all_inverted = inverted.count == shells;
    const double oriented_total = all_inverted ? -out.volume : out.volume;
    if (zero.count == 0 && (inverted.count == 0 || all_inverted) && shells > 1 &&
        (oriented_total <= 0.0 || is_zero_volume(oriented_total, all.diagonal()))) {
      Defect overlap{DefectKind::kOverlappingShells};
      overlap.bound = all_inverted ? 1 : 0;
      double largest_cavity = 0;
      for (int s = 0; s < shells; ++s) {
        const double volume = (all_inverted ? -1.0 : 1.0) * out.component_volume[static_cast<std::size_t>(s)];
        if (volume >= 0) continue;
        ++overlap.count;
        if (-volume > largest_cavity) {
          largest_cavity = -volume;
          overlap.face = faces_of[static_cast<std::size_t>(s)][0];
        }
      }
      overlap.value = oriented_total;
      add(overlap);
    }
  }

  if (out.components > 1) {
    Defect several{DefectKind::kSeveralComponents};
    several.count = out.components;
    several.face = faces_of[1][0];
    several.value = out.components;
    add(several);
  }
  return out;
}

const char* defect_name(DefectKind kind) {
  switch (kind) {
    case DefectKind::kEmptyMesh: return "empty mesh";
    case DefectKind::kNonFiniteCoordinate: return "non-finite coordinates";
    case DefectKind::kCoordinateTooLarge: return "coordinates too large";
    case DefectKind::kIndexOutOfRange: return "vertex index out of range";
    case DefectKind::kDegenerateFace: return "degenerate faces";
    case DefectKind::kDuplicateFace: return "duplicate faces";
    case DefectKind::kBoundaryEdge: return "boundary edges";
    case DefectKind::kNonManifoldEdge: return "non-manifold edges";
    case DefectKind::kNonManifoldVertex: return "non-manifold vertices";
    case DefectKind::kInconsistentOrientation: return "inconsistent orientation";
    case DefectKind::kZeroVolume: return "zero volume";
    case DefectKind::kInsideOut: return "inside-out (negative volume)";
    case DefectKind::kOverlappingShells: return "overlapping shells";
    case DefectKind::kSeveralComponents: return "several components";
  }
  return "unknown defect";
}

const char* defect_unit(DefectKind kind) {
  switch (kind) {
    case DefectKind::kNonFiniteCoordinate:
    case DefectKind::kCoordinateTooLarge:
    case DefectKind::kNonManifoldVertex: return "vertices";
    case DefectKind::kBoundaryEdge:
    case DefectKind::kNonManifoldEdge:
    case DefectKind::kInconsistentOrientation: return "edges";
    case DefectKind::kZeroVolume:
    case DefectKind::kInsideOut:
    case DefectKind::kOverlappingShells: return "shells";
    case DefectKind::kSeveralComponents: return "components";
    default: return "faces";
  }
}

namespace {

long long map_index(long long i, const std::vector<long long>* origin) {
  if (i < 0 || !origin || i >= static_cast<long long>(origin->size())) return i;
  return (*origin)[static_cast<std::size_t>(i)];
}

int line_at(long long i, const std::vector<int>* lines) {
  if (i < 0 || !lines || i >= static_cast<long long>(lines->size())) return 0;
  return (*lines)[static_cast<std::size_t>(i)];
}

bool is_vertex_defect(DefectKind kind) {
  return kind == DefectKind::kNonFiniteCoordinate || kind == DefectKind::kCoordinateTooLarge ||
         kind == DefectKind::kNonManifoldVertex;
}

// (number, line) of the first instance in file numbering; line 0 when unknown.
std::pair<long long, int> first_location(const Defect& d, const DefectSource& s) {
  if (is_vertex_defect(d.kind)) {
    const long long v = map_index(d.vertex, s.vertex_origin);
    return {v, line_at(v, s.vertex_line)};
  }
  const long long f = map_index(d.face, s.face_origin);
  return {f, line_at(f, s.face_line)};
}

}  // namespace

std::string describe_defect(const Defect& d, const DefectSource& s) {
  const auto face = [&s](long long f) { return std::to_string(map_index(f, s.face_origin)); };
  const auto vertex = [&s](long long v) { return std::to_string(map_index(v, s.vertex_origin)); };
  const std::string edge = vertex(d.edge_from) + "-" + vertex(d.edge_to);
  switch (d.kind) {
    case DefectKind::kEmptyMesh:
      return "the mesh has no faces (" + std::to_string(d.bound) + (d.bound == 1 ? " vertex)" : " vertices)");
    case DefectKind::kNonFiniteCoordinate:
      return "coordinate '" + format_double(d.value) + "' is not a finite number";
    case DefectKind::kCoordinateTooLarge:
      return "coordinate '" + format_double(d.value) + "' exceeds the supported magnitude " + format_double(kMaxCoordinate);
    case DefectKind::kIndexOutOfRange:
      if (static_cast<int>(d.value) == kIndexOverflow) return "vertex index does not fit in 32 bits";
      return "vertex index " + format_double(d.value) + " (counting from 0) is out of range: the mesh has " +
             std::to_string(d.bound) + " vertices";
    case DefectKind::kDegenerateFace:
      return "face repeats a vertex";
    case DefectKind::kDuplicateFace:
      return std::string("face repeats the vertices of face ") + face(d.other_face) +
             (d.value > 0 ? " (same orientation)" : " (opposite orientation)");
    case DefectKind::kBoundaryEdge:
      return "the mesh is not closed: edge " + edge + " belongs to one face only";
    case DefectKind::kNonManifoldEdge:
      return "edge " + edge + " is shared by " + format_double(d.value) + " faces";
    case DefectKind::kNonManifoldVertex:
      return "vertex " + vertex(d.vertex) + " joins " + format_double(d.value) + " separate fans of faces";
    case DefectKind::kInconsistentOrientation:
      return "faces " + face(d.face) + " and " + face(d.other_face) + " traverse edge " + edge +
             " in the same direction";
    case DefectKind::kZeroVolume:
      return "closed shell encloses zero volume (signed volume " + format_double(d.value) + ")";
    case DefectKind::kInsideOut:
      if (d.bound > 0 && d.bound % 2 == 1)
        return "cavity shell has positive signed volume " + format_double(d.value) + " (a shell inside another must face inwards)";
      if (d.bound > 0)
        return "shell nested in a cavity has negative signed volume " + format_double(d.value);
      if (d.bound < 0)
        return "shell has negative signed volume " + format_double(d.value) +
               " and too many shells to check which are cavities (at most " + std::to_string(kMaxShellsForNesting) +
               " shells and " + std::to_string(kMaxNestingTriangleTests) + " ray-triangle tests)";
      return "shell is inside-out: signed volume " + format_double(d.value) + " (normals point inwards)";
    case DefectKind::kOverlappingShells:
      return "cavity shell encloses more than the shells around it: the signed volumes sum to " + format_double(d.value) +
             (d.bound == 1 ? " once every face is flipped" : "") + " (shells cross each other)";
    case DefectKind::kSeveralComponents:
      return "the mesh has " + format_double(d.value) + " separate components";
  }
  return "unknown defect";
}

std::string defect_report_line(const std::string& file, const Defect& d, const DefectSource& s) {
  if (d.kind == DefectKind::kEmptyMesh) return file + ": empty mesh: " + describe_defect(d, s);
  const auto [number, line] = first_location(d, s);
  std::string out = file + ": " + defect_name(d.kind) + ": " + std::to_string(d.count) + " (first: " +
                    (is_vertex_defect(d.kind) ? "vertex " : "face ") + std::to_string(number);
  if (line > 0) out += ", line " + std::to_string(line);
  return out + "): " + describe_defect(d, s);
}

std::string defect_error_message(const std::string& file, const Defect& d, const DefectSource& s) {
  if (d.kind == DefectKind::kEmptyMesh) return file + ": empty mesh: " + describe_defect(d, s);
  const auto [number, line] = first_location(d, s);
  std::string out = file;
  if (line > 0) out += ":" + std::to_string(line);
  out += ": " + describe_defect(d, s);
  if (line == 0) out += std::string(is_vertex_defect(d.kind) ? ", vertex " : ", face ") + std::to_string(number);
  if (d.count > 1 && d.kind != DefectKind::kSeveralComponents)
    out += " (" + std::to_string(d.count) + " " + defect_unit(d.kind) + " in all)";
  return out;
}

}  // namespace offsetopt
