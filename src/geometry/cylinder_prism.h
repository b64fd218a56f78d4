// A cylinder approximated by a right prism over a regular polygon: the cutter of a drain hole or a
// channel (geometry/subtract_convex.h). The polygon is inscribed in the circle of `radius` (its
// corners on it), so the prism lies inside the cylinder: volume (sides/2)·r²·sin(2π/sides)·length,
// 0.6% below πr²·length at 32 sides. `turn` (radians) rotates the polygon about the axis: a caller
// whose cut met a degenerate configuration turns it a little and cuts again.
// Caps are fans around their centre point (exactly planar triangles), normals out.
#pragma once
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

// `bottom` != `top`, radius > 0, sides >= 3.
Mesh cylinder_prism(const Eigen::Vector3d& bottom, const Eigen::Vector3d& top, double radius, int sides, double turn = 0.0);

}  // namespace offsetopt
