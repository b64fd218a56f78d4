// Radius of the largest ball inside the solid that touches the surface at a given point: the
// shrinking-ball algorithm (Ma, Bai & Oh 2012, "3D medial axis point approximation using nearest
// neighbors and the normal field"). Starting from an upper bound r, the ball tangent at x with
// centre x + r d (d the inward unit normal) is tested for surface points strictly inside it; the
// nearest one, q, replaces r by the radius of the tangent ball through q,
// r = |x - q|^2 / (2 (q - x) . d), until no point is inside (or `max_iterations`). The centre
// approximates the medial-axis point belonging to x, and r its distance. Points less than
// `relative_tolerance` * r inside the ball are ignored: the radius may exceed the exact one by
// that fraction, and a faceted sphere (whose faces all lie slightly inside the circumsphere)
// stops at once instead of creeping inward.
#pragma once
#include <Eigen/Core>
#include <vector>

#include "geometry/bvh.h"

namespace offsetopt {

struct InscribedBall {
  double radius = 0.0;
  int iterations = 0;
};

// `ignored_faces`: faces never considered (the faces around x, which touch the ball at x).
// `initial_radius` must be an upper bound (e.g. half the chord along d); the result is in
// (0, initial_radius].
InscribedBall inscribed_ball(const TriangleBvh& bvh, const Eigen::Vector3d& x, const Eigen::Vector3d& inward_unit_normal,
                             double initial_radius, const std::vector<int>& ignored_faces = {}, int max_iterations = 8,
                             double relative_tolerance = 1e-2);

// A cheaper upper bound of the same radius from rays: the ball tangent at x through the first hit
// q = x + s u along a unit direction u has radius s / (2 u . d), so the minimum over a fixed fan
// of 25 directions (d and three cones at 20, 40 and 60 degrees around it, eight rays each) bounds
// the inscribed radius from above. Cost: 25 ray casts, independent of how many faces are nearly
// equidistant from the centre (the closest-point search above visits all of them on a sphere).
// Returns at most `max_radius` (e.g. half the chord along d). Stops early, returning a value at
// most `stop_below`, once the radius is known to be that small (for callers that only compare).
double inscribed_radius_by_rays(const TriangleBvh& bvh, const Eigen::Vector3d& x, const Eigen::Vector3d& inward_unit_normal,
                                double max_radius, const std::vector<int>& ignored_faces = {}, double stop_below = 0.0);

}  // namespace offsetopt
