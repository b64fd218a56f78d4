#include "geometry/pose.h"

#include <cmath>

#include <Eigen/Geometry>

#include "geometry/convex_hull_2d.h"
#include "geometry/convex_hull_3d.h"
#include "mass/stability.h"

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

std::string StablePoseSettings::check() const {
  if (!(coplanar_tolerance >= 0.0 && coplanar_tolerance < 1.0)) return "coplanar_tolerance must be in [0, 1)";
  return {};
}

StablePose stable_pose(const Mesh& mesh, const Eigen::Vector3d& center_of_mass, const StablePoseSettings& settings) {
  StablePose pose;
  if (const std::string problem = settings.check(); !problem.empty()) {
    pose.status = StablePoseStatus::bad_settings;
    pose.message = problem;
    return pose;
  }
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points[i] = mesh.V.row(i).transpose();
  const double diagonal = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).norm();
  const ConvexHull3d hull = convex_hull_3d(points, settings.coplanar_tolerance * diagonal);
  if (hull.status != ConvexHullStatus::ok) {
    pose.status = StablePoseStatus::no_hull;
    pose.message = "no convex hull: " + hull.message;
    return pose;
  }
  pose.facet_count = static_cast<int>(hull.facets.size());
  int best = -1;
  Eigen::Matrix3d best_rotation = Eigen::Matrix3d::Identity();
  for (int f = 0; f < static_cast<int>(hull.facets.size()); ++f) {
    const ConvexHullFacet& facet = hull.facets[f];
    if (!(facet.normal.squaredNorm() > 0.5)) continue;  // a degenerate facet has no plane
    const Eigen::Matrix3d R = rotation_to_minus_z(facet.normal);
    std::vector<Eigen::Vector2d> polygon;
    double ground = 0.0;
    for (int v : facet.vertices) {
      const Eigen::Vector3d x = R * points[v];
      polygon.emplace_back(x.x(), x.y());
      ground += x.z();
    }
    ground /= static_cast<double>(facet.vertices.size());
    const Eigen::Vector3d com = R * center_of_mass;
    Stability stability;
    support_polygon_margins(convex_hull_2d(polygon), Eigen::Vector2d(com.x(), com.y()), com.z() - ground, stability);
    if (best < 0 || stability.com_margin > pose.margin) {
      best = f;
      pose.margin = stability.com_margin;
      best_rotation = R;
    }
  }
  if (best < 0) {
    pose.status = StablePoseStatus::no_hull;
    pose.message = "no convex hull facet with a plane";
    return pose;
  }
  const ConvexHullFacet& chosen = hull.facets[best];
  pose.facet_area = chosen.area;
  pose.facet_normal = chosen.normal;
  pose.facet_vertices = static_cast<int>(chosen.vertices.size());
  pose.motion.rotation = best_rotation;
  // The lowest point from the very arithmetic apply_rigid_motion uses, so it lands on z = 0 exactly.
  RigidMotion turn;
  turn.rotation = best_rotation;
  const double zmin = apply_rigid_motion(mesh, turn).V.col(2).minCoeff();
  pose.motion.translation = Eigen::Vector3d(0.0, 0.0, -zmin);
  if (!(pose.margin > 0.0)) {
    pose.status = StablePoseStatus::falls_on_every_facet;
    pose.message = "the centre of mass projects outside every convex-hull facet";
  }
  return pose;
}

}  // namespace offsetopt
