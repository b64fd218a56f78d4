#include "mass/stable_pose.h"

#include <vector>

#include "geometry/convex_hull_2d.h"
#include "geometry/convex_hull_3d.h"
#include "mass/stability.h"

namespace offsetopt {

std::string StablePoseOptions::check() const {
  if (!(coplanar_tolerance >= 0.0 && coplanar_tolerance < 1.0)) return "coplanar_tolerance must be in [0, 1)";
  return {};
}

StablePose stable_pose(const Mesh& mesh, const Eigen::Vector3d& center_of_mass, const StablePoseOptions& settings) {
  StablePose pose;
  if (const std::string problem = settings.check(); !problem.empty()) {
    pose.status = StablePoseStatus::bad_options;
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
