// The analytic gradients of the raw integrals and of P against central finite differences on
// randomly perturbed demo meshes, and the shell (outer minus inner) gradient's sign.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mass/mass_properties.h"
#include "mass/mass_properties_gradient.h"
#include "mass/volume_integrals.h"
#include "mass/volume_integrals_gradient.h"
#include "mass_test_helpers.h"
#include "mesh/demo_meshes.h"
#include "mesh/primitives.h"

using namespace offsetopt;
using namespace offsetopt::test;

namespace {

// Largest over the rows of max_j |analytic − fd| / max_j |analytic| on the sampled columns.
double row_relative_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& fd) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < analytic.rows(); ++k) {
    const double scale = analytic.row(k).cwiseAbs().maxCoeff();
    if (scale == 0.0) continue;
    worst = std::max(worst, (analytic.row(k) - fd.row(k)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

std::vector<Eigen::Index> sample_vertices(Eigen::Index n, int count, Rng& rng) {
  std::vector<Eigen::Index> out;
  for (int i = 0; i < count; ++i) out.push_back(static_cast<Eigen::Index>(rng.below(static_cast<std::uint64_t>(n))));
  return out;
}

}  // namespace

TEST_CASE("gradient of the raw integrals and of P matches central differences on perturbed demo meshes") {
  Rng rng(99);
  double worst_raw = 0.0, worst_P = 0.0;
  for (const auto& name : demo_mesh_names()) {
    const Mesh base = make_demo_mesh(name);
    const double diagonal = bbox_diagonal(base);
    const Mesh mesh = perturbed(base, 2e-3 * diagonal, rng);
    const Eigen::Vector3d origin = mean_vertex(mesh);
    const Eigen::MatrixXd J_raw = volume_integrals_jacobian(mesh, origin);
    const Eigen::MatrixXd J_P = mass_properties_jacobian(mesh, origin);
    const std::vector<Eigen::Index> vertices = sample_vertices(mesh.V.rows(), 24, rng);
    Eigen::MatrixXd raw_analytic(10, 3 * vertices.size()), raw_fd(10, 3 * vertices.size());
    Eigen::MatrixXd P_analytic(10, 3 * vertices.size()), P_fd(10, 3 * vertices.size());
    const double h = 1e-5 * diagonal;
    for (std::size_t s = 0; s < vertices.size(); ++s)
      for (int c = 0; c < 3; ++c) {
        const Eigen::Index column = static_cast<Eigen::Index>(3 * s) + c;
        raw_analytic.col(column) = J_raw.col(3 * vertices[s] + c);
        P_analytic.col(column) = J_P.col(3 * vertices[s] + c);
        raw_fd.col(column) = central_difference(mesh, vertices[s], c, h,
                                                [&](const Mesh& m) { return volume_integrals(m, origin).values; });
        P_fd.col(column) = central_difference(mesh, vertices[s], c, h, [&](const Mesh& m) { return mass_properties(m); });
      }
    const double raw_error = row_relative_error(raw_analytic, raw_fd), P_error = row_relative_error(P_analytic, P_fd);
    MESSAGE(name << ": FD relative error, raw integrals " << raw_error << ", P " << P_error);
    CHECK(raw_error <= 1e-6);
    CHECK(P_error <= 1e-6);
    worst_raw = std::max(worst_raw, raw_error);
    worst_P = std::max(worst_P, P_error);
  }
  MESSAGE("worst FD relative error: raw " << worst_raw << ", P " << worst_P);
}

TEST_CASE("accumulated vector-Jacobian product is the gradient of w·P, for every vertex of a small mesh") {
  Rng rng(5);
  const Mesh mesh = perturbed(make_icosphere(1.3, 1), 0.05, rng);  // 42 vertices: check them all
  Vector10d w;
  for (int k = 0; k < 10; ++k) w(k) = rng.uniform(-1.0, 1.0);
  const VolumeIntegrals integrals = volume_integrals(mesh);
  Vertices gradient = Vertices::Zero(mesh.V.rows(), 3);
  accumulate_mass_properties_gradient(mesh, integrals, w, gradient);
  Vertices fd(mesh.V.rows(), 3);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Matrix<double, 1, 1> d = central_difference(mesh, i, c, 1e-5, [&](const Mesh& m) {
        return Eigen::Matrix<double, 1, 1>(w.dot(mass_properties(volume_integrals(m, integrals.origin))));
      });
      fd(i, c) = d(0);
    }
  const double error = (gradient - fd).cwiseAbs().maxCoeff() / gradient.cwiseAbs().maxCoeff();
  MESSAGE("w·P gradient, all 126 coordinates: relative error " << error);
  CHECK(error < 1e-7);
  // The dense Jacobian agrees with the product.
  const Eigen::MatrixXd J = mass_properties_jacobian(mesh, integrals.origin);
  const Eigen::VectorXd JTw = J.transpose() * w;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int c = 0; c < 3; ++c) CHECK(JTw(3 * i + c) == doctest::Approx(gradient(i, c)).epsilon(1e-12).scale(1.0));
}

TEST_CASE("shell gradient: outer vertices with sign +1, inner vertices with sign -1") {
  Rng rng(17);
  const Mesh outer = perturbed(make_icosphere(2.0, 1), 0.05, rng);
  const Mesh inner = perturbed(transformed(make_icosphere(1.0, 1), Eigen::Matrix3d::Identity(), {0.3, -0.2, 0.4}), 0.05, rng);
  const Eigen::Vector3d origin = mean_vertex(outer);
  Vector10d w;
  for (int k = 0; k < 10; ++k) w(k) = rng.uniform(-1.0, 1.0);
  auto shell_value = [&](const Mesh& o, const Mesh& in) {
    return w.dot(mass_properties(subtract(volume_integrals(o, origin), volume_integrals(in, origin))));
  };
  const VolumeIntegrals shell = subtract(volume_integrals(outer, origin), volume_integrals(inner, origin));
  Vertices g_outer = Vertices::Zero(outer.V.rows(), 3), g_inner = Vertices::Zero(inner.V.rows(), 3);
  accumulate_mass_properties_gradient(outer, shell, w, g_outer, +1.0);
  accumulate_mass_properties_gradient(inner, shell, w, g_inner, -1.0);
  double error = 0.0;
  for (Eigen::Index i = 0; i < inner.V.rows(); i += 3)
    for (int c = 0; c < 3; ++c) {
      const double h = 1e-5;
      auto fd_of = [&](const Mesh& moved_outer, const Mesh& moved_inner) { return shell_value(moved_outer, moved_inner); };
      Mesh o = outer, in = inner;
      o.V(i, c) += h;
      const double op = fd_of(o, inner);
      o.V(i, c) -= 2 * h;
      const double om = fd_of(o, inner);
      in.V(i, c) += h;
      const double ip = fd_of(outer, in);
      in.V(i, c) -= 2 * h;
      const double im = fd_of(outer, in);
      error = std::max(error, std::fabs((op - om) / (2 * h) - g_outer(i, c)) / g_outer.cwiseAbs().maxCoeff());
      error = std::max(error, std::fabs((ip - im) / (2 * h) - g_inner(i, c)) / g_inner.cwiseAbs().maxCoeff());
    }
  MESSAGE("shell gradient: relative error " << error);
  CHECK(error < 1e-7);
}

TEST_CASE("directional Jacobian equals the dense Jacobian contracted with one direction per vertex") {
  Mesh mesh = make_demo_mesh("top");
  Rng rng(11);
  Vertices directions(mesh.V.rows(), 3);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    directions.row(i) = Eigen::RowVector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
  const Eigen::Vector3d origin = mean_vertex(mesh);
  const Eigen::MatrixXd dense = volume_integrals_jacobian(mesh, origin);
  const Eigen::Matrix<double, 10, Eigen::Dynamic> J = volume_integrals_directional_jacobian(mesh, origin, directions);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    for (int k = 0; k < 10; ++k) {
      const double expected = dense(k, 3 * i) * directions(i, 0) + dense(k, 3 * i + 1) * directions(i, 1) +
                              dense(k, 3 * i + 2) * directions(i, 2);
      const double scale = dense.row(k).cwiseAbs().maxCoeff();
      worst = std::max(worst, std::fabs(J(k, i) - expected) / scale);
    }
  CHECK(worst < 1e-12);
}

TEST_CASE("fused integrals and directional Jacobian (10, 4 or 1 rows) are bit-identical to the two separate passes") {
  // Origins: an arbitrary one, +0 (the kernel skips subtracting it; the mesh is moved off the
  // origin so the coordinates are not small) and −0 (subtracted, as x − (−0) turns −0 into +0).
  const Eigen::Vector3d origins[] = {{1.5, -2.0, 3.0}, {0.0, 0.0, 0.0}, {-0.0, 0.0, 0.0}};
  for (const char* name : {"top", "bottle"}) {
    CAPTURE(name);
    Mesh mesh = make_demo_mesh(name);
    mesh.V.col(0).array() += 0.75;
    mesh.V(0, 1) = -0.0;  // a signed zero coordinate
    Rng rng(12);
    Vertices directions(mesh.V.rows(), 3);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
      directions.row(i) = Eigen::RowVector3d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    for (const Eigen::Vector3d& origin : origins) {
      CAPTURE(origin.transpose());
      const Vector10d separate = volume_integrals(mesh, origin).values;
      const Eigen::Matrix<double, 10, Eigen::Dynamic> separate_J =
          volume_integrals_directional_jacobian(mesh, origin, directions);
      for (int rows : {10, 4, 1})
        for (int integral_count : {10, 4, 1}) {
          CAPTURE(rows);
          CAPTURE(integral_count);
          Vector10d integrals;
          Eigen::MatrixXd J;
          volume_integrals_and_directional_jacobian(mesh.V, mesh.F, origin, directions, integrals, J, rows,
                                                    integral_count);
          // The integrals summed: the largest of 1, 4, 10 not above max(rows, count); the others NaN.
          const int wanted = std::max(rows, integral_count);
          const int summed = wanted >= 10 ? 10 : (wanted >= 4 ? 4 : 1);
          for (int k = 0; k < 10; ++k) {
            CAPTURE(k);
            if (k < summed)
              CHECK(integrals(k) == separate(k));
            else
              CHECK(std::isnan(integrals(k)));
          }
          REQUIRE(J.rows() == rows);
          REQUIRE(J.cols() == separate_J.cols());
          CHECK((J.array() == separate_J.topRows(rows).array()).all());
          // A caller that keeps the matrix at +0 between passes gets the same Jacobian without the
          // clearing; a wrong shape is cleared anyway.
          J.setZero();
          Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Constant(2, 3, 7.0);
          Vector10d again, again_wrong;
          volume_integrals_and_directional_jacobian(mesh.V, mesh.F, origin, directions, again, J, rows,
                                                    integral_count, true);
          volume_integrals_and_directional_jacobian(mesh.V, mesh.F, origin, directions, again_wrong, wrong_shape, rows,
                                                    integral_count, true);
          CHECK((J.array() == separate_J.topRows(rows).array()).all());
          CHECK((wrong_shape.array() == separate_J.topRows(rows).array()).all());
          for (int k = 0; k < summed; ++k) CHECK(again(k) == separate(k));
        }
    }
  }
}
