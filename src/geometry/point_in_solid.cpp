#include "geometry/point_in_solid.h"

#include <Eigen/Geometry>
#include <array>
#include <cmath>

#include "geometry/ray_triangle.h"
#include "geometry/triangle_solid_angle.h"
#include "util/det_math.h"

namespace offsetopt {

namespace {

// Directions with no simple rational relation to the axes or to each other, so grid-aligned
// meshes (boxes, revolution surfaces, icospheres) do not put their edges on these rays.
const std::array<Eigen::Vector3d, 7>& probe_directions() {
  static const std::array<Eigen::Vector3d, 7> directions = [] {
    std::array<Eigen::Vector3d, 7> d = {
        Eigen::Vector3d(0.5773502691896258, 0.3141592653589793, 0.7536325413225551),
        Eigen::Vector3d(-0.6180339887498949, 0.2718281828459045, -0.4142135623730951),
        Eigen::Vector3d(0.1732050807568877, -0.8660254037844386, 0.2236067977499790),
        Eigen::Vector3d(-0.3010299956639812, -0.4771212547196624, 0.6989700043360188),
        Eigen::Vector3d(0.7071067811865476, 0.1234567890123457, -0.5432109876543210),
        Eigen::Vector3d(-0.1414213562373095, 0.9510565162951535, 0.3090169943749474),
        Eigen::Vector3d(0.4472135954999579, -0.2588190451025208, -0.8090169943749474)};
    for (auto& v : d) v.normalize();
    return d;
  }();
  return directions;
}

}  // namespace

int ray_winding(const TriangleBvh& bvh, const Eigen::Vector3d& point, const Eigen::Vector3d& direction, bool& ambiguous) {
  ambiguous = false;
  int winding = 0;
  if (bvh.empty()) return 0;
  const Eigen::Vector3d inverse = direction.cwiseInverse();
  // A hit this close to the origin means the point is on the surface (in units of |direction|).
  const double t_surface = 1e-12 * bvh.diagonal() / direction.norm();
  bvh.traverse(
      [&](const Aabb& box) {
        double t0, t1;
        return ray_box_interval(point, inverse, box, 0.0, std::numeric_limits<double>::infinity(), t0, t1);
      },
      [&](int face) {
        const RayTriangleHit h =
            ray_triangle(point, direction, bvh.corner(face, 0), bvh.corner(face, 1), bvh.corner(face, 2), 1e-9);
        if (!h.hit) {
          if (h.ambiguous) ambiguous = true;
          return !ambiguous;
        }
        if (h.t < -t_surface) return true;  // behind the origin
        if (h.ambiguous || h.t <= t_surface) {
          ambiguous = true;
          return false;
        }
        winding += h.orientation > 0.0 ? 1 : -1;
        return true;
      });
  return winding;
}

bool point_in_solid(const TriangleBvh& bvh, const Eigen::Vector3d& point) {
  int votes_inside = 0, clean = 0;
  for (const Eigen::Vector3d& direction : probe_directions()) {
    bool ambiguous = false;
    const int w = ray_winding(bvh, point, direction, ambiguous);
    if (ambiguous) continue;
    ++clean;
    if (w > 0) ++votes_inside;
    if (clean == 3) return votes_inside >= 2;
  }
  return winding_number(bvh.vertices(), bvh.faces(), point) > 0.5;
}

double winding_number(const Vertices& V, const Faces& F, const Eigen::Vector3d& point) {
  double total = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose() - point;
    const Eigen::Vector3d b = V.row(F(f, 1)).transpose() - point;
    const Eigen::Vector3d c = V.row(F(f, 2)).transpose() - point;
    total += triangle_solid_angle(a, b, c);
  }
  return total / (4.0 * kPi);
}

}  // namespace offsetopt
