#include "meshio/validate_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include <Eigen/Geometry>

#include "geometry/aabb.h"
#include "geometry/mesh_shells.h"
#include "geometry/ray_triangle.h"
#include "meshio/read_raw_mesh.h"
#include "util/disjoint_sets.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

constexpr int kMaxShellsForNesting = 10000;
// Ray-triangle tests the nesting check may spend (a few seconds at most). Its cost is the sum,
// over the shells, of the faces of every other shell whose box contains the shell's test point:
// up to #shells x #F, so a file of 10,000 nested shells inside one large one took minutes.
constexpr long long kMaxNestingTriangleTests = 100000000;

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

Eigen::Vector3d row(const Mesh& mesh, int v) { return mesh.V.row(v).transpose(); }

double diagonal(const Aabb& box) { return (box.hi - box.lo).norm(); }

// Counts one more instance of `d`; `note` records its details when `first` says it is the one to
// report (the first found, or one on a smaller face).
template <typename Note>
void count_instance(Defect& d, bool first, Note note) {
  if (first) note(d);
  ++d.count;
}

// ---- The checks, in the order validate_mesh runs them. Each returns its findings: a Defect
// ---- with count 0 when there is none, else the count and the first offending face, vertex or
// ---- edge (describe_defect turns that into the sentence, DefectSource into file and line).

struct CoordinateFindings {
  Defect non_finite{DefectKind::non_finite_coordinate}, too_large{DefectKind::coordinate_too_large};
  std::vector<char> bad_vertex;  // per vertex: one of the two defects
};

// Vertices with a NaN or infinite coordinate, else with one beyond kMaxCoordinate in magnitude.
CoordinateFindings check_coordinates(const Mesh& mesh) {
  const long long nv = mesh.V.rows();
  CoordinateFindings out;
  out.bad_vertex.assign(static_cast<std::size_t>(nv), 0);
  auto note_vertex = [&out](Defect& d, long long v, double x) {
    count_instance(d, d.count == 0, [&](Defect& first) {
      first.vertex = v;
      first.value = x;
    });
    out.bad_vertex[static_cast<std::size_t>(v)] = 1;
  };
  for (long long v = 0; v < nv; ++v) {
    int worst = -1;  // first non-finite coordinate, else first too large one
    for (int k = 0; k < 3 && worst < 0; ++k)
      if (!std::isfinite(mesh.V(v, k))) worst = k;
    if (worst >= 0) {
      note_vertex(out.non_finite, v, mesh.V(v, worst));
      continue;
    }
    for (int k = 0; k < 3 && worst < 0; ++k)
      if (std::fabs(mesh.V(v, k)) > kMaxCoordinate) worst = k;
    if (worst >= 0) note_vertex(out.too_large, v, mesh.V(v, worst));
  }
  return out;
}

// Faces with a vertex index outside [0, #V): the first such index of the first such face.
Defect check_vertex_indices(const Mesh& mesh) {
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
  Defect out_of_range{DefectKind::index_out_of_range};
  out_of_range.bound = nv;
  for (long long f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.F(f, k);
      if (i >= 0 && i < nv) continue;
      count_instance(out_of_range, out_of_range.count == 0, [&](Defect& first) {
        first.face = f;
        first.value = i;
      });
      break;
    }
  }
  return out_of_range;
}

// Vertices no face uses (a note, not a defect): how many, and the first.
void note_unreferenced_vertices(const Mesh& mesh, MeshValidation& out) {
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
  std::vector<char> referenced(static_cast<std::size_t>(nv), 0);
  for (long long f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) referenced[static_cast<std::size_t>(mesh.F(f, k))] = 1;
  for (long long v = 0; v < nv; ++v)
    if (!referenced[static_cast<std::size_t>(v)]) {
      if (out.unreferenced_vertices == 0) out.first_unreferenced = v;
      ++out.unreferenced_vertices;
    }
}

// Faces that repeat a vertex (a defect; load_mesh drops them: added to out.droppable_faces),
// and faces of exactly zero area with three distinct corners (a note in `out`).
Defect check_degenerate_faces(const Mesh& mesh, const std::vector<char>& bad_vertex, MeshValidation& out) {
  const long long nf = mesh.F.rows();
  Defect degenerate{DefectKind::degenerate_face};
  for (long long f = 0; f < nf; ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    bool repeated = a == b || b == c || a == c;
    bool zero_area = false;
    if (!repeated && !bad_vertex[static_cast<std::size_t>(a)] && !bad_vertex[static_cast<std::size_t>(b)] &&
        !bad_vertex[static_cast<std::size_t>(c)]) {
      const Eigen::Vector3d pa = row(mesh, a);
      const Eigen::Vector3d n = (row(mesh, b) - pa).cross(row(mesh, c) - pa);
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
    count_instance(degenerate, degenerate.count == 0, [&](Defect& first) {
      first.face = f;
      first.value = 0;
    });
  }
  return degenerate;
}

// Later faces over the same three vertices as an earlier one, either orientation: found by
// sorting the sorted vertex triples. Same-orientation copies are counted in `out` and added to
// out.droppable_faces (which leaves here sorted and unique).
Defect check_duplicate_faces(const Mesh& mesh, MeshValidation& out) {
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
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
  Defect duplicate{DefectKind::duplicate_face};
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
    count_instance(duplicate, duplicate.count == 0 || copy < duplicate.face, [&](Defect& d) {
      d.face = copy;
      d.other_face = original;
      d.value = same ? 1 : -1;
    });
  }
  std::sort(out.droppable_faces.begin(), out.droppable_faces.end());
  out.droppable_faces.erase(std::unique(out.droppable_faces.begin(), out.droppable_faces.end()), out.droppable_faces.end());
  return duplicate;
}

struct HalfEdge {
  int lo, hi;    // undirected edge, lo < hi
  int face;
  bool forward;  // traversed lo -> hi
};

// Corner 3 f + k of face f at `vertex` (its first corner there when the face repeats it).
std::uint32_t corner_of(const Mesh& mesh, int face, int vertex) {
  int k = 0;
  while (k < 2 && mesh.F(face, k) != vertex) ++k;
  return static_cast<std::uint32_t>(3 * face + k);
}

struct EdgeFindings {
  Defect boundary{DefectKind::boundary_edge}, non_manifold{DefectKind::non_manifold_edge},
      inconsistent{DefectKind::inconsistent_orientation};
  long long edges = 0;  // undirected edges
  // The corners (3 f + k) joined across every shared edge: the fans check_manifold_vertices counts.
  DisjointSets fans{0};
};

// Per undirected edge: one face (boundary), three or more (non-manifold), or two traversing it
// the same way (inconsistent orientation); the first of each by smallest face.
EdgeFindings check_edges(const Mesh& mesh) {
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
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
  EdgeFindings out;
  out.fans = DisjointSets(static_cast<std::size_t>(3 * nf));
  auto note_edge = [](Defect& d, const HalfEdge& e, long long face, long long other, double value) {
    count_instance(d, d.count == 0 || face < d.face, [&](Defect& first) {
      first.face = face;
      first.other_face = other;
      first.edge_from = e.lo;
      first.edge_to = e.hi;
      first.value = value;
    });
  };
  for (std::size_t i = 0; i < half_edges.size();) {
    std::size_t j = i + 1;
    while (j < half_edges.size() && half_edges[j].lo == half_edges[i].lo && half_edges[j].hi == half_edges[i].hi) ++j;
    ++out.edges;
    const HalfEdge& e = half_edges[i];
    const std::size_t n = j - i;
    if (n == 1) {
      note_edge(out.boundary, e, e.face, -1, 1);
    } else if (n > 2) {
      note_edge(out.non_manifold, e, e.face, half_edges[i + 1].face, static_cast<double>(n));
    } else if (half_edges[i].forward == half_edges[i + 1].forward) {
      note_edge(out.inconsistent, e, e.face, half_edges[i + 1].face, 2);
    }
    for (std::size_t k = i + 1; k < j; ++k) {
      out.fans.unite(corner_of(mesh, half_edges[i].face, e.lo), corner_of(mesh, half_edges[k].face, e.lo));
      out.fans.unite(corner_of(mesh, half_edges[i].face, e.hi), corner_of(mesh, half_edges[k].face, e.hi));
    }
    i = j;
  }
  return out;
}

// Vertices whose corners, joined across shared edges (`fans`), form two or more fans. Corners
// grouped by vertex with a counting sort.
Defect check_manifold_vertices(const Mesh& mesh, DisjointSets& fans) {
  const long long nv = mesh.V.rows(), nf = mesh.F.rows();
  std::vector<std::uint32_t> start(static_cast<std::size_t>(nv) + 1, 0);
  for (long long c = 0; c < 3 * nf; ++c) ++start[static_cast<std::size_t>(mesh.F(c / 3, c % 3)) + 1];
  for (long long v = 0; v < nv; ++v) start[static_cast<std::size_t>(v) + 1] += start[static_cast<std::size_t>(v)];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1), roots(static_cast<std::size_t>(3 * nf));
  for (long long c = 0; c < 3 * nf; ++c) {
    const std::size_t v = static_cast<std::size_t>(mesh.F(c / 3, c % 3));
    // A face that repeats a vertex counts once at it: through its first corner there.
    roots[fill[v]++] = fans.find(corner_of(mesh, static_cast<int>(c / 3), static_cast<int>(v)));
  }
  Defect pinched{DefectKind::non_manifold_vertex};
  for (long long v = 0; v < nv; ++v) {
    auto begin = roots.begin() + start[static_cast<std::size_t>(v)], end = roots.begin() + start[static_cast<std::size_t>(v) + 1];
    if (end - begin < 2) continue;
    std::sort(begin, end);
    const long long count = std::unique(begin, end) - begin;
    if (count < 2) continue;
    count_instance(pinched, pinched.count == 0, [&](Defect& first) {
      first.vertex = v;
      first.value = static_cast<double>(count);
    });
  }
  return pinched;
}

// Connected pieces (faces sharing a vertex, geometry/mesh_shells.h), numbered in order of their
// first face, with their signed volumes measured from the centre of the faces' box (compensated
// sums; used only when the mesh is closed and its coordinates finite): sets out.face_component
// and out.components; `faces_of` gets the faces of each, ascending.
MeshShells find_components(const Mesh& mesh, MeshValidation& out, std::vector<std::vector<int>>& faces_of) {
  Aabb all;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) all.extend(row(mesh, mesh.F(f, k)));
  MeshShellsOptions options;
  options.compensated = true;
  MeshShells shells = mesh_shells(mesh, all.center(), options);
  out.face_component = shells.shell_of_face;
  out.components = shells.count;
  faces_of.assign(static_cast<std::size_t>(shells.count), {});
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    faces_of[static_cast<std::size_t>(shells.shell_of_face[static_cast<std::size_t>(f)])].push_back(static_cast<int>(f));
  return shells;
}

enum class RayHit { miss, hit, ambiguous };

// geometry/ray_triangle.h with a relative 1e-9 tolerance: ambiguous when the ray passes that
// close to an edge or the origin lies (nearly) on the triangle, where the parity count cannot be
// trusted; hits behind the origin and rays parallel to the plane miss.
RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Eigen::Vector3d& a,
            const Eigen::Vector3d& b, const Eigen::Vector3d& c, double length_scale) {
  const double eps = 1e-9;
  const RayTriangleHit hit = ray_triangle(origin, direction, a, b, c, eps);
  if (!hit.hit || hit.t < -eps * length_scale) return RayHit::miss;
  if (hit.ambiguous || hit.t < eps * length_scale) return RayHit::ambiguous;
  return RayHit::hit;
}

// Number of shells among `faces_of` (other than `self`) that contain `point`, by ray parity.
int nesting_depth(const Mesh& mesh, const Eigen::Vector3d& point, int self, const std::vector<std::vector<int>>& faces_of,
                  const std::vector<Aabb>& boxes) {
  static const Eigen::Vector3d kDirections[3] = {{0.3183098861837907, 0.5772156649015329, 0.7517464825841436},
                                                 {-0.6, 0.48, 0.64},
                                                 {0.48, -0.64, 0.6}};
  int depth = 0;
  for (std::size_t shell = 0; shell < faces_of.size(); ++shell) {
    if (static_cast<int>(shell) == self || !boxes[shell].contains(point)) continue;
    const double length_scale = diagonal(boxes[shell]);
    int crossings = 0;
    for (const Eigen::Vector3d& direction : kDirections) {
      crossings = 0;
      bool ambiguous = false;
      for (const int f : faces_of[shell]) {
        const RayHit hit = cast(point, direction, row(mesh, mesh.F(f, 0)), row(mesh, mesh.F(f, 1)),
                                row(mesh, mesh.F(f, 2)), length_scale);
        if (hit == RayHit::ambiguous) {
          ambiguous = true;
          break;
        }
        if (hit == RayHit::hit) ++crossings;
      }
      if (!ambiguous) break;
    }
    if (crossings % 2 == 1) ++depth;
  }
  return depth;
}

// A point of each shell: the centroid of its largest face, safely inside that face.
std::vector<Eigen::Vector3d> shell_points(const Mesh& mesh, const std::vector<std::vector<int>>& faces_of) {
  std::vector<Eigen::Vector3d> points(faces_of.size());
  for (std::size_t s = 0; s < faces_of.size(); ++s) {
    int best = faces_of[s][0];
    double best_area = -1;
    for (const int f : faces_of[s]) {
      const Eigen::Vector3d a = row(mesh, mesh.F(f, 0));
      const Eigen::Vector3d n = (row(mesh, mesh.F(f, 1)) - a).cross(row(mesh, mesh.F(f, 2)) - a);
      const double area = n.dot(n);
      if (area > best_area) {
        best_area = area;
        best = f;
      }
    }
    Eigen::Vector3d& point = points[s];
    point.setZero();
    for (int k = 0; k < 3; ++k) point += row(mesh, mesh.F(best, k)) / 3.0;
  }
  return points;
}

// Signed volumes per shell and in all (out.component_volume, out.volume, from `found`), each
// shell's nesting depth (out.component_depth, when at most kMaxShellsForNesting shells and
// kMaxNestingTriangleTests ray-triangle tests; else all 0), then the zero-volume and inside-out
// shells, and shells that cross each other (the oriented total is not positive). Appends the
// defects found to out.defects in DefectKind order.
void check_shells(const Mesh& mesh, const std::vector<std::vector<int>>& faces_of, const MeshShells& found,
                  MeshValidation& out) {
  const long long nf = mesh.F.rows();
  const int shells = out.components;
  std::vector<Aabb> boxes(static_cast<std::size_t>(shells));
  Aabb all;
  for (long long f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = row(mesh, mesh.F(f, k));
      boxes[static_cast<std::size_t>(out.face_component[static_cast<std::size_t>(f)])].extend(p);
      all.extend(p);
    }
  out.component_volume = found.volume;
  out.volume = found.total_volume;
  out.volume_computed = true;
  out.component_depth.assign(static_cast<std::size_t>(shells), 0);
  bool nesting_checked = shells == 1;
  if (shells > 1 && shells <= kMaxShellsForNesting) {
    const std::vector<Eigen::Vector3d> points = shell_points(mesh, faces_of);
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
  Defect zero{DefectKind::zero_volume}, inverted{DefectKind::inside_out};
  // A volume is zero when it is round-off of the coordinates in a box of this diagonal.
  const auto is_zero_volume = [](double volume, double box_diagonal) {
    return std::fabs(volume) <= 1e-12 * box_diagonal * box_diagonal * box_diagonal;
  };
  for (int s = 0; s < shells; ++s) {
    const double volume = out.component_volume[static_cast<std::size_t>(s)];
    const bool is_zero = is_zero_volume(volume, diagonal(boxes[static_cast<std::size_t>(s)]));
    const bool wrong_sign = (volume > 0) != (out.component_depth[static_cast<std::size_t>(s)] % 2 == 0);
    if (!is_zero && !wrong_sign) continue;
    Defect& d = is_zero ? zero : inverted;
    count_instance(d, d.count == 0, [&](Defect& first) {
      first.face = faces_of[static_cast<std::size_t>(s)][0];
      first.value = volume;
      first.bound = nesting_checked ? out.component_depth[static_cast<std::size_t>(s)] : -1;  // -1: unknown
    });
  }
  if (zero.count > 0) out.defects.push_back(zero);
  if (inverted.count > 0) out.defects.push_back(inverted);
  // Every shell faces the right way (or every one the wrong way, which loading fixes by flipping
  // all faces), yet the total is not positive: a cavity encloses more than the part around it,
  // which only shells that cross each other can do. Nesting is decided at one point per shell,
  // so such shells pass the checks above and would reach the optimiser as a solid of negative
  // mass.
  const bool all_inverted = inverted.count == shells;
  const double oriented_total = all_inverted ? -out.volume : out.volume;
  if (zero.count == 0 && (inverted.count == 0 || all_inverted) && shells > 1 &&
      (oriented_total <= 0.0 || is_zero_volume(oriented_total, diagonal(all)))) {
    Defect overlap{DefectKind::overlapping_shells};
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
    if (overlap.count > 0) out.defects.push_back(overlap);
  }
}

// V - E + F over the referenced vertices, and the genus when the mesh is a closed 2-manifold.
void note_topology(long long edges, bool closed_manifold, MeshValidation& out) {
  out.euler_characteristic = (out.vertices - out.unreferenced_vertices) - edges + out.faces;
  if (!closed_manifold) return;
  const long long twice_genus = 2LL * out.components - out.euler_characteristic;
  if (twice_genus >= 0 && twice_genus % 2 == 0) out.genus = twice_genus / 2;
}

}  // namespace

const Defect* MeshValidation::find(DefectKind kind) const {
  for (const Defect& d : defects)
    if (d.kind == kind) return &d;
  return nullptr;
}

MeshValidation validate_mesh(const Mesh& mesh) {
  MeshValidation out;
  out.vertices = mesh.V.rows();
  out.faces = mesh.F.rows();
  auto add = [&out](const Defect& d) {
    if (d.count > 0) out.defects.push_back(d);
  };
  if (out.faces == 0) {
    Defect empty{DefectKind::empty_mesh};
    empty.count = 1;
    empty.bound = out.vertices;
    out.defects.push_back(empty);
    out.unreferenced_vertices = out.vertices;
    out.first_unreferenced = out.vertices > 0 ? 0 : -1;
    return out;
  }
  const CoordinateFindings coordinates = check_coordinates(mesh);
  add(coordinates.non_finite);
  add(coordinates.too_large);
  const Defect out_of_range = check_vertex_indices(mesh);
  if (out_of_range.count > 0) {
    add(out_of_range);
    return out;  // nothing below can index V safely
  }
  note_unreferenced_vertices(mesh, out);
  add(check_degenerate_faces(mesh, coordinates.bad_vertex, out));
  add(check_duplicate_faces(mesh, out));
  EdgeFindings edges = check_edges(mesh);
  out.edges = edges.edges;
  add(edges.boundary);
  add(edges.non_manifold);
  add(check_manifold_vertices(mesh, edges.fans));
  edges.fans = DisjointSets(0);
  add(edges.inconsistent);
  std::vector<std::vector<int>> faces_of;
  const MeshShells shells = find_components(mesh, out, faces_of);
  const bool closed_manifold = edges.boundary.count == 0 && edges.non_manifold.count == 0;
  note_topology(edges.edges, closed_manifold && !out.find(DefectKind::non_manifold_vertex), out);
  const bool coordinates_ok = coordinates.non_finite.count == 0 && coordinates.too_large.count == 0;
  if (closed_manifold && edges.inconsistent.count == 0 && coordinates_ok) check_shells(mesh, faces_of, shells, out);
  if (out.components > 1) {
    Defect several{DefectKind::several_components};
    several.count = out.components;
    several.face = faces_of[1][0];
    several.value = out.components;
    add(several);
  }
  return out;
}

const char* defect_name(DefectKind kind) {
  switch (kind) {
    case DefectKind::empty_mesh: return "empty mesh";
    case DefectKind::non_finite_coordinate: return "non-finite coordinates";
    case DefectKind::coordinate_too_large: return "coordinates too large";
    case DefectKind::index_out_of_range: return "vertex index out of range";
    case DefectKind::degenerate_face: return "degenerate faces";
    case DefectKind::duplicate_face: return "duplicate faces";
    case DefectKind::boundary_edge: return "boundary edges";
    case DefectKind::non_manifold_edge: return "non-manifold edges";
    case DefectKind::non_manifold_vertex: return "non-manifold vertices";
    case DefectKind::inconsistent_orientation: return "inconsistent orientation";
    case DefectKind::zero_volume: return "zero volume";
    case DefectKind::inside_out: return "inside-out (negative volume)";
    case DefectKind::overlapping_shells: return "overlapping shells";
    case DefectKind::several_components: return "several components";
  }
  return "unknown defect";
}

const char* defect_unit(DefectKind kind) {
  switch (kind) {
    case DefectKind::non_finite_coordinate:
    case DefectKind::coordinate_too_large:
    case DefectKind::non_manifold_vertex: return "vertices";
    case DefectKind::boundary_edge:
    case DefectKind::non_manifold_edge:
    case DefectKind::inconsistent_orientation: return "edges";
    case DefectKind::zero_volume:
    case DefectKind::inside_out:
    case DefectKind::overlapping_shells: return "shells";
    case DefectKind::several_components: return "components";
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
  return kind == DefectKind::non_finite_coordinate || kind == DefectKind::coordinate_too_large ||
         kind == DefectKind::non_manifold_vertex;
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
    case DefectKind::empty_mesh:
      return "the mesh has no faces (" + std::to_string(d.bound) + (d.bound == 1 ? " vertex)" : " vertices)");
    case DefectKind::non_finite_coordinate:
      return "coordinate '" + format_double(d.value) + "' is not a finite number";
    case DefectKind::coordinate_too_large:
      return "coordinate '" + format_double(d.value) + "' exceeds the supported magnitude " + format_double(kMaxCoordinate);
    case DefectKind::index_out_of_range:
      if (static_cast<int>(d.value) == kIndexOverflow) return "vertex index does not fit in 32 bits";
      return "vertex index " + format_double(d.value) + " (counting from 0) is out of range: the mesh has " +
             std::to_string(d.bound) + " vertices";
    case DefectKind::degenerate_face:
      return "face repeats a vertex";
    case DefectKind::duplicate_face:
      return std::string("face repeats the vertices of face ") + face(d.other_face) +
             (d.value > 0 ? " (same orientation)" : " (opposite orientation)");
    case DefectKind::boundary_edge:
      return "the mesh is not closed: edge " + edge + " belongs to one face only";
    case DefectKind::non_manifold_edge:
      return "edge " + edge + " is shared by " + format_double(d.value) + " faces";
    case DefectKind::non_manifold_vertex:
      return "vertex " + vertex(d.vertex) + " joins " + format_double(d.value) + " separate fans of faces";
    case DefectKind::inconsistent_orientation:
      return "faces " + face(d.face) + " and " + face(d.other_face) + " traverse edge " + edge +
             " in the same direction";
    case DefectKind::zero_volume:
      return "closed shell encloses zero volume (signed volume " + format_double(d.value) + ")";
    case DefectKind::inside_out:
      if (d.bound > 0 && d.bound % 2 == 1)
        return "cavity shell has positive signed volume " + format_double(d.value) + " (a shell inside another must face inwards)";
      if (d.bound > 0)
        return "shell nested in a cavity has negative signed volume " + format_double(d.value);
      if (d.bound < 0)
        return "shell has negative signed volume " + format_double(d.value) +
               " and too many shells to check which are cavities (at most " + std::to_string(kMaxShellsForNesting) +
               " shells and " + std::to_string(kMaxNestingTriangleTests) + " ray-triangle tests)";
      return "shell is inside-out: signed volume " + format_double(d.value) + " (normals point inwards)";
    case DefectKind::overlapping_shells:
      return "cavity shell encloses more than the shells around it: the signed volumes sum to " + format_double(d.value) +
             (d.bound == 1 ? " once every face is flipped" : "") + " (shells cross each other)";
    case DefectKind::several_components:
      return "the mesh has " + format_double(d.value) + " separate components";
  }
  return "unknown defect";
}

std::string defect_report_line(const std::string& file, const Defect& d, const DefectSource& s) {
  if (d.kind == DefectKind::empty_mesh) return file + ": empty mesh: " + describe_defect(d, s);
  const auto [number, line] = first_location(d, s);
  std::string out = file + ": " + defect_name(d.kind) + ": " + std::to_string(d.count) + " (first: " +
                    (is_vertex_defect(d.kind) ? "vertex " : "face ") + std::to_string(number);
  if (line > 0) out += ", line " + std::to_string(line);
  return out + "): " + describe_defect(d, s);
}

std::string defect_error_message(const std::string& file, const Defect& d, const DefectSource& s) {
  if (d.kind == DefectKind::empty_mesh) return file + ": empty mesh: " + describe_defect(d, s);
  const auto [number, line] = first_location(d, s);
  std::string out = file;
  if (line > 0) out += ":" + std::to_string(line);
  out += ": " + describe_defect(d, s);
  if (line == 0) out += std::string(is_vertex_defect(d.kind) ? ", vertex " : ", face ") + std::to_string(number);
  if (d.count > 1 && d.kind != DefectKind::several_components)
    out += " (" + std::to_string(d.count) + " " + defect_unit(d.kind) + " in all)";
  return out;
}

}  // namespace offsetopt
