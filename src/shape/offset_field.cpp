#include "shape/offset_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/inscribed_ball.h"
#include "geometry/ray_cast.h"
#include "geometry/vertex_cone.h"
#include "geometry/vertex_normals.h"
#include "util/parallel.h"

namespace offsetopt {

std::string OffsetFieldOptions::check() const {
  const OffsetFieldOptions& o = *this;
  const std::pair<bool, const char*> rules[] = {
      {std::isfinite(o.wall) && o.wall >= 0.0, "wall must be finite and >= 0"},
      {o.thickness_cosine_floor > 0.0 && o.thickness_cosine_floor <= 1.0, "thickness_cosine_floor must be in (0, 1]"},
      {o.min_inward_cosine >= 0.0 && o.min_inward_cosine < 1.0, "min_inward_cosine must be in [0, 1)"},
      {o.exit_fraction > 0.0 && o.exit_fraction <= 1.0, "exit_fraction must be in (0, 1]"},
      {std::isfinite(o.min_length) && o.min_length >= 0.0, "min_length must be finite and >= 0"},
      {o.shallow_fraction >= 0.0 && o.shallow_fraction <= 1.0, "shallow_fraction must be in [0, 1]"},
      {o.threads >= 1 && o.threads <= 256, "threads must be in [1, 256]"},
  };
  for (const auto& [ok, what] : rules)
    if (!ok) return std::string("OffsetFieldOptions::") + what;
  return {};
}

OffsetField offset_field(const Mesh& mesh, const Vertices& contracted, const TriangleBvh& bvh,
                         const OffsetFieldOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  const Vertices& V = mesh.V;
  const Faces& F = mesh.F;
  const Eigen::Index n = V.rows();
  if (contracted.rows() != n) throw std::invalid_argument("offset_field: contracted has a different vertex count");
  if (bvh.vertices().rows() != n || bvh.faces().rows() != F.rows())
    throw std::invalid_argument("offset_field: the BVH does not index this mesh");

  OffsetField field;
  field.normals = vertex_normals(V, F);
  field.inner = Vertices::Zero(n, 3);
  field.outer = Vertices::Zero(n, 3);
  field.lower = Eigen::VectorXd::Zero(n);
  field.upper = Eigen::VectorXd::Zero(n);
  field.source.assign(static_cast<std::size_t>(n), OffsetSource::immobile);

  const VertexFaces incident = vertex_faces(n, F);
  const double min_length = options.min_length * bvh.diagonal();
  // Each vertex's direction and bounds depend on that vertex alone, so the vertices are split
  // into contiguous ranges, one per thread; the counts are taken afterwards in vertex order.
  const auto compute_range = [&](Eigen::Index begin, Eigen::Index end) {
    RayCastOptions ray;
    for (Eigen::Index i = begin; i < end; ++i) {
      const int vertex = static_cast<int>(i);
      const Eigen::Vector3d x = V.row(i).transpose();
      const Eigen::Vector3d normal = field.normals.row(i).transpose();
      ray.ignored_faces = incident.of(vertex);
      const bool has_normal = normal.squaredNorm() > 0.0;

      const Eigen::Vector3d to_skeleton = contracted.row(i).transpose() - x;
      const double length = to_skeleton.norm();
      OffsetSource source = OffsetSource::immobile;
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      double upper = 0.0;
      if (has_normal && length > min_length && std::isfinite(length)) {
        const Eigen::Vector3d candidate = to_skeleton / length;
        const double cosine = -candidate.dot(normal);
        if (cosine >= options.min_inward_cosine && direction_enters_solid(V, F, ray.ignored_faces, vertex, candidate)) {
          ray.t_max = std::numeric_limits<double>::infinity();
          const RayCastHit exit = ray_cast_closest(bvh, x, candidate, ray);
          v = candidate;
          if (exit.hit && exit.t < length) {
            source = OffsetSource::shortened;
            upper = options.exit_fraction * exit.t;
          } else {
            source = OffsetSource::contraction;
            upper = length;
            // Under flat or nearly flat regions the meso-skeleton runs close to the surface (the
            // skeleton of a flat-capped cylinder reaches the cap) and the directions converge on it
            // within a few per cent of the part's radius.
            if (options.shallow_fraction > 0.0 && direction_enters_solid(V, F, ray.ignored_faces, vertex, -normal)) {
              const RayCastHit opposite = ray_cast_closest(bvh, x, -normal, ray);
              // rho is at most half the chord along -n and at most exit.t / (2 cos) (the ball
              // through the exit along v), so the ray search runs only when it can succeed, and
              // stops as soon as rho is known to be too small.
              const double depth = length * cosine;
              const double rho_bound = std::min(opposite.hit ? 0.5 * opposite.t : 0.0, exit.hit ? 0.5 * exit.t / cosine : 0.0);
              if (opposite.hit && depth < options.shallow_fraction * rho_bound) {
                const double rho = inscribed_radius_by_rays(bvh, x, -normal, rho_bound, ray.ignored_faces, depth / options.shallow_fraction);
                if (length * cosine < options.shallow_fraction * rho) {
                  source = OffsetSource::shallow;
                  v = -normal;
                  upper = std::min(options.exit_fraction * opposite.t, rho);
                }
              }
            }
          }
        }
      }
      if (source == OffsetSource::immobile && has_normal) {
        v = -normal;
        if (direction_enters_solid(V, F, ray.ignored_faces, vertex, v)) {
          ray.t_max = std::numeric_limits<double>::infinity();
          const RayCastHit hit = ray_cast_closest(bvh, x, v, ray);
          if (hit.hit) {
            source = OffsetSource::fallback;
            upper = options.exit_fraction * hit.t;
          }
        }
      }
      field.inner.row(i) = v.transpose();
      field.upper[i] = upper;
      field.source[static_cast<std::size_t>(i)] = source;
      field.outer.row(i) = options.outer == OuterDirections::normal ? normal.transpose() : Eigen::RowVector3d(-v.transpose());
      const double cosine = -v.dot(normal);
      field.lower[i] = options.wall / (cosine > options.thickness_cosine_floor ? cosine : options.thickness_cosine_floor);
    }
  };
  // Every vertex is computed on its own: ranges of at least 4096 vertices per thread.
  for_ranges(n, options.threads, 4096, compute_range);

  for (const OffsetSource source : field.source) {
    if (source == OffsetSource::shortened) ++field.shortened_count;
    if (source == OffsetSource::shallow) ++field.shallow_count;
    if (source == OffsetSource::shallow || source == OffsetSource::fallback || source == OffsetSource::immobile)
      ++field.fallback_count;
    if (source == OffsetSource::immobile) ++field.immobile_count;
  }
  return field;
}

}  // namespace offsetopt
