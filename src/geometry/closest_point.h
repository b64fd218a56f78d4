// Closest point on a triangle mesh to a query point, through a TriangleBvh (branch and bound on
// box distances), and the point-triangle primitive it uses (Ericson 2005, "Real-Time Collision
// Detection", 5.1.5: Voronoi regions of the vertices, edges and face).
#pragma once
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "geometry/bvh.h"

namespace offsetopt {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

struct ClosestPoint {
  bool found = false;  // false when no face lies within max_distance
  int face = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double distance = std::numeric_limits<double>::infinity();
};

// The nearest point of any face except `ignored_faces` with distance < max_distance; ties go to
// the lowest face index.
ClosestPoint closest_point(const TriangleBvh& bvh, const Eigen::Vector3d& p,
                           double max_distance = std::numeric_limits<double>::infinity(),
                           const std::vector<int>& ignored_faces = {});

// Whether some face lies nearer than `radius` to p: closest_point(bvh, p, radius).found, and with
// `by_root` whether closest_point(bvh, p).distance < radius, to the last bit either way; but it
// stops at the first such face (a decision, not a search: the grid passes that only ask "at least
// a wall deep?" take it).
bool face_within(const TriangleBvh& bvh, const Eigen::Vector3d& p, double radius, bool by_root = false);

}  // namespace offsetopt
