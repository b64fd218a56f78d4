// src/cavity (this is the folder's main header): what is written and its checks: the contoured
// cavity, the printable solid and the verification of the written surfaces. It may include
// src/shape and every folder below it; src/optimize and src/cli sit above it.
//
// The written cavity, valid by construction (DESIGN.md "The written cavity"): the optimised inner
// offset surface may fold, cross itself or cross the outer surface, and keeps no wall in parts
// left solid, so the cavity that is written is the contour of
//   φ(p) = min( d_out(p) − wall − c·h ,  s_in(p) ),
// d_out the distance to the outer surface (positive inside it), s_in the distance to the inner
// offset surface with the sign of its winding number (inside where w >= 1), or the signed distance
// to a quadric's zero set (the optimal void of DESIGN.md "Reachability"), h the grid spacing,
// by marching tetrahedra (geometry/marching_tetrahedra.h) over the cells where φ changes sign.
// Prusa's SLA hollowing contours a level set of the interior in the same spirit.
//
// Why every output is printable (tests/shape/test_contour_cavity.cpp):
// - the shells are closed, embedded, oriented 2-manifolds (marching tetrahedra);
// - a node counts as cavity only when d_out >= wall + margin (the margin c·h, or more where a
//   coarse grid needs it: max(c·h, 1.01·√3·h − wall)), and every contoured triangle lies in a
//   tetrahedron (diameter √3·h < wall + margin) with such a node, so no shell reaches the outer
//   surface; each vertex is then moved along its grid edge, towards the cavity node, until its
//   exact distance to the outer surface is at least `wall` (bisection on the edge, whose cavity
//   end has wall + margin), so the wall holds at every vertex exactly;
// - parts left solid have no node with d_out >= wall + margin: no cavity reaches them;
// - shells enclosing less than min_shell_fraction of the void, and shells that bound an island of
//   material inside the void (negative volume), are dropped: the specks are filled, the islands
//   join the void.
// Cost: node signs from one line per grid row (geometry/grid_winding.h), distances only in blocks
// of 4³ nodes that the Lipschitz bound cannot decide (|φ(centre)| > half the block's diagonal),
// exact values only at the nodes of cells that change sign.
#pragma once
#include <cstdint>
#include <string>

#include "geometry/bvh.h"
#include "geometry/node_grid.h"
#include "mass/volume_integrals.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct ContourCavityOptions {
  double wall = 0.0;               // the wall to keep, mesh units, > 0
  double cells_per_wall = 1.5;     // h = wall / cells_per_wall, in [1.25, 8]
  double margin_cells = 0.25;      // c, in [0.25, 2]
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
  int vertices_moved_for_wall = 0; // moved along their edge to keep the wall exactly
};

// `outer` is the closed outer surface and `outer_bvh` its tree; `inner` the inner offset surface
// (closed as a mesh, possibly folded or crossing `outer`). Both in the same units as the wall.
ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Mesh& inner,
                             const ContourCavityOptions& options);

// The same with a quadric for the inner term: the void is { q < 0 } with
// q(x) = Σ quadric_i m_i(x) over the monomials m = [1, x, y, z, x², y², z², xy, yz, zx] (the order
// of mass/volume_integrals.h), x in the outer surface's units, and s_in = −q/|∇q| (its signed
// distance to first order; exact for a plane). The coefficients may have any common scale.
ContourCavity contour_cavity(const Mesh& outer, const TriangleBvh& outer_bvh, const Vector10d& quadric,
                             const ContourCavityOptions& options);

}  // namespace offsetopt
