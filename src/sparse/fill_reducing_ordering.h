// Fill-reducing orderings for the sparse Cholesky factorisations of mesh matrices (the
// eigensolver's L + sM, 1-ring pattern; the contraction's normal equations, 2-ring pattern). Two
// candidates are analysed symbolically and the one with fewer predicted factorisation flops wins:
//   - approximate minimum degree (sparse/minimum_degree_ordering.h), best on real models whose
//     limbs and ears give small natural separators;
//   - geometric nested dissection (sparse/nested_dissection.h), about half the flops of minimum
//     degree on sphere-like meshes.
// Measured (predicted flops = sum of squared column counts, cotan Laplacian pattern): a 164k-vertex
// icosphere 2.7e9 by nested dissection; the 26k armadillo 4.2e7 by minimum degree against 1.2e8
// by nested dissection, the 173k Armadillo 1.5e9 against 2.4e9.
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

// `pattern` is the matrix to factorise (symmetric pattern, both triangles stored). `positions`
// gives one point per row of `pattern` (#rows by 3) and `graph` the mesh's 1-ring adjacency (any
// symmetric pattern, e.g. the Laplacian's), such that `pattern` links exactly the vertices at
// most `hops` edges apart (1 for L + sM, 2 for L^T L); both are used by nested dissection only,
// which is skipped when their sizes do not match `pattern` or hops < 1 (minimum degree alone). With
// `second_thread` nested dissection runs beside the minimum-degree ordering (the same result).
FillReducingOrdering fill_reducing_ordering(const Eigen::SparseMatrix<double>& pattern, const Vertices& positions,
                                           const Eigen::SparseMatrix<double>& graph, int hops,
                                           bool second_thread = true);

}  // namespace offsetopt
