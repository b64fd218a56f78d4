// Cotangent Laplacian of a triangle mesh (Pinkall & Polthier 1993; Meyer et al. 2003), in the
// positive semi-definite convention DESIGN.md fixes:
//   L_ij = -(cot a_ij + cot b_ij) / 2 for each edge ij (a, b the angles opposite it),
//   L_ii = -sum_j L_ij  (so L * 1 = 0 and the diagonal is >= 0 on a well-shaped mesh).
// L is #V by #V, symmetric, sparse. Cotangents are dot/|cross| (no libm call).
#pragma once
#include <Eigen/Sparse>

#include "mesh/mesh.h"

namespace offsetopt {

struct CotanOptions {
  // Guard for (near-)degenerate triangles: |cross| is floored at this fraction of the product of
  // the two edge lengths, so a cotangent is at most ~1/floor in magnitude (1e-8 -> |cot| <= 1e8)
  // instead of inf/NaN. Collapsing triangles in skeleton contraction rely on this.
  double sine_floor = 1e-8;
};

// Returns L (#V by #V, PSD convention above).
Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F, const CotanOptions& options = {});

}  // namespace offsetopt
