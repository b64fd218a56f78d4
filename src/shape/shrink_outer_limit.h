// Lowers the outer offset limits around faces of a thickened surface that cross each other (the
// optimiser's safety net behind shape/outer_offset_limit.h, whose bounds are local estimates):
// every corner of a face in `pairs` and every vertex sharing a face with one (the fold spans the
// faces around its vertices) gets factor * its limit, then the slope bound is restored
// (shape/lipschitz_envelope.h). `pairs` index rows of mesh.F; limits #V, >= 0, in mesh units;
// factor in [0, 1]; slope >= 0. Returns the new limits (never above the old ones).
#pragma once
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

Eigen::VectorXd shrink_outer_limit(const Mesh& mesh, const Eigen::VectorXd& limit,
                                   const std::vector<std::pair<int, int>>& pairs, double factor, double slope);

}  // namespace offsetopt
