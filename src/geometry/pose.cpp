#include "geometry/pose.h"

#include <cmath>

#include <Eigen/Geometry>

namespace offsetopt {

Eigen::Matrix3d AxisPermutation::matrix() const {
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 3; ++i) R(i, source[i]) = sign[i];
  return R;
}

AxisPermutation AxisPermutation::inverse() const {
  AxisPermutation inv;
  for (int i = 0; i < 3; ++i) {
    inv.source[source[i]] = i;
    inv.sign[source[i]] = sign[i];
  }
  return inv;
}

Eigen::Vector3d AxisPermutation::apply(const Eigen::Vector3d& x) const {
  // Negation, not multiplication by ±1 in a matrix product: the sign of a zero survives, so the
  // inverse restores the very same doubles.
  Eigen::Vector3d y;
  for (int i = 0; i < 3; ++i) y[i] = sign[i] < 0.0 ? -x[source[i]] : x[source[i]];
  return y;
}

bool AxisPermutation::is_identity() const {
  for (int i = 0; i < 3; ++i)
    if (source[i] != i || sign[i] != 1.0) return false;
  return true;
}

bool up_axis_permutation(const std::string& name, AxisPermutation& permutation) {
  std::string axis = name;
  if (axis.size() == 1) axis = "+" + axis;
  struct Entry {
    const char* name;
    int source[3];
    double sign[3];
  };
  // Each a quarter or half turn (determinant +1) taking the named axis to +z.
  static const Entry table[] = {
      {"+z", {0, 1, 2}, {1, 1, 1}},  {"-z", {0, 1, 2}, {1, -1, -1}}, {"+y", {0, 2, 1}, {1, -1, 1}},
      {"-y", {0, 2, 1}, {1, 1, -1}}, {"+x", {2, 1, 0}, {-1, 1, 1}},  {"-x", {2, 1, 0}, {1, 1, -1}},
  };
  for (const Entry& entry : table)
    if (axis == entry.name) {
      for (int i = 0; i < 3; ++i) {
        permutation.source[i] = entry.source[i];
        permutation.sign[i] = entry.sign[i];
      }
      return true;
    }
  return false;
}

Mesh permute_axes(const Mesh& mesh, const AxisPermutation& permutation) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) out.V.row(i) = permutation.apply(mesh.V.row(i).transpose()).transpose();
  return out;
}

Mesh apply_rigid_motion(const Mesh& mesh, const RigidMotion& motion) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const Eigen::Vector3d x = mesh.V.row(i).transpose();
    out.V.row(i) = (motion.rotation * x + motion.translation).transpose();
  }
  return out;
}

Eigen::Matrix3d rotation_to_minus_z(const Eigen::Vector3d& from) {
  const Eigen::Vector3d a = from / from.norm();
  Eigen::Matrix3d pre = Eigen::Matrix3d::Identity();
  Eigen::Vector3d u = a;
  if (a.z() > 0.0) {
    // Near +z the rational form divides by ~0: turn by a half turn about x first.
    pre = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
    u = pre * a;
  }
  // R = I + [v]x + [v]x² / (1 + c), v = u × b, c = u · b, b = −z; here 1 + c = 1 − u_z >= 1.
  const Eigen::Vector3d b(0.0, 0.0, -1.0);
  const Eigen::Vector3d v = u.cross(b);
  const double c = u.dot(b);
  Eigen::Matrix3d K;
  K << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  const Eigen::Matrix3d R = Eigen::Matrix3d::Identity() + K + (K * K) / (1.0 + c);
  return R * pre;
}

}  // namespace offsetopt
