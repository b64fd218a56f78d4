// Lumped (barycentric) mass matrix of the Laplacian's generalised eigenproblem, an area per vertex
// (not physical mass: that is src/mass): M_ii = (sum of the areas of the triangles at vertex i) / 3.
// Returned as the diagonal, a #V vector of non-negative entries whose sum is the surface area.
// With the same intrinsic mollification as the cotan Laplacian (geometry/cotan_laplacian.h,
// Sharp & Crane 2020 section 4.5): when a triangle misses the margin, every area comes from the
// lengthened edges (Heron), so a zero-area triangle still gives its corners a positive mass; when
// no triangle does, the areas are |cross| / 2 exactly as without it.
#pragma once
#include <Eigen/Core>

#include "geometry/intrinsic_mollification.h"
#include "mesh/mesh.h"

namespace offsetopt {

Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F, double mollify_margin = kDefaultMollifyMargin);

}  // namespace offsetopt
