// Poses of a solid before optimisation (issue 13): naming the input's up axis (an exact signed
// permutation of the axes) and the rigid motions that turn a solid onto a plane. Resting the
// object on its most stable convex-hull facet needs the stability test of mass/ and lives in
// mass/stable_pose.h.
#pragma once
#include <string>

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

}  // namespace offsetopt
