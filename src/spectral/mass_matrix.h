// Lumped (barycentric) mass matrix: M_ii = (sum of the areas of the triangles at vertex i) / 3.
// Returned as the diagonal, a #V vector of non-negative entries whose sum is the surface area.
#pragma once
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

Eigen::VectorXd lumped_mass(const Vertices& V, const Faces& F);

}  // namespace offsetopt
