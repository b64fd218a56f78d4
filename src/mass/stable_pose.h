// The stable pose of a solid (issue 13): resting the object on its most stable convex-hull facet,
// the "place on face" of slicers, scored as in Prévost et al. 2013 ("Make It Stand") by how far
// the centre of mass projects inside the support polygon (mass/stability.h). The axis
// permutations and rigid motions it returns are geometry/pose.h's.
#pragma once
#include <string>

#include <Eigen/Core>

#include "geometry/pose.h"
#include "mesh/mesh.h"

namespace offsetopt {

enum class StablePoseStatus { ok, bad_options, no_hull, falls_on_every_facet };

struct StablePose {
  StablePoseStatus status = StablePoseStatus::ok;
  std::string message;
  RigidMotion motion;        // applied to the input: the chosen facet on z = 0, lowest point at 0
  double margin = 0.0;       // distance of the CoM's projection inside the facet polygon (> 0 stands)
  double facet_area = 0.0;
  Eigen::Vector3d facet_normal = Eigen::Vector3d::Zero();  // outward, in the input's frame
  int facet_count = 0;       // merged coplanar hull facets considered
  int facet_vertices = 0;    // hull vertices on the chosen facet
};

// Settings of stable_pose; check() returns an empty string or what is wrong.
struct StablePoseOptions {
  // Two hull triangles are one facet when coplanar within this fraction of the bounding-box
  // diagonal (CAD faces are flat to rounding, scanned "flat" faces are not).
  double coplanar_tolerance = 1e-9;
  std::string check() const;
};

// The hull facet that, turned to be the ground, keeps `center_of_mass` furthest inside the
// facet polygon (first facet on ties), and the motion putting the solid on it. When every facet
// has margin <= 0 (impossible for a solid's own centre of mass, which lies inside its hull) the
// best is still returned with status falls_on_every_facet.
StablePose stable_pose(const Mesh& mesh, const Eigen::Vector3d& center_of_mass, const StablePoseOptions& settings = {});

}  // namespace offsetopt
