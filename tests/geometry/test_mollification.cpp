// Intrinsic mollification (Sharp & Crane 2020, section 4.5) on a CAD-style box with zero-area
// slivers, needles and a cap: the cotan Laplacian stays finite, symmetric and PSD with L 1 = 0,
// the lumped mass stays positive, weights stay bounded (where the sine floor alone gives ~1e8),
// and meshes that need no mollification get bit-identical matrices (epsilon = 0 path).
#include <doctest/doctest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "../meshio/sliver_box.h"
#include "geometry/cotan_laplacian.h"
#include "geometry/intrinsic_mollification.h"
#include "geometry/lumped_mass.h"
#include "mesh/primitives.h"
#include "meshio/validate_mesh.h"

using namespace offsetopt;

TEST_CASE("intrinsic area: Heron agrees with the cross product, and 0 for a degenerate triangle") {
  // 3-4-5 right triangle: area 6. Collinear lengths 1, 2, 3: 0. Needle 1, 1, 1e-9: 0.5e-9 * sqrt(1 - 0.25e-18).
  CHECK(intrinsic_area(3, 4, 5) == doctest::Approx(6.0).epsilon(1e-15));
  CHECK(intrinsic_area(5, 3, 4) == intrinsic_area(3, 4, 5));
  CHECK(intrinsic_area(1, 2, 3) == 0.0);
  CHECK(intrinsic_area(1, 1, 1e-9) == doctest::Approx(0.5e-9).epsilon(1e-12));
}

TEST_CASE("mollification epsilon: 0 on well-shaped meshes, the smallest shift that restores the margin otherwise") {
  const Mesh sphere = make_icosphere(1.0, 2);
  CHECK(intrinsic_mollification(face_edge_lengths(sphere.V, sphere.F), kDefaultMollifyMargin).epsilon == 0.0);
  const Mesh box = sliver_test::sliver_box();
  const auto lengths = face_edge_lengths(box.V, box.F);
  const Mollification m = intrinsic_mollification(lengths, kDefaultMollifyMargin);
  REQUIRE(m.epsilon > 0.0);
  CHECK(m.faces_below_margin >= 2);
  // Every triangle keeps the margin after the shift (up to rounding), and at least one meets it exactly.
  double smallest_slack = HUGE_VAL;
  for (Eigen::Index f = 0; f < lengths.rows(); ++f)
    for (int i = 0; i < 3; ++i) {
      const double slack = (lengths(f, (i + 1) % 3) + m.epsilon) + (lengths(f, (i + 2) % 3) + m.epsilon) - (lengths(f, i) + m.epsilon);
      smallest_slack = std::min(smallest_slack, slack);
    }
  CHECK(smallest_slack == doctest::Approx(m.delta).epsilon(1e-9));
}

TEST_CASE("cotan Laplacian of a box with slivers, needles and a cap: finite, symmetric, PSD, L 1 = 0, bounded") {
  const Mesh box = sliver_test::sliver_box();
  const Eigen::SparseMatrix<double> L = cotan_laplacian(box.V, box.F);
  const Eigen::MatrixXd dense(L);
  REQUIRE(dense.allFinite());
  const double norm = dense.cwiseAbs().rowwise().sum().maxCoeff();
  CHECK((dense - dense.transpose()).cwiseAbs().maxCoeff() == 0.0);
  CHECK((dense * Eigen::VectorXd::Ones(dense.rows())).cwiseAbs().maxCoeff() <= 1e-12 * norm);
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense, Eigen::EigenvaluesOnly).eigenvalues();
  CHECK(eigenvalues(0) >= -1e-12 * norm);
  CHECK(eigenvalues(1) > 1e-9 * norm);  // one connected surface: one zero eigenvalue
  // Mollified weights are bounded by about (mean edge) / delta = 1e4; the sine floor alone
  // (mollify_margin = 0) lets the sliver's weights reach about 1 / sine_floor = 1e8.
  CHECK(dense.cwiseAbs().maxCoeff() < 1e6);
  CotanOptions unmollified;
  unmollified.mollify_margin = 0.0;
  const Eigen::MatrixXd floored(cotan_laplacian(box.V, box.F, unmollified));
  CHECK(floored.cwiseAbs().maxCoeff() > 1e7);

  const Eigen::VectorXd mass = lumped_mass(box.V, box.F);
  REQUIRE(mass.allFinite());
  CHECK(mass.minCoeff() > 0.0);
  // The shift adds area of order epsilon * (edge length) per face, tiny against the box's 88.
  CHECK(mass.sum() == doctest::Approx(88.0).epsilon(1e-2));
}

TEST_CASE("meshes needing no mollification get bit-identical matrices with and without it") {
  for (const Mesh& mesh : {make_icosphere(1.0, 2), make_torus(2.0, 0.5, 16, 8), make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3))}) {
    CotanOptions off;
    off.mollify_margin = 0.0;
    const Eigen::MatrixXd a(cotan_laplacian(mesh.V, mesh.F)), b(cotan_laplacian(mesh.V, mesh.F, off));
    CHECK((a - b).cwiseAbs().maxCoeff() == 0.0);
    CHECK((lumped_mass(mesh.V, mesh.F) - lumped_mass(mesh.V, mesh.F, 0.0)).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("slivers barely move the spectrum: L phi = lambda M phi of a gridded box with and without them") {
  const Mesh clean = sliver_test::grid_box(1, 1, 2, 4);
  Mesh slivers = clean;
  for (int k = 0; k < 4; ++k) sliver_test::add_sliver(slivers, 7 + 29 * k);
  const MeshValidation v = validate_mesh(slivers);
  REQUIRE(v.valid());
  REQUIRE(v.zero_area_faces == 4);
  auto spectrum = [](const Mesh& m) {
    const Eigen::MatrixXd L(cotan_laplacian(m.V, m.F));
    const Eigen::MatrixXd M = lumped_mass(m.V, m.F).asDiagonal();
    return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(L, M, Eigen::EigenvaluesOnly).eigenvalues();
  };
  const Eigen::VectorXd a = spectrum(clean), b = spectrum(slivers);
  CHECK(std::fabs(b(0)) <= 1e-9);
  // The first modes of the box (2 x 2 x 4 grid cells per unit) within 1% of each other.
  for (int i = 1; i < 10; ++i) {
    CAPTURE(i);
    CHECK(b(i) == doctest::Approx(a(i)).epsilon(1e-2));
  }
}
