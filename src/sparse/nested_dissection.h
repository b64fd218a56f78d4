// Geometric nested dissection (George 1973, "Nested dissection of a regular finite element mesh";
// Miller, Teng, Thurston & Vavasis 1998 for separators from geometry): split the vertex set at
// the median of the vertex positions along one of a few fixed directions (13 for the large parts
// of the first levels: axes, face and body diagonals; the 3 axes below), keep the cut with the
// smallest separator, order both halves recursively and the separator last. The separator is
// the band of the half with the shorter boundary within `hops` edges of the other half: 1 for a
// matrix with the mesh's 1-ring pattern (the cotan Laplacian + shift of the eigensolver), 2 for
// the 2-ring pattern of L^T L (the contraction's normal equations). Parts of at most 256 vertices
// and every separator are ordered by minimum degree (sparse/minimum_degree_ordering.h).
//
// On sphere-like meshes it needs about half the factorisation work of minimum degree; on real
// models with limbs minimum degree is often better, which is why sparse/fill_reducing_ordering.h
// analyses both and keeps the cheaper. The ordering only affects speed and the rounding of the
// factorisation, never which problem is solved; it is deterministic (ties broken by index).
#pragma once
#include <Eigen/Sparse>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// `pattern` (n by n, symmetric pattern, both triangles stored) is the matrix to be factorised;
// `graph` the mesh's 1-ring adjacency on the same n vertices (any symmetric pattern, e.g. the
// Laplacian's); `positions` n by 3; `pattern` links exactly the vertices at most `hops` >= 1
// edges apart in `graph`. Returns new_to_old: row/column new_to_old[k] of the matrix becomes
// row/column k of the permuted one.
std::vector<int> nested_dissection(const Eigen::SparseMatrix<double>& pattern, const Vertices& positions,
                                   const Eigen::SparseMatrix<double>& graph, int hops);

}  // namespace offsetopt
