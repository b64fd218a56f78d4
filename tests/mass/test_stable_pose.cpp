// The stable pose (issue 13, mass/stable_pose.h): a tilted box against the analytic margin of its
// largest face, and a sheared, sampled box against the half-width of its sheared faces.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "../sheared_box_points.h"
#include "geometry/pose.h"
#include "mass/mass_properties.h"
#include "mass/stable_pose.h"
#include "mesh/primitives.h"
#include "util/det_math.h"

using namespace offsetopt;

namespace {

// Rotation by `angle` about the unit axis (Rodrigues), built independently of pose.h.
Eigen::Matrix3d axis_angle(Eigen::Vector3d axis, double angle) {
  axis.normalize();
  double s, c;
  det_sincos(angle, s, c);
  Eigen::Matrix3d K;
  K << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(), axis.x(), 0;
  return Eigen::Matrix3d::Identity() + s * K + (1 - c) * K * K;
}

}  // namespace

TEST_CASE("stable_pose: a tilted 4 x 2 x 1 box rests on a 4 x 2 face with margin 1") {
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(4, 2, 1));
  const Eigen::Matrix3d tilt = axis_angle(Eigen::Vector3d(1, 2, 3), 0.7);
  Mesh tilted = box;
  for (Eigen::Index i = 0; i < box.V.rows(); ++i) tilted.V.row(i) = (tilt * box.V.row(i).transpose()).transpose();
  tilted.V.col(0).array() += 5.0;  // away from the origin too
  const Vector10d P = mass_properties(tilted);
  const StablePose pose = stable_pose(tilted, P.segment<3>(kCx));
  REQUIRE(pose.status == StablePoseStatus::ok);
  CHECK(pose.facet_count == 6);
  CHECK(pose.facet_vertices == 4);
  CHECK(pose.facet_area == doctest::Approx(8.0).epsilon(1e-12));
  CHECK(pose.margin == doctest::Approx(1.0).epsilon(1e-12));  // half the smaller side of the face
  // The chosen face is the bottom (z = 0) or top (z = 1) face of the untilted box.
  const Eigen::Vector3d original_normal = tilt.transpose() * pose.facet_normal;
  CHECK(std::fabs(original_normal.z()) == doctest::Approx(1.0).epsilon(1e-12));
  const Mesh posed = apply_rigid_motion(tilted, pose.motion);
  CHECK(posed.V.col(2).minCoeff() == 0.0);
  const double face_z = original_normal.z() < 0 ? 0.0 : 1.0;
  for (Eigen::Index i = 0; i < box.V.rows(); ++i) {
    if (box.V(i, 2) == face_z) CHECK(std::fabs(posed.V(i, 2)) < 1e-12);
    else CHECK(posed.V(i, 2) == doctest::Approx(1.0).epsilon(1e-12));
  }
  StablePoseOptions bad;
  bad.coplanar_tolerance = -1.0;
  CHECK(stable_pose(tilted, P.segment<3>(kCx), bad).status == StablePoseStatus::bad_options);
  // The pose is a rigid motion: edge lengths are kept.
  CHECK((posed.V.row(7) - posed.V.row(0)).norm() == doctest::Approx(std::sqrt(21.0)).epsilon(1e-14));
}

// The sheared box of tests/sheared_box_points.h: its centre of mass (0, 4, 5) projects onto the
// middle of each long face; on a sheared ±y face (a 2-wide rectangle) the margin is 1, its
// half-width, on a ±x face (a parallelogram 1.56 wide) 0.78, and the ends miss it. Before, slivers
// along the edges merged four faces into one facet and the pose rested on a ±x face, margin 0.78.
TEST_CASE("stable_pose: a sheared, finely sampled box rests on a sheared face with margin 1") {
  Mesh points;
  const std::vector<Eigen::Vector3d> list = test::sheared_box_points();
  points.V.resize(static_cast<Eigen::Index>(list.size()), 3);
  for (std::size_t i = 0; i < list.size(); ++i) points.V.row(static_cast<Eigen::Index>(i)) = list[i].transpose();
  const StablePose pose = stable_pose(points, Eigen::Vector3d(0, 4, 5));
  REQUIRE(pose.status == StablePoseStatus::ok);
  CHECK(pose.facet_count == 6);
  CHECK(pose.margin == doctest::Approx(1.0).epsilon(1e-9));
  CHECK(pose.facet_area == doctest::Approx(2.0 * std::sqrt(164.0)).epsilon(1e-12));
  CHECK(std::fabs(pose.facet_normal.x()) < 1e-12);  // a sheared ±y face: normal (0, ∓1, ±0.8)/√1.64
  CHECK(std::fabs(pose.facet_normal.z()) == doctest::Approx(0.8 / std::sqrt(1.64)).epsilon(1e-12));
}
