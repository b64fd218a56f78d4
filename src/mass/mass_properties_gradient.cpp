#include "mass/mass_properties_gradient.h"

#include "mass/mass_properties.h"
#include "mass/volume_integrals_gradient.h"

namespace offsetopt {

void accumulate_mass_properties_gradient(const Mesh& mesh, const VolumeIntegrals& integrals, const Vector10d& weights,
                                         Vertices& gradient, double sign) {
  const Vector10d integral_weights = sign * (mass_properties_jacobian_wrt_integrals(integrals).transpose() * weights);
  accumulate_volume_integrals_gradient(mesh, integrals.origin, integral_weights, gradient);
}

Eigen::MatrixXd mass_properties_jacobian(const Mesh& mesh, const Eigen::Vector3d& origin) {
  const VolumeIntegrals integrals = volume_integrals(mesh, origin);
  return mass_properties_jacobian_wrt_integrals(integrals) * volume_integrals_jacobian(mesh, origin);
}

}  // namespace offsetopt
