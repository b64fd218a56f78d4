// Marching tetrahedra on a regular grid (Doi and Koide 1991; Treece, Prager and Gee 1999): the
// boundary of { value >= 0 } over the cells listed, each cube cut into five tetrahedra by the
// alternating (checkerboard) decomposition: the four corners whose node (i, j, k) has an odd
// sum i + j + k span a central tetrahedron, and each of the other four corners spans a corner
// tetrahedron with its three neighbours along the cube's edges. Adjacent cubes then have
// mirror-image cuts, and the diagonal of every face joins its two nodes of odd sum, so
// neighbouring cubes cut their common face the same way. Unlike marching cubes there is no
// ambiguous case. Against the six tetrahedra around a main diagonal (Kuhn's cut), there is no
// body diagonal and a node has 6 grid edges on average instead of 7: about a fifth fewer
// vertices and triangles, and every triangle fits in a tetrahedron whose longest edge is a face
// diagonal (√2 h). A value equal to 0 counts as positive, so no vertex ever sits on a node.
//
// What the output is, whatever the values (tests/geometry/test_marching_tetrahedra.cpp):
// - the grid edges cut are the axis edges and the face diagonals between two nodes with an odd
//   i + j + k, never a body diagonal;
// - every vertex lies strictly inside one grid edge, between a positive and a negative node, and
//   is shared by every triangle that uses that edge, so every shell is closed and 2-manifold;
// - triangles are oriented with their right-hand normal pointing from the positive side to the
//   negative side (out of { value >= 0 });
// - any placement of the vertices strictly inside their edges keeps the surface embedded (each
//   triangle stays inside its tetrahedron, which only shares faces with the others), which is why
//   a caller may move a vertex along its edge afterwards (the cavity does, to keep the wall).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/node_grid.h"
#include "mesh/mesh.h"
#include "util/parallel.h"

namespace offsetopt {

struct TetContour {
  Mesh mesh;
  // Per vertex: the edge it lies on, as its positive node and its negative node.
  std::vector<std::int64_t> positive_node, negative_node;
  std::vector<double> fraction;  // per vertex: t of positive + t (negative - positive)
};

// `cells`: lowest-node indices of the cells to contour, ascending; every cell whose eight nodes do
// not all have the same sign must be listed (others may be). `value(node)` is asked for the nodes
// of listed cells. The vertex on an edge is at the linear zero crossing, its fraction t clamped
// to [min_fraction, 1 - min_fraction] (0 < min_fraction < 0.5), so no triangle degenerates.
// Vertices are numbered in the order the cells, tetrahedra and edges are visited: the output is a
// function of the input alone.
TetContour marching_tetrahedra(const NodeGrid& grid, const std::vector<std::int64_t>& cells,
                               const std::function<double(std::int64_t)>& value, double min_fraction = 1e-3);
// The same from the values read beforehand: corner_values[8 c + k] is the value at node
// cells[c] + (k & 1) + ((k >> 1) & 1) nx + ((k >> 2) & 1) nx ny. With a pool, the cells are
// contoured in two ranges side by side and joined: the same output, bit for bit.
TetContour marching_tetrahedra(const NodeGrid& grid, const std::vector<std::int64_t>& cells,
                               const std::vector<double>& corner_values, double min_fraction = 1e-3,
                               WorkerPool* pool = nullptr);

}  // namespace offsetopt
