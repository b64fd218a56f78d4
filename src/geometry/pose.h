// Poses of a solid before optimisation (issue 13): naming the input's up axis (an exact signed
// permutation of the axes) and resting the object on its most stable convex-hull facet, the
// "place on face" of slicers, scored as in Prévost et al. 2013 ("Make It Stand") by how far the
// centre of mass projects inside the support polygon.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/mesh.h"

namespace offsetopt {

// A right-handed signed permutation of the axes: output axis i takes sign[i] times input axis
// source[i]. Applying it only moves and negates coordinates, so it and its inverse are exact.
struct AxisPermutation {
  int source[3] = {0, 1, 2};
  double sign[3] = {1.0, 1.0, 1.0};
  Eigen::Matrix3d matrix() const;  // R with R * x = applied x
  AxisPermutation inverse() const;
  Eigen::Vector3d apply(const Eigen::Vector3d& x) const;
  bool is_identity() const;
};

// The permutation taking the named up axis ("+x", "-x", "+y", "-y", "+z", "-z"; "x", "y", "z"
// mean "+…") to +z: +y up is the rotation (x, y, z) -> (x, −z, y) about x, as Blender's y-up
// export is read back. Returns false for any other text.
bool up_axis_permutation(const std::string& name, AxisPermutation& permutation);

// The mesh with every vertex permuted (faces unchanged: a rotation keeps orientation).
Mesh permute_axes(const Mesh& mesh, const AxisPermutation& permutation);

// A rigid motion x -> R x + t.
struct RigidMotion {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

Mesh apply_rigid_motion(const Mesh& mesh, const RigidMotion& motion);

// A proper rotation taking the unit vector `from` to −z, from arithmetic and sqrt only
// (Rodrigues' formula in its rational form; a half turn about x first when `from` is near +z).
Eigen::Matrix3d rotation_to_minus_z(const Eigen::Vector3d& from);

enum class StablePoseStatus { ok, bad_settings, no_hull, falls_on_every_facet };

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
struct StablePoseSettings {
  // Two hull triangles are one facet when coplanar within this fraction of the bounding-box
  // diagonal (CAD faces are flat to rounding, scanned "flat" faces are not).
  double coplanar_tolerance = 1e-9;
  std::string check() const;
};

// The hull facet that, turned to be the ground, keeps `center_of_mass` furthest inside the
// facet polygon (first facet on ties), and the motion putting the solid on it. When every facet
// has margin <= 0 (impossible for a solid's own centre of mass, which lies inside its hull) the
// best is still returned with status falls_on_every_facet.
StablePose stable_pose(const Mesh& mesh, const Eigen::Vector3d& center_of_mass, const StablePoseSettings& settings = {});

}  // namespace offsetopt
