#include "mass/stability.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/convex_hull_2d.h"
#include "util/det_math.h"

namespace offsetopt {

namespace {

double cross2(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double length2 = ab.squaredNorm();
  double t = length2 > 0.0 ? (p - a).dot(ab) / length2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return (p - (a + t * ab)).norm();
}

double degrees(double radians) { return radians * (180.0 / kPi); }

}  // namespace

std::string StabilityOptions::check() const {
  if (!std::isfinite(ground_tol)) return "ground_tol must be finite";
  return std::string();
}

void support_polygon_margins(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& com_xy,
                             double height, Stability& s) {
  if (polygon.empty()) throw std::invalid_argument("support_polygon_margins: empty support polygon");
  const std::size_t n = polygon.size();
  if (n == 1) {
    const double distance = (com_xy - polygon[0]).norm();
    s.com_margin = -distance;
    s.tipping_angle_deg = degrees(det_atan2(-distance, height));
    s.tipping_edge = -1;
    s.stands = false;
    return;
  }
  // A segment is walked both ways (edges 0 and 1), so its two sides are both "edges".
  double min_line_distance = std::numeric_limits<double>::infinity();
  double min_segment_distance = std::numeric_limits<double>::infinity();
  int min_edge = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % n];
    const double line_distance = cross2(b - a, com_xy - a) / (b - a).norm();
    if (line_distance < min_line_distance) {
      min_line_distance = line_distance;
      min_edge = static_cast<int>(i);
    }
    min_segment_distance = std::min(min_segment_distance, distance_to_segment(com_xy, a, b));
  }
  // Inside a convex polygon the distance to the boundary is the distance to the nearest edge
  // line; outside (or for a segment) it is the distance to the nearest edge segment.
  const bool inside = n >= 3 && min_line_distance > 0.0;
  s.com_margin = inside ? min_line_distance : -min_segment_distance;
  s.tipping_angle_deg = degrees(det_atan2(min_line_distance, height));
  s.tipping_edge = min_edge;
  s.stands = s.com_margin > 0.0;
}

Stability compute_stability(const Mesh& mesh, const Eigen::Vector3d& center_of_mass, const StabilityOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  if (mesh.V.rows() == 0) throw std::invalid_argument("compute_stability: empty mesh");
  Stability s;
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = mesh.V.colwise().maxCoeff().transpose();
  s.ground_z = lo.z();
  s.ground_tol = options.ground_tol >= 0.0 ? options.ground_tol : 1e-3 * (hi - lo).norm();
  std::vector<Eigen::Vector2d> contacts;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    if (mesh.V(i, 2) <= s.ground_z + s.ground_tol) contacts.emplace_back(mesh.V(i, 0), mesh.V(i, 1));
  s.contact_vertex_count = static_cast<int>(contacts.size());
  s.support_polygon = convex_hull_2d(std::move(contacts));
  support_polygon_margins(s.support_polygon, center_of_mass.head<2>(), center_of_mass.z() - s.ground_z, s);
  return s;
}

}  // namespace offsetopt
