// The cells of a regular grid around a solid that lie outside its material and are connected to
// the grid's border (the outside world) by a 6-connected flood fill: whether a void is open to the
// outside, or how much of it is enclosed, read off the written surface as a voxel picture.
#pragma once
#include <cstddef>
#include <deque>
#include <vector>

#include "geometry/bvh.h"
#include "geometry/point_in_solid.h"
#include "mesh/mesh.h"

namespace offsetopt::test {

struct OutsideCells {
  Eigen::Vector3d lo;
  double h = 0.0;
  Eigen::Vector3i n;
  std::vector<char> material, outside;  // per cell: centre inside the solid; reached from the border

  std::size_t index(int i, int j, int k) const { return (static_cast<std::size_t>(k) * n.y() + j) * n.x() + i; }
  std::size_t index_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3i c = ((p - lo) / h).array().floor().cast<int>();
    return index(c.x(), c.y(), c.z());
  }
};

// Cells of spacing h over the solid's box grown by two cells on every side (so the border is
// outside the material).
inline OutsideCells outside_cells(const Mesh& solid, double h) {
  OutsideCells g;
  g.h = h;
  const TriangleBvh bvh(solid.V, solid.F);
  g.lo = solid.V.colwise().minCoeff().transpose() - Eigen::Vector3d::Constant(2 * h);
  const Eigen::Vector3d hi = solid.V.colwise().maxCoeff().transpose() + Eigen::Vector3d::Constant(2 * h);
  g.n = ((hi - g.lo) / h).array().ceil().cast<int>();
  g.material.assign(static_cast<std::size_t>(g.n.prod()), 0);
  g.outside.assign(g.material.size(), 0);
  for (int k = 0; k < g.n.z(); ++k)
    for (int j = 0; j < g.n.y(); ++j)
      for (int i = 0; i < g.n.x(); ++i)
        g.material[g.index(i, j, k)] = point_in_solid(bvh, g.lo + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5)) ? 1 : 0;
  std::deque<Eigen::Vector3i> queue{Eigen::Vector3i(0, 0, 0)};
  g.outside[g.index(0, 0, 0)] = 1;
  while (!queue.empty()) {
    const Eigen::Vector3i c = queue.front();
    queue.pop_front();
    for (int d = 0; d < 6; ++d) {
      Eigen::Vector3i m = c;
      m(d / 2) += d % 2 ? 1 : -1;
      if ((m.array() < 0).any() || (m.array() >= g.n.array()).any()) continue;
      const std::size_t id = g.index(m.x(), m.y(), m.z());
      if (g.outside[id] || g.material[id]) continue;
      g.outside[id] = 1;
      queue.push_back(m);
    }
  }
  return g;
}

}  // namespace offsetopt::test
