#include "geometry/marching_tetrahedra.h"

#include "util/parallel.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <cstdint>
#include <utility>

#include <Eigen/Geometry>

namespace offsetopt {

namespace {

// Cube corners as bit masks: x = 1, y = 2, z = 4. The alternating five-tetrahedra cut: the four
// corners of one parity class (an even or an odd number of bits) span the central tetrahedron,
// whose six edges are one diagonal of each face; each corner of the other class, with its three
// neighbours along the cube's edges, spans a corner tetrahedron. tets[c] is the cut whose central
// tetrahedron has the corners with (bit count & 1) == c, central first, each tetrahedron stored
// with positive orientation.
struct FiveTetTable {
  std::array<std::array<std::array<int, 4>, 5>, 2> tets;
  FiveTetTable() {
    auto corner = [](int c) { return Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1); };
    auto bit_parity = [](int c) { return (c ^ (c >> 1) ^ (c >> 2)) & 1; };
    for (int central = 0; central < 2; ++central) {
      std::array<std::array<int, 4>, 5>& cut = tets[static_cast<std::size_t>(central)];
      int at = 0, filled = 1;
      for (int c = 0; c < 8; ++c)
        if (bit_parity(c) == central) cut[0][static_cast<std::size_t>(at++)] = c;
      for (int c = 0; c < 8; ++c)
        if (bit_parity(c) != central) cut[static_cast<std::size_t>(filled++)] = {c, c ^ 1, c ^ 2, c ^ 4};
      for (std::array<int, 4>& tet : cut) {
        const Eigen::Vector3d a = corner(tet[0]);
        const double orientation = (corner(tet[1]) - a).cross(corner(tet[2]) - a).dot(corner(tet[3]) - a);
        if (orientation < 0) std::swap(tet[1], tet[2]);
      }
    }
  }
};

// An edge's key: its lower node (by index) times kDirectionCodes plus the code of the step to its
// upper node, (dx + 1) + 3 (dy + 1) + 9 (dz + 1) with each step in {-1, 0, 1}. Face diagonals run
// both ways across the grid (x + y and x - y), so the key names the node pair, not a cube's corner.
constexpr std::int64_t kDirectionCodes = 32;

// An even permutation of (0, 1, 2, 3) that starts with `first` (and, when second >= 0, continues
// with `second`): even permutations keep a positively oriented tetrahedron positive.
std::array<int, 4> even_order(int first, int second) {
  static const int starts[4][4] = {{0, 1, 2, 3}, {1, 0, 3, 2}, {2, 3, 0, 1}, {3, 2, 1, 0}};
  std::array<int, 4> p = {starts[first][0], starts[first][1], starts[first][2], starts[first][3]};
  if (second >= 0)
    for (int r = 0; r < 3 && p[1] != second; ++r) {  // rotating the last three is even
      const int keep = p[1];
      p[1] = p[2];
      p[2] = p[3];
      p[3] = keep;
    }
  return p;
}

// Edge key (>= 0) -> vertex index, open addressing with linear probing: looked up only, so the
// order never matters; one flat array instead of a node per entry.
class EdgeVertexMap {
 public:
  explicit EdgeVertexMap(std::size_t expected) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    slots_.assign(capacity, {-1, -1});
    mask_ = capacity - 1;
  }
  int find(std::int64_t key) const {
    for (std::size_t at = slot_of(key);; at = (at + 1) & mask_) {
      if (slots_[at].first == key) return slots_[at].second;
      if (slots_[at].first < 0) return -1;
    }
  }
  void insert(std::int64_t key, int value) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    place(key, value);
  }

 private:
  std::size_t slot_of(std::int64_t key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> 20) & mask_;
  }
  void place(std::int64_t key, int value) {
    std::size_t at = slot_of(key);
    while (slots_[at].first >= 0) at = (at + 1) & mask_;
    slots_[at] = {key, value};
    ++size_;
  }
  void grow() {
    std::vector<std::pair<std::int64_t, int>> old(2 * slots_.size(), {-1, -1});
    old.swap(slots_);
    mask_ = slots_.size() - 1;
    size_ = 0;
    for (const auto& entry : old)
      if (entry.first >= 0) place(entry.first, entry.second);
  }
  std::vector<std::pair<std::int64_t, int>> slots_;
  std::size_t mask_ = 0, size_ = 0;
};

// One range of cells contoured alone: its vertices (with their edges' keys) and faces.
struct RangeContour {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;
  std::vector<std::int64_t> positive_node, negative_node, key;
  std::vector<double> fraction;
  EdgeVertexMap edge_vertex{16};
};

}  // namespace

TetContour marching_tetrahedra(const NodeGrid& grid, const std::vector<std::int64_t>& cells,
                               const std::function<double(std::int64_t)>& value, double min_fraction) {
  std::vector<double> corner_values(8 * cells.size());
  const std::int64_t corner_offset[8] = {0, 1, grid.nx, 1 + grid.nx, grid.nx * grid.ny, 1 + grid.nx * grid.ny,
                                         grid.nx + grid.nx * grid.ny, 1 + grid.nx + grid.nx * grid.ny};
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int k = 0; k < 8; ++k) corner_values[8 * c + static_cast<std::size_t>(k)] = value(cells[c] + corner_offset[k]);
  return marching_tetrahedra(grid, cells, corner_values, min_fraction, nullptr);
}

namespace {

// The cells [begin, end) contoured alone, their vertices numbered from 0 in visiting order.
void contour_range(const NodeGrid& grid, const std::vector<std::int64_t>& cells, const std::vector<double>& corner_values,
                   double min_fraction, std::size_t begin, std::size_t end, RangeContour& out) {
  static const FiveTetTable five_tets;
  std::vector<Eigen::Vector3d>& vertices = out.vertices;
  std::vector<std::array<int, 3>>& faces = out.faces;
  out.edge_vertex = EdgeVertexMap((end - begin) * 3);
  EdgeVertexMap& edge_vertex = out.edge_vertex;
  vertices.reserve((end - begin) * 3);
  faces.reserve((end - begin) * 6);
  const std::int64_t corner_offset[8] = {0,
                                         1,
                                         grid.nx,
                                         1 + grid.nx,
                                         grid.nx * grid.ny,
                                         1 + grid.nx * grid.ny,
                                         grid.nx + grid.nx * grid.ny,
                                         1 + grid.nx + grid.nx * grid.ny};
  for (std::size_t cell_index = begin; cell_index < end; ++cell_index) {
    const std::int64_t cell = cells[cell_index];
    std::array<double, 8> values;
    bool any_positive = false, any_negative = false;
    for (int c = 0; c < 8; ++c) {
      values[static_cast<std::size_t>(c)] = corner_values[8 * cell_index + static_cast<std::size_t>(c)];
      (values[static_cast<std::size_t>(c)] >= 0.0 ? any_positive : any_negative) = true;
    }
    if (!any_positive || !any_negative) continue;
    // Neighbouring cubes cut their common face along the diagonal that joins its two nodes with an
    // odd i + j + k: the central tetrahedron is on those corners.
    const std::int64_t i = cell % grid.nx, j = (cell / grid.nx) % grid.ny, k = cell / (grid.nx * grid.ny);
    const int central = static_cast<int>((i + j + k + 1) & 1);
    // The vertex on the edge between cube corners a and b (either order). A face diagonal is
    // shared by two tetrahedra of the cell: the cell's own table answers the second before the
    // shared map.
    int in_cell[8][8];
    for (auto& row : in_cell) std::fill(std::begin(row), std::end(row), -1);
    auto edge = [&](int a, int b) {
      int& local = in_cell[std::min(a, b)][std::max(a, b)];
      if (local >= 0) return local;
      const int low = corner_offset[a] < corner_offset[b] ? a : b, high = low == a ? b : a;
      const int step = ((high & 1) - (low & 1) + 1) + 3 * (((high >> 1) & 1) - ((low >> 1) & 1) + 1) +
                       9 * (((high >> 2) & 1) - ((low >> 2) & 1) + 1);
      const std::int64_t key = (cell + corner_offset[low]) * kDirectionCodes + step;
      const int found = edge_vertex.find(key);
      if (found >= 0) return local = found;
      const bool a_positive = values[static_cast<std::size_t>(a)] >= 0.0;
      const int p = a_positive ? a : b, q = a_positive ? b : a;
      const double vp = values[static_cast<std::size_t>(p)], vq = values[static_cast<std::size_t>(q)];
      const double t = std::clamp(vp / (vp - vq), min_fraction, 1.0 - min_fraction);
      const std::int64_t np = cell + corner_offset[p], nq = cell + corner_offset[q];
      const Eigen::Vector3d xp = grid.position(np), xq = grid.position(nq);
      const int index = static_cast<int>(vertices.size());
      vertices.push_back(xp + t * (xq - xp));
      out.positive_node.push_back(np);
      out.negative_node.push_back(nq);
      out.fraction.push_back(t);
      out.key.push_back(key);
      edge_vertex.insert(key, index);
      return local = index;
    };
    for (const auto& tet : five_tets.tets[static_cast<std::size_t>(central)]) {
      int positives = 0, first_positive = -1, second_positive = -1, first_negative = -1;
      for (int v = 0; v < 4; ++v) {
        if (values[static_cast<std::size_t>(tet[static_cast<std::size_t>(v)])] >= 0.0) {
          ++positives;
          (first_positive < 0 ? first_positive : second_positive) = v;
        } else if (first_negative < 0) {
          first_negative = v;
        }
      }
      if (positives == 0 || positives == 4) continue;
      auto corner = [&](int local) { return tet[static_cast<std::size_t>(local)]; };
      if (positives == 1 || positives == 3) {
        const int lone = positives == 1 ? first_positive : first_negative;
        const std::array<int, 4> p = even_order(lone, -1);
        const int e1 = edge(corner(p[0]), corner(p[1])), e2 = edge(corner(p[0]), corner(p[2])),
                  e3 = edge(corner(p[0]), corner(p[3]));
        // One positive corner: the face opposite it, shrunk towards it, faces away from it.
        if (positives == 1) faces.push_back({e1, e2, e3});
        else faces.push_back({e1, e3, e2});
        continue;
      }
      const std::array<int, 4> p = even_order(first_positive, second_positive);
      const int x = corner(p[0]), y = corner(p[1]), z = corner(p[2]), w = corner(p[3]);
      const int q0 = edge(x, w), q1 = edge(y, w), q2 = edge(y, z), q3 = edge(x, z);
      const double d02 = (vertices[static_cast<std::size_t>(q0)] - vertices[static_cast<std::size_t>(q2)]).squaredNorm();
      const double d13 = (vertices[static_cast<std::size_t>(q1)] - vertices[static_cast<std::size_t>(q3)]).squaredNorm();
      if (d02 <= d13) {
        faces.push_back({q0, q1, q2});
        faces.push_back({q0, q2, q3});
      } else {
        faces.push_back({q0, q1, q3});
        faces.push_back({q1, q2, q3});
      }
    }
  }
}

}  // namespace

TetContour marching_tetrahedra(const NodeGrid& grid, const std::vector<std::int64_t>& cells,
                               const std::vector<double>& corner_values, double min_fraction, WorkerPool* pool) {
  // Two ranges of cells side by side. The first range's vertices are the serial run's first ones;
  // the second's, in their visiting order, are either on an edge the first range already has
  // (that vertex, at the same position: same values, same formula) or the serial run's next new
  // ones. The numbering, positions and faces are therefore the serial run's, whatever the split.
  const int parts = pool ? 2 : 1;
  std::vector<RangeContour> range(static_cast<std::size_t>(parts));
  auto run = [&](int part) {
    contour_range(grid, cells, corner_values, min_fraction, static_cast<std::size_t>(split_point(static_cast<long>(cells.size()), parts, part)),
                  static_cast<std::size_t>(split_point(static_cast<long>(cells.size()), parts, part + 1)),
                  range[static_cast<std::size_t>(part)]);
  };
  if (pool) pool->run_parts(parts, run);
  else run(0);
  // Global index of every range's local vertex.
  std::vector<std::vector<int>> global(static_cast<std::size_t>(parts));
  std::vector<std::vector<char>> fresh(static_cast<std::size_t>(parts));  // not on an earlier range's edge
  int vertex_count = 0;
  for (int part = 0; part < parts; ++part) {
    const RangeContour& r = range[static_cast<std::size_t>(part)];
    std::vector<int>& g = global[static_cast<std::size_t>(part)];
    g.resize(r.vertices.size());
    fresh[static_cast<std::size_t>(part)].assign(r.vertices.size(), 0);
    // An earlier range's edge has its low node within one cell's reach of an earlier cell: below
    // this range's first cell + (1, 1, 1). Only vertices on such edges are looked up.
    const std::size_t first_cell = static_cast<std::size_t>(split_point(static_cast<long>(cells.size()), parts, part));
    const std::int64_t reach = first_cell < cells.size() ? cells[first_cell] + 1 + grid.nx + grid.nx * grid.ny : 0;
    for (std::size_t v = 0; v < r.vertices.size(); ++v) {
      int earlier = -1;
      for (int before = 0; before < part && earlier < 0 && r.key[v] / kDirectionCodes < reach; ++before) {
        const int local = range[static_cast<std::size_t>(before)].edge_vertex.find(r.key[v]);
        if (local >= 0) earlier = global[static_cast<std::size_t>(before)][static_cast<std::size_t>(local)];
      }
      g[v] = earlier >= 0 ? earlier : vertex_count++;
      fresh[static_cast<std::size_t>(part)][v] = earlier < 0;
    }
  }
  TetContour out;
  std::size_t face_count = 0;
  for (const RangeContour& r : range) face_count += r.faces.size();
  out.mesh.V.resize(vertex_count, 3);
  out.mesh.F.resize(static_cast<Eigen::Index>(face_count), 3);
  out.positive_node.resize(static_cast<std::size_t>(vertex_count));
  out.negative_node.resize(static_cast<std::size_t>(vertex_count));
  out.fraction.resize(static_cast<std::size_t>(vertex_count));
  Eigen::Index row = 0;
  for (int part = 0; part < parts; ++part) {
    const RangeContour& r = range[static_cast<std::size_t>(part)];
    const std::vector<int>& g = global[static_cast<std::size_t>(part)];
    for (std::size_t v = 0; v < r.vertices.size(); ++v) {
      if (!fresh[static_cast<std::size_t>(part)][v]) continue;
      const std::size_t at = static_cast<std::size_t>(g[v]);
      out.mesh.V.row(g[v]) = r.vertices[v].transpose();
      out.positive_node[at] = r.positive_node[v];
      out.negative_node[at] = r.negative_node[v];
      out.fraction[at] = r.fraction[v];
    }
    for (const auto& face : r.faces) {
      for (int c = 0; c < 3; ++c) out.mesh.F(row, c) = g[static_cast<std::size_t>(face[static_cast<std::size_t>(c)])];
      ++row;
    }
  }
  return out;
}

}  // namespace offsetopt
