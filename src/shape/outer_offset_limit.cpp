#include "shape/outer_offset_limit.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/closest_point.h"
#include "geometry/ray_cast.h"
#include "geometry/vertex_cone.h"
#include "shape/lipschitz_envelope.h"
#include "util/parallel.h"

namespace offsetopt {

std::string OuterOffsetLimitOptions::check() const {
  const OuterOffsetLimitOptions& o = *this;
  const std::pair<bool, const char*> rules[] = {
      {o.free_fraction > 0.0 && o.free_fraction <= 1.0, "free_fraction must be in (0, 1]"},
      {o.focal_fraction > 0.0 && o.focal_fraction <= 1.0, "focal_fraction must be in (0, 1]"},
      {o.reach >= 1.0 && std::isfinite(o.reach), "reach must be finite and >= 1"},
      {o.nearest_fraction > 0.0 && o.nearest_fraction <= 1.0, "nearest_fraction must be in (0, 1]"},
      {o.max_halvings >= 0 && o.max_halvings <= 30, "max_halvings must be in [0, 30]"},
      {o.slope >= 0.0 && std::isfinite(o.slope), "slope must be finite and >= 0"},
      {o.threads >= 1 && o.threads <= 256, "threads must be in [1, 256]"},
  };
  for (const auto& [ok, what] : rules)
    if (!ok) return std::string("OuterOffsetLimitOptions::") + what;
  return {};
}

namespace {

// The smallest |delta| at which the face, its corners moved by delta along their directions,
// turns over: q(delta) = N(delta) . N(0) = |N0|^2 + c1 delta + c2 delta^2 reaches 0 (infinity when
// it never does; a degenerate face gives no bound).
double face_turnover(const Eigen::Vector3d x[3], const Eigen::Vector3d w[3]) {
  const Eigen::Vector3d e1 = x[1] - x[0], e2 = x[2] - x[0], a = w[1] - w[0], b = w[2] - w[0];
  const Eigen::Vector3d n0 = e1.cross(e2);
  const double c0 = n0.squaredNorm();
  const double c1 = (a.cross(e2) + e1.cross(b)).dot(n0);
  const double c2 = a.cross(b).dot(n0);
  double best = std::numeric_limits<double>::infinity();
  if (!(c0 > 0.0)) return best;
  auto keep = [&](double root) {
    if (std::isfinite(root) && root != 0.0) best = std::min(best, std::fabs(root));
  };
  const double scale = std::fabs(c1) + std::sqrt(std::fabs(c2) * c0);
  if (std::fabs(c2) <= 1e-14 * (scale * scale / c0)) {
    if (c1 != 0.0) keep(-c0 / c1);
    return best;
  }
  const double discriminant = c1 * c1 - 4.0 * c2 * c0;
  if (discriminant < 0.0) return best;
  // The root of larger magnitude without cancellation, the other from the product c0 / c2.
  const double q = -0.5 * (c1 + (c1 >= 0.0 ? 1.0 : -1.0) * std::sqrt(discriminant));
  keep(q / c2);
  if (q != 0.0) keep(c0 / q);
  return best;
}

}  // namespace

OuterOffsetLimit outer_offset_limit(const Mesh& mesh, const TriangleBvh& bvh, const Vertices& outer_directions,
                                    const Vertices& normals, const Eigen::VectorXd& requested,
                                    const OuterOffsetLimitOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  const Eigen::Index n = mesh.V.rows();
  if (outer_directions.rows() != n || normals.rows() != n || requested.size() != n)
    throw std::invalid_argument("outer_offset_limit: directions, normals and requested limits need one row per vertex");
  if (bvh.vertices().rows() != n || bvh.faces().rows() != mesh.F.rows())
    throw std::invalid_argument("outer_offset_limit: the BVH does not index this mesh");

  // Focal rule, per face, then per vertex: the smallest over its faces.
  Eigen::VectorXd focal = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    Eigen::Vector3d x[3], w[3];
    for (int c = 0; c < 3; ++c) {
      x[c] = mesh.V.row(mesh.F(f, c)).transpose();
      w[c] = outer_directions.row(mesh.F(f, c)).transpose();
    }
    const double turnover = options.focal_fraction * face_turnover(x, w);
    for (int c = 0; c < 3; ++c) focal(mesh.F(f, c)) = std::min(focal(mesh.F(f, c)), turnover);
  }

  OuterOffsetLimit out;
  out.limit = Eigen::VectorXd::Zero(n);
  std::vector<char> lowered(static_cast<std::size_t>(3 * n), 0);  // free, focal, nearest per vertex
  const VertexFaces incident = vertex_faces(n, mesh.F);
  const auto compute_range = [&](Eigen::Index begin, Eigen::Index end) {
    RayCastOptions ray;
    for (Eigen::Index i = begin; i < end; ++i) {
      const Eigen::Vector3d x = mesh.V.row(i).transpose();
      const Eigen::Vector3d w = outer_directions.row(i).transpose();
      const Eigen::Vector3d normal = normals.row(i).transpose();
      const double want = requested(i);
      if (!(want > 0.0) || w.squaredNorm() == 0.0 || normal.squaredNorm() == 0.0) continue;
      double limit = want;
      ray.ignored_faces = incident.of(static_cast<int>(i));
      ray.t_max = want / options.free_fraction;
      const RayCastHit hit = ray_cast_closest(bvh, x, w, ray);
      if (hit.hit && options.free_fraction * hit.t < limit) {
        limit = options.free_fraction * hit.t;
        lowered[static_cast<std::size_t>(3 * i)] = 1;
      }
      if (focal(i) < limit) {
        limit = focal(i);
        lowered[static_cast<std::size_t>(3 * i + 1)] = 1;
      }
      // Nearest rule: a point whose distance to the surface is not (nearly) its distance to x_i's
      // own faces has some other part of the surface nearer than x_i's neighbourhood. Not the
      // height above the tangent plane: at a concave crease the faces across it are x_i's own and
      // nearer than that height at every scale (0.71 of it at a right angle), so halving never
      // passed and every engraved letter of a CAD part kept no thickening.
      const std::vector<int>& own_faces = ray.ignored_faces;
      for (int halving = 0;; ++halving) {
        if (!(limit * w.dot(normal) > 0.0)) {
          limit = 0.0;
          break;
        }
        const Eigen::Vector3d p = x + options.reach * limit * w;
        double own = std::numeric_limits<double>::infinity();
        for (int face : own_faces) {
          const Eigen::Vector3d corner[3] = {mesh.V.row(mesh.F(face, 0)).transpose(), mesh.V.row(mesh.F(face, 1)).transpose(),
                                             mesh.V.row(mesh.F(face, 2)).transpose()};
          own = std::min(own, (p - closest_point_on_triangle(p, corner[0], corner[1], corner[2])).norm());
        }
        const ClosestPoint nearest = closest_point(bvh, p, options.nearest_fraction * own);
        if (!nearest.found) break;
        lowered[static_cast<std::size_t>(3 * i + 2)] = 1;
        if (halving == options.max_halvings) {
          limit = 0.0;
          break;
        }
        limit *= 0.5;
      }
      out.limit(i) = limit;
    }
  };
  for_ranges(n, options.threads, 4096, compute_range);
  for (Eigen::Index i = 0; i < n; ++i) {
    out.free_limited += lowered[static_cast<std::size_t>(3 * i)];
    out.focal_limited += lowered[static_cast<std::size_t>(3 * i + 1)];
    out.nearest_limited += lowered[static_cast<std::size_t>(3 * i + 2)];
  }
  out.limit = lipschitz_envelope(mesh, out.limit, options.slope);
  return out;
}

}  // namespace offsetopt
