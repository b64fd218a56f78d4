// The box [-1,1]² × [0,10] sampled every 0.25 on its surface and sheared y += 0.8 z (tests/geometry
// and tests/mass): the sheared points along each edge are collinear only up to rounding, so the
// convex hull has sliver triangles along its edges. Its faces: two 2 × 10 parallelograms (the ±x
// faces, 1.56 wide between their long sides), two 2 × 2·√41 rectangles (the sheared ±y faces) and
// two 2 × 2 ends; its centre of mass (0, 4, 5).
#pragma once
#include <vector>

#include <Eigen/Core>

namespace offsetopt::test {

inline std::vector<Eigen::Vector3d> sheared_box_points() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 8; ++j)
      for (int k = 0; k <= 40; ++k) {
        if (i != 0 && i != 8 && j != 0 && j != 8 && k != 0 && k != 40) continue;  // the surface only
        const double x = -1.0 + 0.25 * i, y = -1.0 + 0.25 * j, z = 0.25 * k;
        points.emplace_back(x, y + 0.8 * z, z);
      }
  return points;
}

}  // namespace offsetopt::test
