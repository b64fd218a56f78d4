#include "geometry/face_shortlist.h"

#include <algorithm>
#include <cmath>

namespace offsetopt {

namespace {
// Far above the relative rounding of a computed distance (a few ulps), far below anything a
// gathering radius is chosen by.
constexpr double kSlack = 1e-9;
}  // namespace

void FaceShortlist::gather(const TriangleBvh& bvh, const Eigen::Vector3d& centre, double radius) {
  bvh_ = &bvh;
  centre_ = centre;
  radius_ = radius;
  gathered_ = true;
  overflowed_ = false;
  faces_.clear();
  const double limit = radius * radius;
  bvh.traverse([&](const Aabb& box) { return box.squared_distance(centre) <= limit; },
               [&](int face) {
                 const double squared = bvh.face_box(face).squared_distance(centre);
                 if (squared <= limit) faces_.push_back({std::sqrt(squared), face});
                 overflowed_ = faces_.size() > kMaxFaces;
                 return !overflowed_;
               });
  if (overflowed_) {
    faces_.clear();
    return;
  }
  // Nearest the centre first: a point's search stops at the first face too far from the centre
  // to come within its best distance.
  std::sort(faces_.begin(), faces_.end(), [](const Entry& a, const Entry& b) { return a.from_centre < b.from_centre; });
  // Rounding of the distances compared when stopping (coordinates' and radius' scale).
  stop_slack_ = kSlack * (radius + centre.cwiseAbs().maxCoeff());
}

bool FaceShortlist::covers(const Eigen::Vector3d& centre, double reach) const {
  return gathered_ && ((centre - centre_).norm() + reach) * (1.0 + kSlack) <= radius_;
}

ClosestPoint FaceShortlist::nearest(const TriangleBvh& bvh, const Eigen::Vector3d& p, double max_distance, int hint) const {
  if (!gathered_ || overflowed_ || bvh_ != &bvh) {
    ++fallbacks;
    return closest_point(bvh, p, max_distance);
  }
  ClosestPoint best;
  double best_squared = max_distance * max_distance;
  // closest_point's own measure and tie rule, so the order the faces are met in does not matter;
  // a face whose box is clearly beyond the best so far cannot be nearer (nor tie).
  auto measure = [&](int face) {
    if (bvh.face_box(face).squared_distance(p) > best_squared * (1.0 + kSlack)) return;
    const Eigen::Vector3d q = closest_point_on_triangle(p, bvh.corner(face, 0), bvh.corner(face, 1), bvh.corner(face, 2));
    const double d = (q - p).squaredNorm();
    if (d < best_squared || (d == best_squared && best.found && face < best.face)) {
      best_squared = d;
      best.found = true;
      best.face = face;
      best.point = q;
    }
  };
  if (hint >= 0) measure(hint);
  // A face at least `from_centre` from the centre is at least that minus |p − c| from p.
  const double offset = (p - centre_).norm() + stop_slack_;
  double best_distance = std::sqrt(best_squared);
  for (const Entry& entry : faces_) {
    if (entry.from_centre - offset > best_distance) break;
    if (entry.face == hint) continue;
    const double before = best_squared;
    measure(entry.face);
    if (best_squared != before) best_distance = std::sqrt(best_squared);
  }
  if (best.found) best.distance = (best.point - p).norm();
  // Any face nearer than the answer (or within max_distance) lies within |p − c| + that of the
  // centre, so it was gathered when that is within the radius; else the tree decides.
  const double reach = best.found ? best.distance : max_distance;
  if (!(std::isfinite(reach) && covers(p, reach))) {
    ++fallbacks;
    return closest_point(bvh, p, max_distance);
  }
  return best;
}

}  // namespace offsetopt
