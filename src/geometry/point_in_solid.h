// Inside/outside classification of points against a closed, outward-oriented triangle mesh.
//
// point_in_solid casts rays in fixed generic directions and sums signed crossings (+1 where the
// ray leaves the solid, -1 where it enters): for a closed mesh that sum is the winding number of
// the point. A ray that passes within tolerance of an edge, a vertex or the point itself, or lies
// in a face's plane, is discarded and the next direction tried; the answer is the majority of the
// first three clean rays (which also tolerates small holes). When fewer than three of the seven
// directions are clean the exact generalised winding number decides.
//
// winding_number is that exact value, the sum of the signed solid angles of the faces seen from
// the point over 4 pi (Van Oosterom & Strackee 1983), O(#F), via det_atan2: 1 inside a closed
// outward mesh, 0 outside, 1/2 on a smooth part of the surface.
#pragma once
#include <Eigen/Core>

#include "geometry/bvh.h"

namespace offsetopt {

bool point_in_solid(const TriangleBvh& bvh, const Eigen::Vector3d& point);

double winding_number(const Vertices& V, const Faces& F, const Eigen::Vector3d& point);

// Signed crossing count of the ray point + t * direction, t > 0; `ambiguous` set when a hit is
// too close to an edge, a vertex or the origin to be trusted, or the ray lies in a face's plane.
int ray_winding(const TriangleBvh& bvh, const Eigen::Vector3d& point, const Eigen::Vector3d& direction, bool& ambiguous);

}  // namespace offsetopt
