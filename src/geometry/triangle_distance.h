// The smallest distance between two closed triangles in 3-D, and the segment-segment distance it
// is made of. Two disjoint triangles are nearest at a vertex of one against the other, or at a
// pair of edges, so the distance is the least of six point-triangle distances
// (geometry/closest_point.h) and nine segment-segment distances; 0 when they meet
// (geometry/triangle_triangle.h). Used to check that a contoured cavity's faces, not only its
// vertices, keep the wall (cavity/contour_cavity.h). Plain double arithmetic.
#pragma once
#include <Eigen/Core>

namespace offsetopt {

// Distance between the closed segments a0-a1 and b0-b1 (either may be a point).
double segment_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& b0,
                        const Eigen::Vector3d& b1);

// Distance between the closed triangles (a0, a1, a2) and (b0, b1, b2), >= 0.
double triangle_distance(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                         const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2);

}  // namespace offsetopt
