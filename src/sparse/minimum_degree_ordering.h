// Approximate minimum degree ordering (Amestoy, Davis & Duff 1996, "An approximate minimum degree
// ordering algorithm"), Eigen's implementation: best on meshes with limbs, ears and handles whose
// small natural separators it finds by itself. Deterministic (a function of the pattern only).
#pragma once
#include <Eigen/Sparse>
#include <vector>

namespace offsetopt {

// `pattern` is n by n with a symmetric pattern, both triangles stored (values are not read).
// Returns new_to_old: new_to_old[k] is the row/column placed at position k.
std::vector<int> minimum_degree_ordering(const Eigen::SparseMatrix<double>& pattern);

}  // namespace offsetopt
