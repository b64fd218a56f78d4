// A closed box written the way CAD exports write it: T-junctions closed by zero-area triangles
// with three distinct collinear corners (OpenSCAD STL), plus needle triangles (one tiny edge) and
// a cap (an angle near 180 degrees). The solid is exactly the clean box, so every volume integral
// must agree with it. Shared by the meshio, spectral and skeleton tests.
#pragma once
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/primitives.h"

namespace sliver_test {

inline int add_vertex(offsetopt::Mesh& m, const Eigen::RowVector3d& p) {
  m.V.conservativeResize(m.V.rows() + 1, 3);
  m.V.row(m.V.rows() - 1) = p;
  return static_cast<int>(m.V.rows() - 1);
}

inline void add_face(offsetopt::Mesh& m, int a, int b, int c) {
  m.F.conservativeResize(m.F.rows() + 1, 3);
  m.F.row(m.F.rows() - 1) << a, b, c;
}

// Face f = (a, b, c) split at the midpoint m of its edge a-b into (a, m, c) and (m, b, c); the
// face across a-b keeps the edge, and the sliver (a, b, m) closes the T-junction.
inline void add_sliver(offsetopt::Mesh& m, int f) {
  const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
  const int mid = add_vertex(m, 0.5 * (m.V.row(a) + m.V.row(b)));
  m.F.row(f) << a, mid, c;
  add_face(m, mid, b, c);
  add_face(m, a, b, mid);
}

// Face f = (a, b, c) split at p = a + s (b - a) + t (c - a), a point of the face's plane.
inline void add_fan_point(offsetopt::Mesh& m, int f, double s, double t) {
  const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
  const int p = add_vertex(m, m.V.row(a) + s * (m.V.row(b) - m.V.row(a)) + t * (m.V.row(c) - m.V.row(a)));
  m.F.row(f) << a, b, p;
  add_face(m, b, c, p);
  add_face(m, c, a, p);
}

// The box [0,2]x[0,4]x[0,6] (make_box's faces) with 2 slivers, 2 needles near a corner and one cap.
inline offsetopt::Mesh sliver_box() {
  offsetopt::Mesh m = offsetopt::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 4, 6));
  add_sliver(m, 0);               // edge 0-2 on z = 0
  add_sliver(m, 2);               // edge 4-5 on z = 6
  add_fan_point(m, 6, 1e-7, 1e-7);  // needles at corner 2 on y = 4
  add_fan_point(m, 11, 1e-9, 2e-9); // needles at corner 3 on x = 2
  add_fan_point(m, 9, 0.5, 1e-9);   // a cap: almost on the midpoint of edge 2-4 on x = 0
  return m;
}

// The box [0, sx] x [0, sy] x [0, sz] with every face a grid of `cells` squares per unit of
// length (each split into two triangles), outward orientation. Dyadic coordinates keep every
// midpoint exact, so add_sliver makes exactly zero-area triangles anywhere on it.
inline offsetopt::Mesh grid_box(int sx, int sy, int sz, int cells) {
  offsetopt::Mesh m;
  m.V.resize(0, 3);
  m.F.resize(0, 3);
  const int size[3] = {sx, sy, sz};
  std::vector<std::pair<Eigen::Vector3i, int>> index;  // grid point -> vertex, found by a linear scan per face edge
  auto vertex = [&](const Eigen::Vector3i& g) {
    for (const auto& [key, id] : index)
      if (key == g) return id;
    const int id = add_vertex(m, g.cast<double>().transpose() / cells);
    index.emplace_back(g, id);
    return id;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) right-handed
      for (int i = 0; i < size[u] * cells; ++i)
        for (int j = 0; j < size[v] * cells; ++j) {
          Eigen::Vector3i g[4];
          const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
          for (int k = 0; k < 4; ++k) {
            g[k][axis] = side * size[axis] * cells;
            g[k][u] = i + di[k];
            g[k][v] = j + dj[k];
          }
          int q[4];
          for (int k = 0; k < 4; ++k) q[k] = vertex(g[k]);
          if (side == 1) {  // counter-clockwise seen from +axis
            add_face(m, q[0], q[1], q[2]);
            add_face(m, q[0], q[2], q[3]);
          } else {
            add_face(m, q[0], q[2], q[1]);
            add_face(m, q[0], q[3], q[2]);
          }
        }
    }
  return m;
}

}  // namespace sliver_test
