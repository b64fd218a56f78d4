// src/cavity (this is the folder's main header): what is written and its checks: the contoured
// cavity, the printable solid and the verification of the written surfaces. It may include
// src/shape and every folder below it; src/optimize and src/cli sit above it.
//
// The written cavity, valid by construction (docs/design.md "The written cavity"): the optimised inner
// offset surface may fold, cross itself or cross the outer surface, and keeps no wall in parts
// left solid, so the cavity that is written is the contour of
//   φ(p) = min( d_out(p) − wall − c·h ,  s_in(p) ),
// d_out the distance to the outer surface (positive inside it), s_in the distance to the inner
// offset surface with the sign of its winding number (inside where w >= 1), or the signed distance
// to a quadric's zero set (the optimal void of docs/design.md "Reachability"), h the grid spacing,
// by marching tetrahedra (geometry/marching_tetrahedra.h) over the cells where φ changes sign.
// Prusa's SLA hollowing contours a level set of the interior in the same spirit.
//
// Why every output is printable (tests/cavity/test_contour_cavity.cpp, docs/cavity.md):
// - the shells are closed, embedded, oriented 2-manifolds (marching tetrahedra), and stay so
//   wherever on its grid edge each vertex is put;
// - a node counts as cavity only when d_out >= T + 0.02·h, T = the wall (+ c·h when asked) and
//   a rounding hair; each vertex goes to the first point of its edge where the inner boundary is
//   crossed or the exact distance to the outer surface falls to T (regula falsi on the edge, to
//   within 10⁻⁴ of the wall above T), so the wall-bound part of the cavity sits at the requested
//   wall, not a margin above it;
// - every point of a contoured triangle lies within h of one of its vertices (its diameter is at
//   most √2 h, a face diagonal: the five-tetrahedra cut has no body diagonal), and T >= 1.01 h,
//   so no shell reaches the outer surface;
// - faces that dip below the wall between their vertices (at concave parts of the outer surface)
//   are found by exact triangle distances and their vertices lifted along their edges; where that
//   is not enough, their void nodes become material and the contour is made again;
// - parts left solid have no node with d_out >= T + 0.02·h: no cavity reaches them;
// - shells enclosing less than min_shell_fraction of the void, and shells that bound an island of
//   material inside the void (negative volume), are dropped: the specks are filled, the islands
//   join the void.
// Cost: node signs from one line per grid row (geometry/grid_winding.h), distances only in blocks
// of 4³ nodes that the Lipschitz bound cannot decide (|φ(centre)| > half the block's diagonal),
// exact values only at the nodes of cells that change sign.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/node_grid.h"
#include "mass/volume_integrals.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct ContourCavityOptions {
  double wall = 0.0;               // the wall to keep, mesh units, > 0
  double cells_per_wall = 1.5;     // h = wall / cells_per_wall, in [1.25, 8]
  double margin_cells = 0.0;       // c: where the outer surface binds, the cavity keeps wall + c·h; in [0, 2]
  std::int64_t max_nodes = std::int64_t{1} << 25;  // h grows when the box needs more nodes
  double min_shell_fraction = 1e-3;  // shells below this fraction of the void are filled
  int threads = 2;                 // 1..64; the result is the same for any count

  // Empty when the options are valid, else what is wrong.
  std::string check() const;
};

struct ContourCavity {
  bool ok = false;
  std::string message;             // why not, when !ok
  Mesh cavity;                     // closed shells, normals out of the void (into the material)
  NodeGrid grid;
  std::int64_t active_cells = 0;   // cells where φ changes sign (the contoured ones)
  std::int64_t distance_nodes = 0; // nodes whose distance to the outer surface was computed one by one
  int shells = 0;                  // kept
  int shells_dropped = 0;
  double dropped_volume = 0.0;     // signed sum of the dropped shells' volumes
  int vertices_moved_for_wall = 0; // put on the wall: moved along their edge to the exact distance
  // Faces between vertices on the wall can dip below it where the outer surface is concave (a
  // chord of a cylinder or sphere around an inner edge or corner). Each face is measured (exactly,
  // unless its vertices' distances already bound it), and the vertices of those below are lifted.
  double largest_face_deficit = 0.0;  // how far below the wall a face came before any lift
  int faces_lifted = 0;               // faces below the wall before any lift
  int demotions = 0;                  // contours again because lifts along the edges did not suffice
  int faces_below_wall = 0;           // after every lift and demotion (0 unless the caps ran out;
                                      // optimize then calls the solid invalid)
};

// The box the contour grids: the void's (the inner surface's box; for a quadric, the outer
// surface's), clipped to the outer surface's; empty when they do not overlap.
Aabb cavity_box(const Aabb& void_box, const Aabb& outer_box);

// The contour's grid over `box`: spacing wall / cells_per_wall, grown by 5% steps while the box
// would need more than max_nodes nodes; false when even 60 steps do not bring it under.
bool cavity_grid(const Aabb& box, double wall, double cells_per_wall, std::int64_t max_nodes, NodeGrid& grid);

// The distance to the outer surface from which a grid node of spacing h counts as cavity (the
// node test above): a cell whose eight nodes all keep it is written whole. `outer_box` bounds the
// outer surface (the rounding hair grows with the coordinates' size).
double cavity_node_level(double wall, double h, double margin_cells, const Aabb& outer_box);

// A mesh's winding numbers at the nodes of a grid (geometry/grid_winding.h).
struct GridWinding {
  NodeGrid grid;
  std::vector<std::int8_t> winding;
};

// `outer` is the closed outer surface and `outer_bvh` its tree; `inner` the inner offset surface
// (closed as a mesh, possibly folded or crossing `outer`). Both in the same units as the wall.
// `inner_winding` (optional): `inner`'s winding numbers, computed before (cavity/fold_integrals.h);
// read when their grid is the contour's own, else computed again: the same result either way.
ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Mesh& inner,
                             const ContourCavityOptions& options, const GridWinding* inner_winding = nullptr);

// The same with a quadric for the inner term: the void is { q < 0 } with
// q(x) = Σ quadric_i m_i(x) over the monomials m = [1, x, y, z, x², y², z², xy, yz, zx] (the order
// of mass/volume_integrals.h), x in the outer surface's units, and s_in = −q/|∇q| (its signed
// distance to first order; exact for a plane). The coefficients may have any common scale.
//
// `reuse` (optional): what does not depend on the quadric (the outer surface's winding numbers
// at the nodes, which nodes keep the node level, their distances, and the wall placement of every
// vertex whose edge and inputs are the same), kept from one call to the next on the same outer
// surface and options (the rounds of optimize/quadric_void.h); the result is the one computed
// without it. Started empty (a null pointer); started afresh when the grid or levels differ.
struct ContourReuse;
ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Vector10d& quadric,
                             const ContourCavityOptions& options, std::shared_ptr<ContourReuse>* reuse = nullptr);

}  // namespace offsetopt
