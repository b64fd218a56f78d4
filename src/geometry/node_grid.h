// A regular grid of sample points (nodes) in a box, the domain of the implicit cavity
// (docs/design.md "The written cavity"): node (i, j, k), 0 <= i < nx, 0 <= j < ny, 0 <= k < nz,
// sits at origin + spacing (i, j, k), and has the index i + nx (j + ny k). Cell (i, j, k) is the cube
// whose lowest node is (i, j, k); it exists for i < nx - 1, j < ny - 1, k < nz - 1.
#pragma once
#include <cstdint>

#include <Eigen/Core>

namespace offsetopt {

struct NodeGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  std::int64_t nx = 0, ny = 0, nz = 0;

  std::int64_t node_count() const { return nx * ny * nz; }
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k) const { return i + nx * (j + ny * k); }
  // Coordinates computed one axis at a time, origin + spacing * i, the same way everywhere.
  double x(std::int64_t i) const { return origin.x() + spacing * static_cast<double>(i); }
  double y(std::int64_t j) const { return origin.y() + spacing * static_cast<double>(j); }
  double z(std::int64_t k) const { return origin.z() + spacing * static_cast<double>(k); }
  Eigen::Vector3d position(std::int64_t i, std::int64_t j, std::int64_t k) const { return Eigen::Vector3d(x(i), y(j), z(k)); }
  Eigen::Vector3d position(std::int64_t node) const {
    return position(node % nx, (node / nx) % ny, node / (nx * ny));
  }
};

// Whether two grids have the same nodes (origin, spacing and counts, exactly).
inline bool same_grid(const NodeGrid& a, const NodeGrid& b) {
  return a.origin == b.origin && a.spacing == b.spacing && a.nx == b.nx && a.ny == b.ny && a.nz == b.nz;
}

// The grid of `g`'s cell centres: point (i, j, k) is the centre of cell (i, j, k).
inline NodeGrid cell_centres(const NodeGrid& g) {
  NodeGrid c;
  c.spacing = g.spacing;
  c.origin = g.origin + Eigen::Vector3d::Constant(0.5 * g.spacing);
  c.nx = g.nx - 1;
  c.ny = g.ny - 1;
  c.nz = g.nz - 1;
  return c;
}

}  // namespace offsetopt
