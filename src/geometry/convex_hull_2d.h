// Planar convex hull by Andrew's monotone chain (Andrew 1979) on an exact orientation predicate
// (floating-point filter, then exact expansion arithmetic as in Shewchuk 1997, "Adaptive
// Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates"), so nearly collinear
// ground-contact points never produce a non-convex or self-crossing support polygon.
#pragma once
#include <vector>

#include <Eigen/Core>

namespace offsetopt {

// Positive when a, b, c turn counter-clockwise, negative when clockwise, zero exactly when they
// are collinear. The sign is exact for all finite inputs below ~1e150 in magnitude; the magnitude
// approximates twice the signed triangle area.
double orient2d(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);

// The hull's vertices in counter-clockwise order, starting from the lexicographically smallest
// (x, then y) point. Collinear points on the boundary and duplicates are dropped. Degenerate
// input gives a degenerate hull: no points -> empty, all points equal -> 1 point, all collinear ->
// the 2 extreme points.
std::vector<Eigen::Vector2d> convex_hull_2d(std::vector<Eigen::Vector2d> points);

}  // namespace offsetopt
