// Laplacian contraction: full contraction reaches the analytic skeletons of primitives (sphere
// centre, capsule/cylinder axis, torus core circle); one step equals the dense least-squares
// solution of Au et al.'s system; the normalised frame makes the result independent of units;
// collapsing and degenerate triangles do not break it.
#include <doctest/doctest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "geometry/cotan_laplacian.h"
#include "mesh/primitives.h"
#include "skeleton/laplacian_contraction.h"

using namespace offsetopt;

namespace {

// Au et al.'s own stopping rule for a full (1-D) skeleton: volume below 1e-6 of the input's.
ContractionOptions full_contraction() {
  ContractionOptions o;
  o.stop_volume_ratio = 1e-6;
  o.max_steps = 12;
  return o;
}

double max_distance_to_axis(const Vertices& V) {
  double d = 0.0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) d = std::max(d, std::hypot(V(i, 0), V(i, 1)));
  return d;
}

double signed_volume(const Vertices& V, const Faces& F) {
  double v = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

}  // namespace

TEST_CASE("an icosphere contracts to its centre") {
  const double R = 2.5;
  const Eigen::RowVector3d centre(1.0, -2.0, 0.5);
  Mesh m = make_icosphere(R, 3);
  m.V.rowwise() += centre;
  const ContractionResult r = laplacian_contraction(m.V, m.F, full_contraction());
  CHECK(r.status == ContractionStatus::volume_ratio_reached);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.V.rows(); ++i) worst = std::max(worst, (r.V.row(i) - centre).norm());
  CHECK(worst < 0.05 * R);
  CHECK(r.volume_ratio <= 1e-6);
  CHECK(r.V.allFinite());
}

TEST_CASE("a capsule and a cylinder contract to their axis, keeping its length") {
  const double radius = 1.0;
  SUBCASE("capsule") {
    const Mesh m = make_capsule(radius, 2.0, 24, 8, 12);
    const ContractionResult r = laplacian_contraction(m.V, m.F, full_contraction());
    CHECK(r.status == ContractionStatus::volume_ratio_reached);
    CHECK(max_distance_to_axis(r.V) < 0.05 * radius);
    // A curve along the axis, not a point: it keeps most of the cylinder's length (4).
    CHECK(r.V.col(2).maxCoeff() - r.V.col(2).minCoeff() > 3.0);
  }
  SUBCASE("cylinder with flat caps") {
    const Mesh m = make_cylinder(radius, -2.0, 2.0, 24, 12, 4);
    const ContractionResult r = laplacian_contraction(m.V, m.F, full_contraction());
    CHECK(r.status == ContractionStatus::volume_ratio_reached);
    CHECK(max_distance_to_axis(r.V) < 0.05 * radius);
    CHECK(r.V.col(2).maxCoeff() - r.V.col(2).minCoeff() > 2.5);
  }
}

TEST_CASE("a torus contracts to its core circle") {
  const double R = 3.0, r_tube = 1.0;
  const Mesh m = make_torus(R, r_tube, 48, 16);
  const ContractionResult r = laplacian_contraction(m.V, m.F, full_contraction());
  CHECK(r.status == ContractionStatus::volume_ratio_reached);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.V.rows(); ++i)
    worst = std::max(worst, std::hypot(std::hypot(r.V(i, 0), r.V(i, 1)) - R, r.V(i, 2)));
  CHECK(worst < 0.1 * r_tube);
}

TEST_CASE("one step equals the dense least-squares solution of the stacked system (W_L L, W_H) X = (0, W_H X_t)") {
  // A lumpy sphere so the cotangent weights are not all alike.
  Mesh m = make_icosphere(1.0, 2);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) m.V.row(i) *= 1.0 + 0.2 * m.V(i, 0) * m.V(i, 1) + 0.1 * m.V(i, 2);
  ContractionOptions o;
  o.max_steps = 1;
  o.attraction_weight = 0.7;
  const ContractionResult r = laplacian_contraction(m.V, m.F, o);
  REQUIRE(r.steps == 1);
  // Independent reference in the normalised frame: dense QR of the stacked system.
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  const double diagonal = (hi - lo).norm();
  const Vertices X = (m.V.rowwise() - 0.5 * (lo + hi)) / diagonal;
  double area = 0.0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = X.row(m.F(f, 0)), b = X.row(m.F(f, 1)), c = X.row(m.F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  const double WL = o.initial_laplacian_weight / std::sqrt(area / static_cast<double>(m.F.rows()));
  CotanOptions cotan;
  cotan.sine_floor = o.cotan_sine_floor;
  const Eigen::MatrixXd L = Eigen::MatrixXd(cotan_laplacian(X, m.F, cotan));
  const Eigen::Index n = X.rows();
  Eigen::MatrixXd A(2 * n, n);
  A << WL * L, o.attraction_weight * Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd b(2 * n, 3);
  b << Eigen::MatrixXd::Zero(n, 3), o.attraction_weight * Eigen::MatrixXd(X);
  const Eigen::MatrixXd expected = A.colPivHouseholderQr().solve(b) * diagonal;
  const Eigen::MatrixXd got = (r.V.rowwise() - 0.5 * (lo + hi));
  CHECK((got - expected).cwiseAbs().maxCoeff() < 1e-9 * diagonal);
  CHECK(r.history.size() == 1);
  CHECK(r.history[0].laplacian_weight == doctest::Approx(WL));
}

TEST_CASE("the result does not depend on the model's units or position") {
  const Mesh m = make_capsule(1.0, 1.5, 16, 6, 8);
  Mesh scaled = m;
  const Eigen::RowVector3d shift(100.0, -40.0, 7.0);
  scaled.V = (m.V * 250.0).rowwise() + shift;
  const ContractionResult a = laplacian_contraction(m.V, m.F);
  const ContractionResult b = laplacian_contraction(scaled.V, scaled.F);
  CHECK(a.steps == b.steps);
  CHECK(a.volume_ratio == doctest::Approx(b.volume_ratio).epsilon(1e-9));
  const Vertices back = (b.V.rowwise() - shift) / 250.0;
  CHECK((back - a.V).cwiseAbs().maxCoeff() < 1e-9);
}

TEST_CASE("the default run stops at the meso-skeleton stage with the volume shrinking every step") {
  const Mesh m = make_torus(2.0, 0.7, 40, 16);
  const ContractionResult r = laplacian_contraction(m.V, m.F);
  CHECK(r.status == ContractionStatus::volume_ratio_reached);
  CHECK(r.volume_ratio <= ContractionOptions{}.stop_volume_ratio);
  REQUIRE(r.history.size() == static_cast<std::size_t>(r.steps));
  double previous = 1.0;
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    CHECK(r.history[k].volume_ratio < previous);
    previous = r.history[k].volume_ratio;
    if (k > 0) CHECK(r.history[k].laplacian_weight == doctest::Approx(3.0 * r.history[k - 1].laplacian_weight));
  }
  // The stop came at the first step under the threshold.
  if (r.history.size() > 1) CHECK(r.history[r.history.size() - 2].volume_ratio > ContractionOptions{}.stop_volume_ratio);
  // Reported ratios are those of the returned mesh.
  CHECK(r.volume_ratio == doctest::Approx(signed_volume(r.V, m.F) / signed_volume(m.V, m.F)).epsilon(1e-9));
  CHECK(!r.ordering.empty());
  CHECK(r.predicted_factor_flops > 0.0);
}

TEST_CASE("collapsed and sliver triangles do not break the contraction") {
  Mesh m = make_icosphere(1.0, 3);
  // Pull a few vertices onto a neighbour: zero-area triangles and zero-length edges.
  for (int k = 0; k < 5; ++k) {
    const int i = m.F(k * 37, 0), j = m.F(k * 37, 1);
    m.V.row(i) = m.V.row(j);
  }
  // Near-sliver: squash one triangle to 1e-9 of its height.
  const int a = m.F(200, 0), b = m.F(200, 1), c = m.F(200, 2);
  m.V.row(c) = 0.5 * (m.V.row(a) + m.V.row(b)) + 1e-9 * (m.V.row(c) - 0.5 * (m.V.row(a) + m.V.row(b)));
  const ContractionResult r = laplacian_contraction(m.V, m.F, full_contraction());
  CHECK(r.status != ContractionStatus::factorization_failed);
  CHECK(r.V.allFinite());
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.V.rows(); ++i) worst = std::max(worst, r.V.row(i).norm());
  CHECK(worst < 0.1);
}

TEST_CASE("degenerate input and option checks") {
  Mesh empty;
  empty.V = Vertices::Zero(3, 3);
  empty.F.resize(0, 3);
  const ContractionResult r = laplacian_contraction(empty.V, empty.F);
  CHECK(r.status == ContractionStatus::degenerate_input);
  CHECK(r.steps == 0);
  CHECK(r.V == empty.V);
  Mesh flat;  // every vertex at one point: zero bounding box
  flat.V = Vertices::Zero(4, 3);
  flat.F.resize(1, 3);
  flat.F << 0, 1, 2;
  CHECK(laplacian_contraction(flat.V, flat.F).status == ContractionStatus::degenerate_input);
  Mesh bad = make_icosphere(1.0, 1);
  bad.F(0, 0) = -1;
  CHECK_THROWS_AS(laplacian_contraction(bad.V, bad.F), std::invalid_argument);

  const Mesh good = make_icosphere(1.0, 1);
  auto rejects = [&good](auto&& change) {
    ContractionOptions o;
    change(o);
    CHECK_FALSE(o.check().empty());
    CHECK_THROWS_AS(laplacian_contraction(good.V, good.F, o), std::invalid_argument);
  };
  rejects([](ContractionOptions& o) { o.initial_laplacian_weight = 0.0; });
  rejects([](ContractionOptions& o) { o.laplacian_weight_growth = 0.5; });
  rejects([](ContractionOptions& o) { o.attraction_weight = -1.0; });
  rejects([](ContractionOptions& o) { o.stop_volume_ratio = 1.0; });
  rejects([](ContractionOptions& o) { o.max_steps = 0; });
  rejects([](ContractionOptions& o) { o.cotan_sine_floor = 0.0; });
  rejects([](ContractionOptions& o) { o.area_ratio_floor = 2.0; });
  rejects([](ContractionOptions& o) { o.threads = 0; });
  CHECK(ContractionOptions{}.check().empty());
}
