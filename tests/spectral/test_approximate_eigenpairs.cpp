// ApproximateEigenpairs against Eigen's dense SelfAdjointEigenSolver: the values bit for bit, the
// vectors within the proven distance bound (checked against the dense solver's vectors), and an
// infinite bound where a value is repeated (no single vector is determined).
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "spectral/approximate_eigenpairs.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

// A symmetric block-tridiagonal matrix like the Lanczos projection (band `b`), plus a dense
// arrow part when `arrow` (the shape after a thick restart).
Eigen::MatrixXd projection_like(int n, int b, bool arrow, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    H(i, i) = 1.0 / (1.0 + 0.05 * i) + 1e-3 * rng.uniform(-1.0, 1.0);
    for (int d = 1; d <= b && i + d < n; ++d) H(i, i + d) = H(i + d, i) = 1e-2 * rng.uniform(-1.0, 1.0);
    if (arrow && i >= n / 2)
      for (int c = 0; c < n / 2; ++c) H(i, c) = H(c, i) = 1e-3 * rng.uniform(-1.0, 1.0);
  }
  return H;
}

}  // namespace

TEST_CASE("approximate_eigenpairs: values bit for bit those of SelfAdjointEigenSolver") {
  for (int n : {2, 7, 42, 96, 180}) {
    for (bool arrow : {false, true}) {
      const Eigen::MatrixXd H = projection_like(n, 6, arrow, 17u + static_cast<std::uint64_t>(n));
      const ApproximateEigenpairs ours(H);
      REQUIRE(ours.ok());
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(H);
      for (int i = 0; i < n; ++i) CHECK(ours.values()(i) == dense.eigenvalues()(n - 1 - i));
    }
  }
}

TEST_CASE("approximate_eigenpairs: vectors within their bound of the dense solver's") {
  for (int n : {12, 60, 150}) {
    const Eigen::MatrixXd H = projection_like(n, 6, n == 60, 5u + static_cast<std::uint64_t>(n));
    const ApproximateEigenpairs ours(H);
    REQUIRE(ours.ok());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(H);
    int proven = 0;
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd z;
      const double bound = ours.vector(i, z);
      CHECK(std::abs(z.norm() - 1.0) < 1e-12);
      if (!std::isfinite(bound)) continue;
      ++proven;
      const Eigen::VectorXd u = dense.eigenvectors().col(n - 1 - i);
      const double distance = std::min((z - u).norm(), (z + u).norm());
      CHECK(distance <= bound);
      CHECK(bound < 1e-6);  // these values are well separated: the bound must be useful
    }
    CHECK(proven == n);
  }
}

TEST_CASE("approximate_eigenpairs: a repeated value gets no proven vector") {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(5, 5);
  H.diagonal() << 3.0, 2.0, 2.0, 1.0, 0.5;
  const Eigen::MatrixXd rotation =
      Eigen::HouseholderQR<Eigen::MatrixXd>(projection_like(5, 4, false, 3u)).householderQ();
  H = (rotation * H * rotation.transpose()).eval();
  H = 0.5 * (H + H.transpose()).eval();
  const ApproximateEigenpairs ours(H);
  REQUIRE(ours.ok());
  Eigen::VectorXd z;
  CHECK(std::isfinite(ours.vector(0, z)));
  CHECK_FALSE(std::isfinite(ours.vector(1, z)));
  CHECK_FALSE(std::isfinite(ours.vector(2, z)));
  CHECK(std::isfinite(ours.vector(3, z)));
}

TEST_CASE("approximate_eigenpairs: a cluster's subspace within its bound of the dense solver's") {
  // Values 3, 2 + 1e-9, 2, 2 - 1e-9, 1, 0.5 in a random orthonormal frame: the cluster at 2 has
  // no proven single vector but a well-determined three-dimensional subspace.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, 6);
  H.diagonal() << 3.0, 2.0 + 1e-9, 2.0, 2.0 - 1e-9, 1.0, 0.5;
  const Eigen::MatrixXd rotation =
      Eigen::HouseholderQR<Eigen::MatrixXd>(projection_like(6, 5, false, 9u)).householderQ();
  H = (rotation * H * rotation.transpose()).eval();
  H = 0.5 * (H + H.transpose()).eval();
  const ApproximateEigenpairs ours(H);
  REQUIRE(ours.ok());
  Eigen::MatrixXd V;
  const double bound = ours.subspace(1, 3, V);
  REQUIRE(std::isfinite(bound));
  CHECK(bound < 1e-6);
  CHECK((V.transpose() * V - Eigen::MatrixXd::Identity(3, 3)).norm() < 1e-12);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> dense(H);
  const Eigen::MatrixXd Z = dense.eigenvectors().middleCols(2, 3);  // ascending: 0.5, 1, then the cluster
  // min over orthogonal Q of ‖Z - V Q‖₂: Q from the polar factor of Vᵀ Z.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(V.transpose() * Z, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd Q = svd.matrixU() * svd.matrixV().transpose();
  CHECK((Z - V * Q).operatorNorm() <= bound);
  // A part of the cluster, separated by 1e-9 only: whatever bound it gets must hold too.
  const double part_bound = ours.subspace(1, 2, V);
  const Eigen::MatrixXd Z2 = dense.eigenvectors().middleCols(3, 2);
  Eigen::JacobiSVD<Eigen::MatrixXd> part_svd(V.transpose() * Z2, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd Q2 = part_svd.matrixU() * part_svd.matrixV().transpose();
  CHECK((Z2 - V * Q2).operatorNorm() <= part_bound);
}
