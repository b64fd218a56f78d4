// src/geometry (this header opens the folder's mesh operators): computations on a mesh's
// shape. It owns spatial queries (BVH, ray casting, point in solid, closest point, triangle
// intersections, self-intersections and pinches), hulls, plane sections, poses (axis
// permutations and rigid motions; the stable pose needs mass and is mass/stable_pose.h), the flat-base
// cut, polygon triangulation, grid winding numbers, marching tetrahedra, mesh shells, and the
// discrete differential operators of a surface: the cotan Laplacian (this file), the lumped area
// matrix (lumped_mass.h; an area per vertex, not physical mass, which is src/mass) and their
// intrinsic mollification. It may include util, optim, mesh and itself; the eigensolver
// (src/spectral) and the contraction (src/skeleton) sit above it and take its operators.
//
// Cotangent Laplacian of a triangle mesh (Pinkall & Polthier 1993; Meyer et al. 2003), in the
// positive semi-definite convention of docs/design.md and Musialski et al. 2015 eq. 2 (sign
// flipped to make it PSD):
//   L_ij = -(cot a_ij + cot b_ij) / 2 for each edge ij (a, b the angles opposite it),
//   L_ii = -sum_j L_ij  (so L * 1 = 0 and the diagonal is >= 0 on a well-shaped mesh).
// L is #V by #V, symmetric (bit for bit), sparse, both triangles stored. It does not change when
// the mesh is scaled (cotangents are dimensionless).
//
// Cotangents are dot/|cross| (no libm call). Near-degenerate triangles: each triangle uses one
// denominator for its three corners, max(|cross|, sine_floor * (longest edge)²), so a cotangent
// is at most about 1/sine_floor in magnitude instead of inf/NaN. Because the three corners share
// the denominator, the triangle's 3 by 3 contribution stays positive semi-definite (the sum of its
// weights is positive and cot·cot summed over corner pairs is (2·area / denominator)² >= 0), so L
// is PSD on any mesh, degenerate triangles included. A triangle with all edges of zero length
// contributes nothing.
//
// Zero-area and needle triangles (CAD exports, collapsing triangles in skeleton contraction):
// when any triangle misses the strict triangle inequality by the margin of
// geometry/intrinsic_mollification.h, every edge is lengthened by the same epsilon and the whole
// matrix is built from edge lengths (cot of the angle at corner i = (l_j² + l_k² - l_i²) / (4·area),
// area by Heron), which keeps every weight bounded by about (mean edge) / delta and L PSD (each
// triangle's block is that of a valid Euclidean triangle). When epsilon is 0 the formulas above
// run unchanged, so such meshes give bit-identical matrices.
#pragma once
#include <Eigen/Sparse>
#include <string>

#include "geometry/intrinsic_mollification.h"
#include "mesh/mesh.h"

namespace offsetopt {

struct CotanOptions {
  // Floor on |sin| of a triangle's angles, relative to its longest edge: 1e-8 keeps |cot| below
  // about 1e8. Collapsing triangles in skeleton contraction rely on this.
  double sine_floor = 1e-8;
  // Intrinsic mollification margin, relative to the mean edge length (0 turns it off).
  double mollify_margin = kDefaultMollifyMargin;
  // Empty when valid, else what is wrong.
  std::string check() const;
};

// Returns L (#V by #V, PSD convention above). F indexes rows of V.
Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F, const CotanOptions& options = {});

}  // namespace offsetopt
