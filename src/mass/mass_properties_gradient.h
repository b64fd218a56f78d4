// Analytic derivative of the 10 mass properties P (mass/mass_properties.h, paper eq. 4) with
// respect to every vertex coordinate, by the chain rule
//   ∂P/∂X = (∂P/∂values)(∂values/∂X)
// through the raw volume integrals (mass/volume_integrals_gradient.h). O(#F) per call.
#pragma once
#include <Eigen/Core>

#include "mass/volume_integrals.h"

namespace offsetopt {

// gradient += (∂P/∂V)ᵀ w for the mesh whose integrals are `integrals` (computed from this mesh
// with integrals.origin, or, for one surface of a shell, the shell's integrals: pass the shell's
// integrals and `sign` = +1 for the outer surface, −1 for the inner one, both measured from the
// same origin). `gradient` is #V by 3, already sized like mesh.V.
void accumulate_mass_properties_gradient(const Mesh& mesh, const VolumeIntegrals& integrals, const Vector10d& weights,
                                         Vertices& gradient, double sign = 1.0);

// Dense 10 by 3#V Jacobian ∂P/∂V of mass_properties(volume_integrals(mesh, origin)); column
// 3i + c is vertex i's coordinate c. For tests and small meshes.
Eigen::MatrixXd mass_properties_jacobian(const Mesh& mesh, const Eigen::Vector3d& origin);

}  // namespace offsetopt
