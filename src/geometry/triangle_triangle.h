// Triangle-triangle and segment-triangle overlap tests for closed triangles (touching counts as
// intersecting). The 3-D test is Guigue & Devillers 2003, "Fast and Robust Triangle-Triangle
// Overlap Test Using Orientation Predicates": only signs of 3x3 determinants, no intersection
// line is constructed. Coplanar pairs are decided in the 2-D projection that drops the dominant
// normal axis (edge crossings or containment). Plain double arithmetic: exact-arithmetic
// robustness is not claimed; inputs that nearly touch may go either way.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

bool triangles_intersect(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& r1,
                         const Eigen::Vector3d& p2, const Eigen::Vector3d& q2, const Eigen::Vector3d& r2);

// Closed segment a-b against closed triangle p-q-r (coplanar segments handled in 2-D).
bool segment_intersects_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& p,
                                 const Eigen::Vector3d& q, const Eigen::Vector3d& r);

}  // namespace offsetopt
