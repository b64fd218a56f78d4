// Cotan Laplacian and lumped mass: the structural properties docs/design.md relies on (symmetry,
// constants in the null space, positive semi-definite), closed-form values on a regular
// tetrahedron, invariance under scaling, and the degenerate-triangle guard.
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "../test_meshes.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/lumped_mass.h"

using namespace offsetopt;

namespace {

double infinity_norm(const Eigen::SparseMatrix<double>& L) {
  return Eigen::MatrixXd(L).cwiseAbs().rowwise().sum().maxCoeff();
}

void check_structure(const Mesh& mesh, const std::string& name) {
  CAPTURE(name);
  const Eigen::SparseMatrix<double> L = cotan_laplacian(mesh.V, mesh.F);
  const Eigen::MatrixXd dense(L);
  const double norm = infinity_norm(L);
  REQUIRE(norm > 0.0);
  REQUIRE(dense.allFinite());
  // Symmetric bit for bit.
  CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() == 0.0);
  // L 1 = 0.
  CHECK((dense * Eigen::VectorXd::Ones(dense.rows())).cwiseAbs().maxCoeff() <= 1e-12 * norm);
  // Positive semi-definite, and (closed, connected mesh) exactly one zero eigenvalue.
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly).eigenvalues();
  CHECK(eigenvalues(0) >= -1e-12 * norm);
  CHECK(eigenvalues(1) > 1e-6 * norm);
}

}  // namespace

TEST_CASE("cotan Laplacian is symmetric, annihilates constants and is PSD, also scaled by 1e8 and 1e-8") {
  for (const auto& [name, mesh] : test::test_meshes()) {
    check_structure(mesh, name);
    check_structure(test::scaled(mesh, 1e8), name + " x 1e8");
    check_structure(test::scaled(mesh, 1e-8), name + " x 1e-8");
    // Cotangents are dimensionless: scaling leaves L unchanged up to rounding.
    const Eigen::MatrixXd L(cotan_laplacian(mesh.V, mesh.F));
    for (double factor : {1e8, 1e-8}) {
      const Mesh copy = test::scaled(mesh, factor);
      const Eigen::MatrixXd S(cotan_laplacian(copy.V, copy.F));
      CHECK((S - L).cwiseAbs().maxCoeff() <= 1e-12 * L.cwiseAbs().maxCoeff());
    }
  }
}

TEST_CASE("cotan Laplacian and mass of a regular tetrahedron have their closed forms") {
  // Every angle is 60 degrees: each edge has weight (cot 60 + cot 60) / 2 = 1/sqrt(3).
  Mesh tet;
  tet.V.resize(4, 3);
  tet.V << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  tet.F.resize(4, 3);
  tet.F << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  const Eigen::MatrixXd L(cotan_laplacian(tet.V, tet.F));
  const double w = 1.0 / std::sqrt(3.0);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) CHECK(L(i, j) == doctest::Approx(i == j ? 3.0 * w : -w).epsilon(1e-14));
  }
  // Edge length 2 sqrt(2): face area sqrt(3)/4 * 8 = 2 sqrt(3); each vertex has 3 faces / 3.
  const Eigen::VectorXd mass = lumped_mass(tet.V, tet.F);
  for (int i = 0; i < 4; ++i) CHECK(mass(i) == doctest::Approx(2.0 * std::sqrt(3.0)).epsilon(1e-14));
}

TEST_CASE("lumped mass is positive and sums to the surface area") {
  const Mesh box = make_box({-1, -2, -0.5}, {1, 2, 0.5});  // 2 x 4 x 1
  const Eigen::VectorXd mass = lumped_mass(box.V, box.F);
  CHECK(mass.minCoeff() > 0.0);
  CHECK(mass.sum() == doctest::Approx(2.0 * (2 * 4 + 4 * 1 + 2 * 1)).epsilon(1e-14));
  // An icosphere's area approaches 4 pi R^2 from below.
  const Mesh sphere = make_icosphere(2.0, 5);
  const double area = lumped_mass(sphere.V, sphere.F).sum();
  CHECK(area < 4.0 * kPi * 4.0);
  CHECK(area > 0.998 * 4.0 * kPi * 4.0);
}

TEST_CASE("degenerate triangles give finite weights and keep L positive semi-definite") {
  // An octahedron whose top vertex drops onto the midpoint of the edge 0-2: face (0, 2, 4) turns
  // into a needle and finally into a segment (zero area).
  for (double squash : {1e-3, 1e-9, 0.0}) {
    CAPTURE(squash);
    Mesh m;
    m.V.resize(6, 3);
    m.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
    m.F.resize(8, 3);
    m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
    m.V.row(4) << 0.5, 0.5, squash;
    const Eigen::SparseMatrix<double> L = cotan_laplacian(m.V, m.F);
    const Eigen::MatrixXd dense(L);
    REQUIRE(dense.allFinite());
    const double norm = dense.cwiseAbs().rowwise().sum().maxCoeff();
    CHECK(norm <= 1e9);  // |cot| <= ~1/sine_floor
    CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK((dense * Eigen::VectorXd::Ones(6)).cwiseAbs().maxCoeff() <= 1e-12 * norm);
    const double smallest = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly).eigenvalues()(0);
    CHECK(smallest >= -1e-12 * norm);
  }
  // All three corners at one point: the triangle contributes nothing.
  Mesh point;
  point.V = Vertices::Zero(3, 3);
  point.F.resize(1, 3);
  point.F << 0, 1, 2;
  CHECK(Eigen::MatrixXd(cotan_laplacian(point.V, point.F)).cwiseAbs().maxCoeff() == 0.0);
}
