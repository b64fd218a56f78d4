#include "geometry/grid_winding.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "util/parallel.h"

namespace offsetopt {

namespace {

// Side of the point (py, pz) of the projected edge lower -> upper (vertex indices lower < upper),
// as an edge function value; `sign` is its sign after the symbolic move by (ε, ε²).
struct EdgeSide {
  double value = 0.0;
  int sign = 0;
};

EdgeSide canonical_side(const Vertices& V, int lower, int upper, double py, double pz) {
  const double uy = V(lower, 1), uz = V(lower, 2), vy = V(upper, 1), vz = V(upper, 2);
  EdgeSide s;
  s.value = (vy - uy) * (pz - uz) - (vz - uz) * (py - uy);
  if (s.value > 0.0) s.sign = 1;
  else if (s.value < 0.0) s.sign = -1;
  else if (vz != uz) s.sign = vz < uz ? 1 : -1;  // ε (-(vz - uz))
  else if (vy != uy) s.sign = vy > uy ? 1 : -1;  // ε² (vy - uy)
  return s;
}

EdgeSide side(const Vertices& V, int a, int b, double py, double pz) {
  if (a < b) return canonical_side(V, a, b, py, pz);
  EdgeSide s = canonical_side(V, b, a, py, pz);
  s.value = -s.value;
  s.sign = -s.sign;
  return s;
}

}  // namespace

std::vector<std::int8_t> grid_winding(const Mesh& mesh, const NodeGrid& grid, int threads) {
  const std::int64_t rows = grid.ny * grid.nz;
  std::vector<std::vector<std::pair<double, int>>> crossings(static_cast<std::size_t>(rows));
  std::vector<std::int8_t> winding(static_cast<std::size_t>(grid.node_count()), 0);
  const double h = grid.spacing;
  const int parts = 2;
  WorkerPool pool(std::max(1, std::min(threads, parts)));
  // Part p owns the rows with k in its range: it alone appends to them.
  pool.run_parts(parts, [&](int part) {
    const std::int64_t k_begin = split_point(grid.nz, parts, part), k_end = split_point(grid.nz, parts, part + 1);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
      const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
      const double ylo = std::min({mesh.V(a, 1), mesh.V(b, 1), mesh.V(c, 1)});
      const double yhi = std::max({mesh.V(a, 1), mesh.V(b, 1), mesh.V(c, 1)});
      const double zlo = std::min({mesh.V(a, 2), mesh.V(b, 2), mesh.V(c, 2)});
      const double zhi = std::max({mesh.V(a, 2), mesh.V(b, 2), mesh.V(c, 2)});
      // Rows one further on each side: the symbolic move may put a row on the bound inside.
      const std::int64_t j0 = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor((ylo - grid.origin.y()) / h)) - 1);
      const std::int64_t j1 = std::min<std::int64_t>(grid.ny - 1, static_cast<std::int64_t>(std::floor((yhi - grid.origin.y()) / h)) + 1);
      const std::int64_t k0 = std::max<std::int64_t>(k_begin, static_cast<std::int64_t>(std::floor((zlo - grid.origin.z()) / h)) - 1);
      const std::int64_t k1 = std::min<std::int64_t>(k_end - 1, static_cast<std::int64_t>(std::floor((zhi - grid.origin.z()) / h)) + 1);
      for (std::int64_t k = k0; k <= k1; ++k) {
        const double pz = grid.z(k);
        if (pz < zlo || pz > zhi) continue;
        for (std::int64_t j = j0; j <= j1; ++j) {
          const double py = grid.y(j);
          if (py < ylo || py > yhi) continue;
          const EdgeSide ab = side(mesh.V, a, b, py, pz), bc = side(mesh.V, b, c, py, pz), ca = side(mesh.V, c, a, py, pz);
          if (ab.sign == 0 || ab.sign != bc.sign || bc.sign != ca.sign) continue;
          const double sum = ab.value + bc.value + ca.value;
          double x;
          if (sum != 0.0) x = (bc.value * mesh.V(a, 0) + ca.value * mesh.V(b, 0) + ab.value * mesh.V(c, 0)) / sum;
          else x = (mesh.V(a, 0) + mesh.V(b, 0) + mesh.V(c, 0)) / 3.0;
          // Entering through a face with n_x < 0 (edge functions negative) adds one.
          crossings[static_cast<std::size_t>(j + grid.ny * k)].emplace_back(x, -ab.sign);
        }
      }
    }
    for (std::int64_t k = k_begin; k < k_end; ++k)
      for (std::int64_t j = 0; j < grid.ny; ++j) {
        auto& row = crossings[static_cast<std::size_t>(j + grid.ny * k)];
        std::sort(row.begin(), row.end());
        int w = 0;
        std::size_t next = 0;
        for (std::int64_t i = 0; i < grid.nx; ++i) {
          const double x = grid.x(i);
          while (next < row.size() && row[next].first <= x) w += row[next++].second;
          winding[static_cast<std::size_t>(grid.index(i, j, k))] = static_cast<std::int8_t>(std::clamp(w, -127, 127));
        }
        std::vector<std::pair<double, int>>().swap(row);
      }
  });
  return winding;
}

}  // namespace offsetopt
