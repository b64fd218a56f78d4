#include "cavity/fold_integrals.h"

#include "geometry/aabb.h"
#include "geometry/grid_winding.h"

namespace offsetopt {

FoldIntegrals fold_integrals(const Mesh& outer, const Mesh& inner, const ContourCavityOptions& options,
                             const Eigen::Vector3d& origin, double scale) {
  FoldIntegrals out;
  if (inner.F.rows() == 0 || outer.F.rows() == 0) {  // no void: nothing folds
    out.ok = true;
    return out;
  }
  // The box contour_cavity grids: the inner surface's, within the outer surface's.
  Aabb box = bounding_box(inner.V);
  const Aabb outer_box = bounding_box(outer.V);
  box.lo = box.lo.cwiseMax(outer_box.lo);
  box.hi = box.hi.cwiseMin(outer_box.hi);
  if (box.empty()) {
    out.ok = true;
    return out;
  }
  if (!cavity_grid(box, options.wall, options.cells_per_wall, options.max_nodes, out.inner.grid)) return out;
  out.ok = true;
  const NodeGrid& grid = out.inner.grid;
  out.inner.winding = grid_winding(inner, grid, options.threads);
  const double side = grid.spacing * scale, cube = side * side * side, square_term = side * side / 12.0;
  for (std::int64_t node = 0; node < grid.node_count(); ++node) {
    const int w = out.inner.winding[static_cast<std::size_t>(node)];
    const double weight = (w >= 1 ? 1.0 : 0.0) - static_cast<double>(w);
    if (weight == 0.0) continue;
    ++out.folded_nodes;
    const Eigen::Vector3d c = (grid.position(node) - origin) * scale;
    Vector10d cell;
    cell << 1.0, c.x(), c.y(), c.z(), c.x() * c.x() + square_term, c.y() * c.y() + square_term, c.z() * c.z() + square_term,
        c.x() * c.y(), c.y() * c.z(), c.z() * c.x();
    out.integrals += (weight * cube) * cell;
  }
  out.volume = out.integrals(kIntVolume) / (scale * scale * scale);
  return out;
}

}  // namespace offsetopt
