// Winding numbers of a closed triangle mesh at every node of a grid, one line per grid row
// (docs/design.md "The written cavity": signs by one ray per row with prefix sums of signed
// crossings). The mesh may fold or cross itself: the winding number still says how often a node
// is enclosed (inside an offset surface that folds means w >= 1, Jacobson et al. 2013).
//
// Each row is the line { (t, y_j, z_k) }. A triangle is crossed where its projection onto the
// (y, z) plane contains (y_j, z_k); entering through a face whose outward normal has n_x < 0
// adds 1 to every node beyond it. The containment test is exact in its tie-breaking: every edge
// function is evaluated with the edge's lower-index vertex first (so the two faces on an edge
// see the same number, negated), and a point on an edge counts as moved by (ε, ε²) in (y, z)
// (simulation of simplicity, Edelsbrunner and Mücke 1990). So a row through a shared edge or
// vertex of a closed mesh is counted exactly once, and faces seen edge-on count zero times.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/node_grid.h"
#include "mesh/mesh.h"

namespace offsetopt {

// Per node (NodeGrid::index order): the winding number, saturated to [-127, 127]. A crossing
// exactly at a node's x counts as before the node. `threads` >= 1 splits the rows in fixed
// parts; the result is the same for any count.
std::vector<std::int8_t> grid_winding(const Mesh& mesh, const NodeGrid& grid, int threads = 2);

}  // namespace offsetopt
