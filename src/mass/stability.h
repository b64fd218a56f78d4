// Static stability of a solid resting on the ground plane as posed (z up, gravity −z): the ground
// contact set, its support polygon and how far the centre of mass is from falling over
// (Prévost et al. 2013, "Make It Stand"; Musialski et al. 2015, section 6.2, eq. 5).
//
// Contact set: vertices with z ≤ zmin + ground_tol. Support polygon: the convex hull of their xy,
// counter-clockwise, collinear points dropped (geometry/convex_hull_2d.h). Edge i runs from
// support_polygon[i] to support_polygon[(i + 1) % n]; the inside is on its left.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

struct StabilityOptions {
  // Height above the lowest vertex that still counts as touching the ground, in mesh units.
  // Negative (the default): 1e-3 times the bounding-box diagonal.
  double ground_tol = -1.0;

  // Empty when valid, else what is wrong (compute_stability throws it as std::invalid_argument).
  std::string check() const;
};

struct Stability {
  double ground_z = 0.0;    // zmin, the ground plane's height
  double ground_tol = 0.0;  // the tolerance actually used
  int contact_vertex_count = 0;
  std::vector<Eigen::Vector2d> support_polygon;  // CCW; 1 or 2 points when degenerate
  // Signed distance from the centre of mass's xy projection to the polygon boundary, positive
  // inside. For a degenerate polygon (a point or a segment: zero area) it is minus the distance
  // to it, so never positive.
  double com_margin = 0.0;
  // Smallest rotation about a support edge that topples the object: min over edges of
  // atan2(d_edge, h), d_edge the signed distance of the CoM projection to the edge's line
  // (positive inside), h = cz − zmin; in degrees, negative when it already falls. For a single
  // contact point: atan2(−distance, h).
  double tipping_angle_deg = 0.0;
  int tipping_edge = -1;  // the edge attaining the minimum; −1 for a single contact point
  bool stands = false;    // com_margin > 0
};

Stability compute_stability(const Mesh& mesh, const Eigen::Vector3d& center_of_mass,
                            const StabilityOptions& options = {});

// The margin and tipping part of compute_stability for a given support polygon (CCW convex
// hull as convex_hull_2d returns it, at least one point) and a centre of mass at height h above
// the ground. Fills com_margin, tipping_angle_deg, tipping_edge and stands; the rest untouched.
void support_polygon_margins(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& com_xy,
                             double height, Stability& stability);

}  // namespace offsetopt
