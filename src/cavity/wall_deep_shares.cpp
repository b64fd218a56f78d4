#include "cavity/wall_deep_shares.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "cavity/distance_band.h"
#include "geometry/closest_point.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

constexpr int kBalls = 9;  // about the closest points of a cell's 8 corners and its centre

struct CellBalls {
  std::array<Eigen::Vector3d, kBalls> centre;
  int count = 0;
};

// Squared distances from p to the nearest and the farthest point of the cube [lo, lo + side].
std::pair<double, double> cube_distances(const Eigen::Vector3d& p, const Eigen::Vector3d& lo, double side) {
  double nearest = 0.0, farthest = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double below = lo[a] - p[a], above = p[a] - (lo[a] + side);
    const double out = std::max(0.0, std::max(below, above));
    const double far = std::max(std::fabs(p[a] - lo[a]), std::fabs(p[a] - lo[a] - side));
    nearest += out * out;
    farthest += far * far;
  }
  return {nearest, farthest};
}

// The volume of the cube [lo, lo + side] that no ball (of `balls`, those in `live`) holds, counted
// on sub-cubes down to `levels` halvings: a bound from above. A sub-cube is held when its farthest
// corner is within `inside` (squared), and reached into when its nearest point is within `touches`.
double kept_volume(const CellBalls& balls, unsigned live, const Eigen::Vector3d& lo, double side, int levels, double inside,
                   double touches) {
  unsigned partial = 0;
  for (int b = 0; b < balls.count; ++b) {
    if (!(live >> b & 1u)) continue;
    const auto [nearest, farthest] = cube_distances(balls.centre[static_cast<std::size_t>(b)], lo, side);
    if (farthest <= inside) return 0.0;
    if (nearest < touches) partial |= 1u << b;
  }
  if (partial == 0 || levels == 0) return side * side * side;
  const double half = 0.5 * side;
  double sum = 0.0;
  for (int octant = 0; octant < 8; ++octant) {
    const Eigen::Vector3d sub = lo + half * Eigen::Vector3d(octant & 1, (octant >> 1) & 1, (octant >> 2) & 1);
    sum += kept_volume(balls, partial, sub, half, levels - 1, inside, touches);
  }
  return sum;
}

// The balls of one cell: about the closest surface points of its 8 corners (`at_node`, per sorted
// `nodes`), and about the centre's nearest point on those corners' nearest faces (any surface
// point bounds the distance, so the centre's ball needs no search of its own).
CellBalls cell_balls(const CarvableCells& cells, const TriangleBvh& surface, const std::vector<std::int64_t>& nodes,
                     const std::vector<ClosestPoint>& at_node, std::int64_t cell) {
  const NodeGrid& grid = cells.grid;
  CellBalls balls;
  std::array<const ClosestPoint*, 8> corner;
  for (int k = 0; k < 8; ++k) {
    const std::int64_t node = cell + (k & 1) + ((k >> 1) & 1) * grid.nx + ((k >> 2) & 1) * grid.nx * grid.ny;
    const ClosestPoint& c = at_node[static_cast<std::size_t>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin())];
    corner[static_cast<std::size_t>(k)] = &c;
    if (c.found) balls.centre[static_cast<std::size_t>(balls.count++)] = c.point;
  }
  const Eigen::Vector3d middle = cells.centre(cell);
  double nearest = std::numeric_limits<double>::infinity();
  Eigen::Vector3d on_surface = Eigen::Vector3d::Zero();
  for (const ClosestPoint* c : corner) {
    if (!c->found) continue;
    const Eigen::Vector3d point =
        closest_point_on_triangle(middle, surface.corner(c->face, 0), surface.corner(c->face, 1), surface.corner(c->face, 2));
    const double d = (point - middle).squaredNorm();
    if (d < nearest) {
      nearest = d;
      on_surface = point;
    }
  }
  if (nearest < std::numeric_limits<double>::infinity()) balls.centre[static_cast<std::size_t>(balls.count++)] = on_surface;
  return balls;
}

}  // namespace

WallDeepShares wall_deep_shares(const CarvableCells& cells, const TriangleBvh& surface, double wall, int levels, int threads) {
  WallDeepShares out;
  const NodeGrid& grid = cells.grid;
  const double h = grid.spacing;
  const double r = 0.5 * std::sqrt(3.0) * h;
  out.share.assign(cells.outer.size(), 1.0);

  // Mid cells (centre a wall deep) at least wall + r deep hold no point nearer than the wall.
  const NodeGrid centres = cell_centres(grid);
  auto centre_index = [&](std::int64_t cell) {
    const std::int64_t i = cell % grid.nx, j = (cell / grid.nx) % grid.ny, k = cell / (grid.nx * grid.ny);
    return static_cast<std::size_t>(centres.index(i, j, k));
  };
  std::vector<std::int8_t> mask(static_cast<std::size_t>(centres.node_count()), 0);
  for (std::int64_t c : cells.mid) mask[centre_index(c)] = 1;
  std::int64_t band_queries = 0;
  const std::vector<std::int8_t> deep = distance_band(centres, mask, surface, {wall + r}, threads, band_queries);

  std::vector<std::size_t> shell;  // positions in cells.outer
  for (std::size_t s = 0; s < cells.outer.size(); ++s)
    if (deep[centre_index(cells.outer[s])] == 0) shell.push_back(s);
  out.shell_cells = static_cast<std::int64_t>(shell.size());

  // The closest surface points of the shell cells' corners, each node once.
  std::vector<std::int64_t> nodes;
  nodes.reserve(8 * shell.size());
  for (std::size_t s : shell)
    for (int corner = 0; corner < 8; ++corner)
      nodes.push_back(cells.outer[s] + (corner & 1) + ((corner >> 1) & 1) * grid.nx + ((corner >> 2) & 1) * grid.nx * grid.ny);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  std::vector<ClosestPoint> at_node(nodes.size());
  for_ranges(static_cast<long>(nodes.size()), threads, 512, [&](long begin, long end) {
    for (long n = begin; n < end; ++n)
      at_node[static_cast<std::size_t>(n)] = closest_point(surface, grid.position(nodes[static_cast<std::size_t>(n)]));
  });

  // The balls' radius less far more than the rounding of the closest points and of the squared
  // distances (relative to the coordinates' size, which may be far from the origin).
  const Eigen::Vector3d far_corner = grid.position(grid.nx - 1, grid.ny - 1, grid.nz - 1);
  const double size = std::max(grid.origin.cwiseAbs().maxCoeff(), far_corner.cwiseAbs().maxCoeff());
  const double radius = wall - 1e-12 * (size + wall);
  const double inside = radius * radius, touches = wall * wall * (1.0 + 1e-9);
  for_ranges(static_cast<long>(shell.size()), threads, 64, [&](long begin, long end) {
    for (long q = begin; q < end; ++q) {
      const std::size_t s = shell[static_cast<std::size_t>(q)];
      const std::int64_t cell = cells.outer[s];
      const CellBalls balls = cell_balls(cells, surface, nodes, at_node, cell);
      const double kept = kept_volume(balls, (1u << balls.count) - 1u, grid.position(cell), h, levels, inside, touches);
      out.share[s] = std::min(1.0, kept / (h * h * h));
    }
  });
  out.queries = band_queries + static_cast<std::int64_t>(nodes.size());
  return out;
}

}  // namespace offsetopt
