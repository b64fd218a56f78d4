// Convex hull of a 3-D point set by Quickhull (Barber, Dobkin & Huhdanpaa 1996, "The Quickhull
// Algorithm for Convex Hulls") on an exact orientation predicate (floating-point filter, then
// exact expansion arithmetic as in Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic
// and Fast Robust Geometric Predicates"), so the triangulated hull is a closed, consistently
// oriented convex surface for any finite input. Coplanar hull triangles are then merged into
// facets (a box has 6 facets of 2 triangles), with a distance tolerance, because real meshes
// (and exactly rotated boxes) have faces that are flat only up to rounding.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace offsetopt {

// Positive when d lies on the side of the plane through a, b, c that (b − a) × (c − a) points
// to, negative on the other side, zero exactly when the four points are coplanar. The sign is
// exact for all finite inputs below ~1e100 in magnitude; the magnitude approximates six times the
// signed tetrahedron volume.
double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d);

enum class ConvexHullStatus {
  ok,
  too_few_points,  // fewer than 4 distinct points
  flat,            // all points coplanar: no 3-D hull
  too_many_steps,  // the step cap was reached (never seen; a guard against a bug)
};

struct ConvexHullFacet {
  std::vector<int> triangles;  // indices into ConvexHull3d::triangles, ascending
  std::vector<int> vertices;   // distinct point indices of those triangles, ascending
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit, outward (area-weighted mean)
  double area = 0.0;
};

struct ConvexHull3d {
  ConvexHullStatus status = ConvexHullStatus::ok;
  std::string message;
  // Triangles over indices into the input points, counter-clockwise seen from outside.
  std::vector<std::array<int, 3>> triangles;
  // Maximal groups of edge-adjacent triangles lying in one plane within `coplanar_tolerance`,
  // ordered by their smallest triangle index.
  std::vector<ConvexHullFacet> facets;
};

// The hull of `points` (duplicates allowed). Two adjacent hull triangles belong to one facet when
// the far corner of each is within `coplanar_tolerance` (a length, >= 0) of the other's plane; a
// triangle no neighbour takes so (a sliver along a hull edge, or one of no area) joins the first
// neighbour whose plane holds its three corners, so that no sliver joins two faces.
ConvexHull3d convex_hull_3d(const std::vector<Eigen::Vector3d>& points, double coplanar_tolerance);

}  // namespace offsetopt
