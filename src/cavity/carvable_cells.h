// The cells of a regular grid that a void may occupy (docs/design.md "Reachability: what any void can
// do"), read two ways so that both of reachability's answers are honest:
// - inner: cells the contoured cavity can write whole: all 8 nodes inside the outer surface with
//   distance >= wall + margin (the contour's own node test, cavity/contour_cavity.h, with its
//   spacing h = wall / cells_per_wall and margin from cavity_node_level). A void made of inner
//   cells is one the tool can write, so it backs the claim "reachable";
// - outer: every cell that may contain a point at least `wall` inside: the signed distance of its
//   centre (positive inside) plus half its diagonal r = √3·h/2 is >= wall (with --outer, the wall
//   may be measured from material added outside, so >= wall − outer_max). Every point of any
//   void keeping the wall lies in an outer cell, so it backs the claim "unreachable". inner ⊆ outer.
// With `band`, also the cells the outer offset may fill (material ADDED, docs/design.md; the base is kept
// as cli --outer keeps it: nothing within 2·outer_max + ground_tol of the ground):
// - band_inner: cells whose centre is outside within outer_max, the bottom above the kept base (the
//   outer offset is a displaced surface, not a union of cells: no cell reading is exactly what it
//   writes, and a whole-cell one keeps less than half of a band two walls thick);
// - band_outer: any cell that may hold such a point (centre distance <= outer_max + r outside or
//   <= r inside), its top above the ground contacts;
// - skin_outer: cells inside that --outer may shave (the outer surface also moves inward, up to
//   outer_max): centre depth <= outer_max + r, top above the ground contacts. Only the generous
//   reading has them (a strict one would have to keep the wall between shaved and carved cells).
// Cell (i, j, k) is the cube [node (i, j, k), node (i+1, j+1, k+1)] of `grid`, named by the lowest
// node's index (NodeGrid::index); lists are ascending. Input units throughout.
//
// Signs from grid winding numbers (geometry/grid_winding.h) at the nodes and at the cell centres;
// one nearest-face query per block of 4³ points, whose distance and closest point bound every
// point's (most of the interior needs nothing more); a point those bounds leave open takes its
// distance from the faces gathered once for its 2³ sub-block, and face_within decides the rare
// distance within rounding of a threshold.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "geometry/bvh.h"
#include "geometry/node_grid.h"
#include "mass/volume_integrals.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct CarvableCellsOptions {
  double wall = 0.0;                 // input units, > 0
  double cells_per_wall = 1.5;       // h = wall / cells_per_wall (the contour's), in [1.25, 8]
  double margin_cells = 0.0;         // c, in [0, 2] (cavity/contour_cavity.h)
  // The node test's margin, input units; negative: the contour's at this grid's h
  // (cavity_node_level). A grid finer than the contour's passes the contour's margin here.
  double node_margin = -1.0;
  std::int64_t max_nodes = std::int64_t{1} << 25;  // h grows (×1.05 steps) when the box needs more
  bool band = false;                 // also the outer band (--outer)
  double outer_max = 0.0;            // band: how far outside material may be added, > 0
  double ground_z = 0.0;             // band: the ground plane (lowest vertex)
  double ground_tol = 0.0;           // band: >= 0
  int threads = 2;                   // 1..64; the result is the same for any count
  // The inner reading needs a pass over the nodes (their winding and distance); the mid and outer
  // readings only the centres. Without it `inner` stays empty (and `outer` is the same: a cell
  // whose 8 nodes are a wall + margin deep has its centre deeper than wall − r).
  bool strict = true;

  std::string check() const;
};

struct CarvableCells {
  bool ok = false;
  std::string message;               // why not, when !ok
  NodeGrid grid;
  double margin = 0.0;               // the contour's interpolation margin at this spacing
  std::vector<std::int64_t> inner, outer;            // void cells (see above)
  // Cells whose centre is at least `wall` inside: the contour's void, which reaches the wall
  // exactly, read at the cell scale (half cells lost and gained along the wall about cancel).
  // Neither a subset nor a superset of what can be written; inner ⊆ mid ⊆ outer.
  std::vector<std::int64_t> mid;
  std::vector<std::int64_t> band_inner, band_outer;  // --outer: cells that add material
  std::vector<std::int64_t> skin_outer;              // --outer: cells that may lose material
  std::int64_t distance_queries = 0;                 // points whose distance was computed (blocks not counted)

  Eigen::Vector3d centre(std::int64_t cell) const;
  Eigen::Vector3d centre(std::int64_t i, std::int64_t j, std::int64_t k) const;  // of the cell whose lowest node is (i, j, k)
  double cell_volume() const { return grid.spacing * grid.spacing * grid.spacing; }
};

CarvableCells carvable_cells(const Mesh& outer, const TriangleBvh& outer_bvh, const CarvableCellsOptions& options);

// The 10 raw integrals (mass/volume_integrals.h order) of the axis-aligned cube of side h centred
// at `centre`, coordinates measured from `origin`: exact (∫x² = h³ (p_x² + h²/12), ∫xy = h³ p_x p_y).
Vector10d cube_integrals(const Eigen::Vector3d& centre, double h, const Eigen::Vector3d& origin);

}  // namespace offsetopt
