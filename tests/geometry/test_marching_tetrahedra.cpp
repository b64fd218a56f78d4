// Marching tetrahedra and grid winding numbers against independent answers: on random fields the
// contour is closed, consistently oriented and embedded, cuts only axis edges and the face
// diagonals between odd nodes, stays embedded wherever its vertices move along their edges, and
// the exact solid-angle winding number of the contour is 1 at every node with a value >= 0 and 0
// at every other node; grid winding
// numbers equal the solid-angle ones, also where grid rows run exactly through mesh vertices and
// edges, and count a doubly covered region twice.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "../mesh_checks.h"
#include "../mass/geometry_checks.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/grid_winding.h"
#include "geometry/intersecting_faces.h"
#include "geometry/marching_tetrahedra.h"
#include "mesh/primitives.h"
#include "util/rng.h"

using namespace offsetopt;
using offsetopt::test::closed_and_oriented;
using offsetopt::test::winding_number;

namespace {

// Every vertex's faces form one fan (a disk): no two cones meet at a vertex.
bool vertex_manifold(const Mesh& mesh) {
  std::vector<std::map<int, int>> next(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      next[static_cast<std::size_t>(mesh.F(f, c))][mesh.F(f, (c + 1) % 3)] = mesh.F(f, (c + 2) % 3);
  for (const auto& ring : next) {
    if (ring.empty()) continue;
    int start = ring.begin()->first, v = start;
    std::size_t steps = 0;
    do {
      const auto it = ring.find(v);
      if (it == ring.end()) return false;
      v = it->second;
      ++steps;
    } while (v != start && steps <= ring.size());
    if (steps != ring.size()) return false;
  }
  return true;
}

}  // namespace

TEST_CASE("marching tetrahedra on random fields gives closed, oriented, embedded shells") {
  Rng rng(20261125);
  for (int trial = 0; trial < 12; ++trial) {
    NodeGrid grid;
    grid.origin = Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    grid.spacing = 0.3 + rng.uniform();
    grid.nx = 5 + static_cast<std::int64_t>(rng.uniform() * 4);
    grid.ny = 5 + static_cast<std::int64_t>(rng.uniform() * 4);
    grid.nz = 5 + static_cast<std::int64_t>(rng.uniform() * 4);
    // Random values, exact zeros (which count as positive) among them, negative on the border so
    // every shell closes inside the grid.
    std::vector<double> value(static_cast<std::size_t>(grid.node_count()));
    for (std::int64_t k = 0; k < grid.nz; ++k)
      for (std::int64_t j = 0; j < grid.ny; ++j)
        for (std::int64_t i = 0; i < grid.nx; ++i) {
          const bool border = i == 0 || j == 0 || k == 0 || i == grid.nx - 1 || j == grid.ny - 1 || k == grid.nz - 1;
          const double r = rng.uniform();
          double v = r < 0.1 ? 0.0 : rng.uniform(-1.0, 1.0);
          if (border) v = -0.5 - rng.uniform();
          value[static_cast<std::size_t>(grid.index(i, j, k))] = v;
        }
    std::vector<std::int64_t> cells;
    for (std::int64_t k = 0; k + 1 < grid.nz; ++k)
      for (std::int64_t j = 0; j + 1 < grid.ny; ++j)
        for (std::int64_t i = 0; i + 1 < grid.nx; ++i) cells.push_back(grid.index(i, j, k));
    const TetContour contour =
        marching_tetrahedra(grid, cells, [&](std::int64_t n) { return value[static_cast<std::size_t>(n)]; });
    REQUIRE(contour.mesh.F.rows() > 0);
    CHECK(closed_and_oriented(contour.mesh));
    CHECK(vertex_manifold(contour.mesh));
    const TriangleBvh bvh(contour.mesh.V, contour.mesh.F);
    CHECK(self_intersections(bvh, 10).pairs.empty());
    // Every vertex strictly inside the edge between its positive and its negative node.
    for (Eigen::Index v = 0; v < contour.mesh.V.rows(); ++v) {
      const std::size_t u = static_cast<std::size_t>(v);
      CHECK(value[static_cast<std::size_t>(contour.positive_node[u])] >= 0.0);
      CHECK(value[static_cast<std::size_t>(contour.negative_node[u])] < 0.0);
      CHECK(contour.fraction[u] >= 1e-3);
      CHECK(contour.fraction[u] <= 1.0 - 1e-3);
    }
    // The edges cut: an axis edge, or a face diagonal between two nodes with an odd i + j + k (so
    // both cubes on a face cut it the same way); each edge carries one vertex.
    std::set<std::pair<std::int64_t, std::int64_t>> edges;
    int bad_edges = 0, diagonals[2] = {0, 0};
    for (Eigen::Index v = 0; v < contour.mesh.V.rows(); ++v) {
      const std::int64_t a = contour.positive_node[static_cast<std::size_t>(v)], b = contour.negative_node[static_cast<std::size_t>(v)];
      const std::int64_t ia = a % grid.nx, ja = (a / grid.nx) % grid.ny, ka = a / (grid.nx * grid.ny);
      const std::int64_t ib = b % grid.nx, jb = (b / grid.nx) % grid.ny, kb = b / (grid.nx * grid.ny);
      const std::int64_t di = std::abs(ia - ib), dj = std::abs(ja - jb), dk = std::abs(ka - kb);
      const bool step = std::max({di, dj, dk}) == 1;
      const std::int64_t axes = di + dj + dk;
      const bool odd_ends = ((ia + ja + ka) & 1) == 1 && ((ib + jb + kb) & 1) == 1;
      bad_edges += !(step && (axes == 1 || (axes == 2 && odd_ends)));
      if (axes == 2) ++diagonals[(ia - ib) * (ja - jb) + (ja - jb) * (ka - kb) + (ia - ib) * (ka - kb) > 0];
      CHECK(edges.insert({std::min(a, b), std::max(a, b)}).second);
    }
    CHECK(bad_edges == 0);
    CHECK(diagonals[0] > 0);  // both directions of face diagonal (x + y and x - y) occur
    CHECK(diagonals[1] > 0);
    // The solid-angle winding number of the contour is 1 exactly at the non-negative nodes, with
    // the vertices where marching tetrahedra put them and anywhere else strictly inside their
    // edges (also at either end of the range the cavity's placement uses): the surface stays
    // embedded.
    Mesh moved = contour.mesh;
    for (Eigen::Index v = 0; v < moved.V.rows(); ++v) {
      const std::size_t u = static_cast<std::size_t>(v);
      const double r = rng.uniform();
      const double t = r < 0.25 ? 1e-3 : r < 0.5 ? 1.0 - 1e-3 : rng.uniform(1e-3, 1.0 - 1e-3);
      const Eigen::Vector3d p = grid.position(contour.positive_node[u]), q = grid.position(contour.negative_node[u]);
      moved.V.row(v) = (p + t * (q - p)).transpose();
    }
    const TriangleBvh moved_bvh(moved.V, moved.F);
    CHECK(self_intersections(moved_bvh, 10).pairs.empty());
    const Mesh* placements[2] = {&contour.mesh, &moved};
    for (const Mesh* mesh : placements) {
      int mismatches = 0;
      for (std::int64_t n = 0; n < grid.node_count(); ++n) {
        const double w = winding_number(*mesh, grid.position(n));
        const double expected = value[static_cast<std::size_t>(n)] >= 0.0 ? 1.0 : 0.0;
        mismatches += std::fabs(w - expected) > 1e-6;
      }
      CHECK(mismatches == 0);
    }
  }
}

TEST_CASE("grid winding numbers equal solid-angle winding numbers, also on rows through vertices and edges") {
  // The box's corners and the icosphere's poles lie exactly on grid rows and at node positions.
  const Mesh box = make_box({0, 0, 0}, {2, 3, 1});
  const Mesh sphere = make_icosphere(1.5, 2);
  for (const Mesh* mesh : {&box, &sphere}) {
    NodeGrid grid;
    grid.origin = Eigen::Vector3d(-2, -2, -2);
    grid.spacing = 0.5;
    grid.nx = grid.ny = grid.nz = 15;
    const TriangleBvh bvh(mesh->V, mesh->F);
    for (int threads : {1, 2}) {
      const std::vector<std::int8_t> w = grid_winding(*mesh, grid, threads);
      int mismatches = 0, on_surface = 0;
      for (std::int64_t n = 0; n < grid.node_count(); ++n) {
        // Nodes on the surface itself may count on either side.
        if (closest_point(bvh, grid.position(n), 1e-9).found) {
          ++on_surface;
          continue;
        }
        const double exact = winding_number(*mesh, grid.position(n));
        mismatches += w[static_cast<std::size_t>(n)] != static_cast<int>(std::lround(exact));
      }
      CHECK(mismatches == 0);
      if (mesh == &box) CHECK(on_surface > 0);  // rows do run through the box's faces and edges
    }
  }
}

TEST_CASE("grid winding counts a doubly covered region twice") {
  Mesh two = make_icosphere(1.0, 2);
  const Mesh shifted = make_icosphere(1.0, 2);
  const Eigen::Index n = two.V.rows(), f = two.F.rows();
  two.V.conservativeResize(2 * n, 3);
  two.F.conservativeResize(2 * f, 3);
  for (Eigen::Index i = 0; i < n; ++i) two.V.row(n + i) = shifted.V.row(i) + Eigen::RowVector3d(0.7, 0.0, 0.0);
  for (Eigen::Index i = 0; i < f; ++i) two.F.row(f + i) = shifted.F.row(i).array() + static_cast<int>(n);
  NodeGrid grid;
  grid.origin = Eigen::Vector3d(-1.31, -1.27, -1.23);
  grid.spacing = 0.1;
  grid.nx = 32;
  grid.ny = grid.nz = 26;
  const std::vector<std::int8_t> w = grid_winding(two, grid, 2);
  int twice = 0, mismatches = 0;
  for (std::int64_t node = 0; node < grid.node_count(); ++node) {
    const double exact = winding_number(two, grid.position(node));
    mismatches += w[static_cast<std::size_t>(node)] != static_cast<int>(std::lround(exact));
    twice += w[static_cast<std::size_t>(node)] == 2;
  }
  CHECK(mismatches == 0);
  CHECK(twice > 100);
}

TEST_CASE("marching tetrahedra in two ranges joined equals the serial contour, bit for bit") {
  Rng rng(23);
  WorkerPool pool(2);
  for (int trial = 0; trial < 12; ++trial) {
    NodeGrid grid;
    grid.origin = Eigen::Vector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    grid.spacing = 0.1 + rng.uniform() * 0.2;
    grid.nx = 4 + static_cast<std::int64_t>(rng.uniform() * 8);
    grid.ny = 4 + static_cast<std::int64_t>(rng.uniform() * 8);
    grid.nz = 4 + static_cast<std::int64_t>(rng.uniform() * 8);
    // A ball's field with noise (surfaces that cross the split between the ranges) and zeros.
    const Eigen::Vector3d centre = grid.position(grid.index(grid.nx / 2, grid.ny / 2, grid.nz / 2));
    std::vector<double> value(static_cast<std::size_t>(grid.node_count()));
    for (std::int64_t n = 0; n < grid.node_count(); ++n) {
      const double r = rng.uniform();
      value[static_cast<std::size_t>(n)] =
          r < 0.05 ? 0.0 : 2.5 * grid.spacing - (grid.position(n) - centre).norm() + rng.uniform(-0.5, 0.5) * grid.spacing;
    }
    // Every cell, or only the mixed ones (the contour's own list).
    for (const bool only_mixed : {false, true}) {
      std::vector<std::int64_t> cells;
      std::vector<double> corners;
      for (std::int64_t k = 0; k + 1 < grid.nz; ++k)
        for (std::int64_t j = 0; j + 1 < grid.ny; ++j)
          for (std::int64_t i = 0; i + 1 < grid.nx; ++i) {
            const std::int64_t c = grid.index(i, j, k);
            double at[8];
            int positive = 0;
            for (int corner = 0; corner < 8; ++corner) {
              at[corner] = value[static_cast<std::size_t>(c + (corner & 1) + ((corner >> 1) & 1) * grid.nx +
                                                          ((corner >> 2) & 1) * grid.nx * grid.ny)];
              positive += at[corner] >= 0.0;
            }
            if (only_mixed && (positive == 0 || positive == 8)) continue;
            cells.push_back(c);
            corners.insert(corners.end(), at, at + 8);
          }
      const TetContour serial = marching_tetrahedra(grid, cells, [&](std::int64_t n) { return value[static_cast<std::size_t>(n)]; });
      const TetContour joined = marching_tetrahedra(grid, cells, corners, 1e-3, &pool);
      REQUIRE(serial.mesh.F.rows() > 0);
      CHECK(joined.mesh.V == serial.mesh.V);
      CHECK(joined.mesh.F == serial.mesh.F);
      CHECK(joined.positive_node == serial.positive_node);
      CHECK(joined.negative_node == serial.negative_node);
      CHECK(joined.fraction == serial.fraction);
    }
  }
}
