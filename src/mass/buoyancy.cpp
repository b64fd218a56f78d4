#include "mass/buoyancy.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "mass/mass_properties.h"

namespace offsetopt {

VolumeIntegrals volume_integrals_below(const Mesh& mesh, double level) {
  const Eigen::Vector3d mean = mean_vertex(mesh);
  const Eigen::Vector3d origin(mean.x(), mean.y(), level);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    // Sutherland-Hodgman against the half-space z <= level; crossing points get z = level exactly.
    Eigen::Vector3d polygon[4];
    int count = 0;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = mesh.V.row(mesh.F(f, k)).transpose();
      const Eigen::Vector3d q = mesh.V.row(mesh.F(f, (k + 1) % 3)).transpose();
      const bool p_in = p.z() <= level, q_in = q.z() <= level;
      if (p_in) polygon[count++] = p;
      if (p_in != q_in) {
        const double t = (level - p.z()) / (q.z() - p.z());
        Eigen::Vector3d crossing = p + t * (q - p);
        crossing.z() = level;
        polygon[count++] = crossing;
      }
    }
    if (count < 3) continue;
    const int base = static_cast<int>(points.size());
    for (int k = 0; k < count; ++k) points.push_back(polygon[k]);
    for (int k = 1; k + 1 < count; ++k) triangles.push_back({base, base + k, base + k + 1});
  }
  Mesh clipped;
  clipped.V.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) clipped.V.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  clipped.F.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int c = 0; c < 3; ++c) clipped.F(static_cast<Eigen::Index>(i), c) = triangles[i][static_cast<std::size_t>(c)];
  return volume_integrals(clipped, origin);
}

std::string FloatingOptions::check() const {
  if (!(fluid_density > 0.0) || !std::isfinite(fluid_density)) return "fluid_density must be a positive number";
  if (max_iterations <= 0) return "max_iterations must be positive";
  if (!(level_tolerance > 0.0)) return "level_tolerance must be positive";
  return std::string();
}

FloatingEquilibrium floating_equilibrium(const Mesh& outer, double mass, const FloatingOptions& options) {
  if (const std::string problem = options.check(); !problem.empty()) throw std::invalid_argument(problem);
  if (outer.V.rows() == 0) throw std::invalid_argument("floating_equilibrium: empty mesh");
  double lo = outer.V.col(2).minCoeff(), hi = outer.V.col(2).maxCoeff();
  FloatingEquilibrium out;
  auto record = [&](double level) {
    const VolumeIntegrals below = volume_integrals_below(outer, level);
    out.waterline = level;
    out.displaced_volume = below.values(kIntVolume);
    if (out.displaced_volume > 0.0) {
      const Vector10d P = mass_properties(below);
      out.center_of_buoyancy = Eigen::Vector3d(P(kCx), P(kCy), P(kCz));
    }
  };
  if (mass >= options.fluid_density * volume_integrals(outer).values(kIntVolume)) {
    out.status = FloatingEquilibrium::Status::sinks;
    record(hi);
    return out;
  }
  out.status = FloatingEquilibrium::Status::floats;
  const double tolerance = options.level_tolerance * (hi - lo);
  while (out.iterations < options.max_iterations && hi - lo > tolerance) {
    ++out.iterations;
    const double mid = 0.5 * (lo + hi);
    if (options.fluid_density * volume_integrals_below(outer, mid).values(kIntVolume) < mass)
      lo = mid;
    else
      hi = mid;
  }
  record(0.5 * (lo + hi));
  return out;
}

}  // namespace offsetopt
