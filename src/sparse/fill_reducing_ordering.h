// Fill-reducing orderings for the sparse Cholesky factorisations of the contraction's normal
// equations (2-ring pattern of a surface mesh). Two candidates are analysed symbolically and the
// one with fewer predicted factorisation flops wins:
//   - approximate minimum degree (Eigen's AMD, Amestoy, Davis & Duff 1996), best on real models
//     whose limbs and ears give small natural separators;
//   - geometric nested dissection (George 1973): recursive median splits of the vertex positions
//     along the direction (13 tried for large parts: axes, face and body diagonals; 3 axes for
//     small ones) cutting the fewest mesh edges; the separator is the band of one half within
//     `hops` edges of the other (2 for L^T L), numbered last; small parts by AMD. On sphere-like
//     meshes it needs about half the flops of AMD.
// Both are deterministic functions of the pattern and the positions.
#pragma once
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace offsetopt {

// Symbolic Cholesky analysis of P A P^T for A symmetric with a full (both triangles) pattern.
struct CholeskyCounts {
  std::vector<int> parent;         // elimination tree, -1 at roots (indices in the new order)
  std::vector<int> column_counts;  // non-zeros per column of L, diagonal included
  double flops = 0.0;              // sum of column_counts^2: proportional to factorisation work
  double nonzeros = 0.0;           // nnz(L)
};

// new_to_old[k] = the original index placed at position k.
CholeskyCounts cholesky_counts(const Eigen::SparseMatrix<double>& pattern, const std::vector<int>& new_to_old);

struct FillReducingOrdering {
  std::vector<int> new_to_old;
  std::string method;  // "amd" or "nested_dissection"
  CholeskyCounts counts;
};

// `positions` gives one point per row of `pattern` (#rows by 3) and `graph` the mesh's 1-ring
// adjacency (any symmetric pattern, e.g. the Laplacian's), such that `pattern` links exactly the
// vertices at most `hops` edges apart; both are used by nested dissection only. With
// `second_thread` nested dissection runs beside the minimum-degree ordering (the same result).
FillReducingOrdering fill_reducing_ordering(const Eigen::SparseMatrix<double>& pattern, const Vertices& positions,
                                           const Eigen::SparseMatrix<double>& graph, int hops,
                                           bool second_thread = true);

}  // namespace offsetopt
