#include "cavity/fold_integrals.h"

#include <algorithm>

#include "cavity/carvable_cells.h"
#include "geometry/aabb.h"
#include "geometry/closest_point.h"
#include "geometry/grid_winding.h"
#include "util/parallel.h"

namespace offsetopt {

namespace {

// The integrals, in the frame, of the cube of side h about node position p (carvable_cells.h's,
// read in the frame's coordinates).
Vector10d frame_cube_integrals(const Eigen::Vector3d& p, double h, const Eigen::Vector3d& origin, double scale) {
  return cube_integrals((p - origin) * scale, h * scale, Eigen::Vector3d::Zero());
}

// Parts of the node range, fixed whatever the thread count.
constexpr int kParts = 16;

}  // namespace

FoldIntegrals fold_integrals(const Mesh& outer, const Mesh& inner, const ContourCavityOptions& options,
                             const Eigen::Vector3d& origin, double scale) {
  FoldIntegrals out;
  if (inner.F.rows() == 0 || outer.F.rows() == 0) {  // no void: nothing folds
    out.ok = true;
    return out;
  }
  const Aabb box = cavity_box(bounding_box(inner.V), bounding_box(outer.V));
  if (box.empty()) {
    out.ok = true;
    return out;
  }
  if (!cavity_grid(box, options.wall, options.cells_per_wall, options.max_nodes, out.inner.grid)) return out;
  out.ok = true;
  const NodeGrid& grid = out.inner.grid;
  out.inner.winding = grid_winding(inner, grid, options.threads);
  for (std::int64_t node = 0; node < grid.node_count(); ++node) {
    const int w = out.inner.winding[static_cast<std::size_t>(node)];
    const double weight = (w >= 1 ? 1.0 : 0.0) - static_cast<double>(w);
    if (weight == 0.0) continue;
    ++out.folded_nodes;
    out.integrals += weight * frame_cube_integrals(grid.position(node), grid.spacing, origin, scale);
  }
  out.volume = out.integrals(kIntVolume) / (scale * scale * scale);
  return out;
}

WallCutIntegrals wall_cut_integrals(const Mesh& outer, const TriangleBvh& outer_bvh, const FoldIntegrals& folds,
                                    const ContourCavityOptions& options, const Eigen::Vector3d& origin, double scale) {
  WallCutIntegrals out;
  const NodeGrid& grid = folds.inner.grid;
  if (!folds.ok || folds.inner.winding.size() != static_cast<std::size_t>(grid.node_count()) || grid.node_count() == 0)
    return out;
  const std::vector<std::int8_t> outer_winding = grid_winding(outer, grid, options.threads);
  const double level = cavity_node_level(options.wall, grid.spacing, options.margin_cells, bounding_box(outer.V));
  Vector10d part_sums[kParts];
  WorkerPool pool(std::max(1, std::min(options.threads, kParts)));
  pool.run_parts(kParts, [&](int part) {
    Vector10d sum = Vector10d::Zero();
    const long count = static_cast<long>(grid.node_count());
    for (long node = split_point(count, kParts, part); node < split_point(count, kParts, part + 1); ++node) {
      const std::size_t i = static_cast<std::size_t>(node);
      if (folds.inner.winding[i] < 1) continue;
      const Eigen::Vector3d p = grid.position(node);
      // The contour's node test (cavity/contour_cavity.h): inside the outer surface, and no face
      // within the level.
      if (outer_winding[i] >= 1 && !closest_point(outer_bvh, p, level).found) continue;
      sum -= frame_cube_integrals(p, grid.spacing, origin, scale);
    }
    part_sums[part] = sum;
  });
  for (const Vector10d& sum : part_sums) out.integrals += sum;
  out.volume = out.integrals(kIntVolume) / (scale * scale * scale);
  return out;
}

}  // namespace offsetopt
