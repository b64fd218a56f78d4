// Closest-hit ray casting and segment-versus-mesh tests on a TriangleBvh: the distance along an
// offset direction to the other side of the solid, and whether a segment stays inside.
// Rays are origin + t * direction with t in (t_min, t_max]; t is in units of |direction|.
#pragma once
#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "geometry/bvh.h"

namespace offsetopt {

struct RayCastHit {
  bool hit = false;
  int face = -1;
  double t = std::numeric_limits<double>::infinity();
  double u = 0.0, v = 0.0;  // barycentrics of the face's corners 1 and 2
  bool exiting = false;     // direction . face normal > 0: the ray leaves the solid here
};

struct RayCastOptions {
  double t_min = 0.0;  // hits with t <= t_min are ignored
  double t_max = std::numeric_limits<double>::infinity();
  // Faces the ray ignores, e.g. the faces around the vertex it starts from (they all contain the
  // origin, so they would be hit at t = 0). Small lists; searched linearly.
  std::vector<int> ignored_faces;
  // Barycentric enlargement of each triangle (see ray_triangle): conservative, so a ray through
  // a shared edge or vertex is never lost between its faces.
  double tolerance = 1e-10;

  // Empty when valid, else what is wrong (one line). The casts below do not call it: they run
  // per ray, with options their callers build; a caller taking them from input checks them once.
  std::string check() const;
};

// The nearest hit with t in (t_min, t_max]; ties in t go to the lowest face index, so the result
// does not depend on the traversal order.
RayCastHit ray_cast_closest(const TriangleBvh& bvh, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            const RayCastOptions& options = {});

// True when the segment p -> q meets any face other than `ignored_faces` (endpoints included,
// with the same conservative tolerance).
bool segment_hits_mesh(const TriangleBvh& bvh, const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                       const std::vector<int>& ignored_faces = {});

}  // namespace offsetopt
