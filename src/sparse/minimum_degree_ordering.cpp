#include "sparse/minimum_degree_ordering.h"

#include <Eigen/OrderingMethods>

namespace offsetopt {

std::vector<int> minimum_degree_ordering(const Eigen::SparseMatrix<double>& pattern) {
  // Eigen's AMD returns P⁻¹ with indices()[new] = old.
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> new_to_old;
  Eigen::AMDOrdering<int> amd;
  amd(pattern, new_to_old);
  return std::vector<int>(new_to_old.indices().data(), new_to_old.indices().data() + new_to_old.size());
}

}  // namespace offsetopt
