// Nested dissection on the 1-ring pattern of L + sI: a permutation, deterministic, with less fill
// than the natural order and close to minimum degree's (the 2-ring pattern of L^T L is covered by
// tests/sparse/test_supernodal_cholesky.cpp through fill_reducing_ordering).
#include <doctest/doctest.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <algorithm>

#include "../test_meshes.h"
#include "geometry/cotan_laplacian.h"
#include "sparse/nested_dissection.h"

using namespace offsetopt;

namespace {

long factor_nonzeros(const Eigen::SparseMatrix<double>& A, const std::vector<int>& order) {
  const int n = static_cast<int>(A.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(n);
  for (int i = 0; i < n; ++i) P.indices()[order[i]] = i;
  Eigen::SparseMatrix<double> permuted;
  permuted = A.twistedBy(P);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(permuted);
  return static_cast<long>(ldlt.matrixL().nestedExpression().nonZeros());
}

}  // namespace

TEST_CASE("nested dissection returns a permutation that beats the natural order and is near AMD") {
  const Mesh mesh = test::bumpy_icosphere(5);  // 10242 vertices
  Eigen::SparseMatrix<double> A = cotan_laplacian(mesh.V, mesh.F);
  for (Eigen::Index i = 0; i < A.rows(); ++i) A.coeffRef(i, i) += 1.0;
  const std::vector<int> order = nested_dissection(A, mesh.V, A, 1);
  REQUIRE(order.size() == static_cast<std::size_t>(A.rows()));
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) REQUIRE(sorted[i] == static_cast<int>(i));
  std::vector<int> natural(order.size());
  for (std::size_t i = 0; i < natural.size(); ++i) natural[i] = static_cast<int>(i);
  Eigen::AMDOrdering<int> amd;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  amd(A, inverse);
  const std::vector<int> amd_order(inverse.indices().data(), inverse.indices().data() + A.rows());
  const long nd = factor_nonzeros(A, order);
  CHECK(nd < factor_nonzeros(A, natural) / 2);
  CHECK(nd < 1.1 * static_cast<double>(factor_nonzeros(A, amd_order)));
  // Deterministic.
  CHECK(nested_dissection(A, mesh.V, A, 1) == order);
}
