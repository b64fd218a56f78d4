// The largest per-vertex field below given values whose slope along mesh edges is at most
// `slope`: out_i = min_j (values_j + slope * edge-path length from j to i), by Dijkstra on the
// edge graph (the minimum over paths, so the same bits whatever the order of ties). Bounds built
// this way cannot jump between neighbours, where a jump folds an offset surface. Lengths in mesh units, slope dimensionless
// (>= 0); values may be any finite numbers; #V in, #V out.
#pragma once
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

Eigen::VectorXd lipschitz_envelope(const Mesh& mesh, const Eigen::VectorXd& values, double slope);

}  // namespace offsetopt
