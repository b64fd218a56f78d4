// The coarse copy (decimate_mesh) stays a closed 2-manifold of input vertices close to the input
// surface, and the coarse-to-fine contraction carries the coarse skeleton back to every vertex:
// a torus still reaches its core circle, and the vertices agree with the full contraction's.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "mesh/primitives.h"
#include "skeleton/coarse_copy.h"
#include "skeleton/decimate_mesh.h"
#include "skeleton/laplacian_contraction.h"

using namespace offsetopt;

namespace {

double signed_volume(const Vertices& V, const Faces& F) {
  double v = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

// Every undirected edge in exactly two faces, once in each direction (closed and oriented).
bool closed_and_oriented(const Faces& F) {
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      if (a == b) return false;
      ++directed[{a, b}];
    }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto back = directed.find({edge.second, edge.first});
    if (back == directed.end() || back->second != 1) return false;
  }
  return true;
}

// Every vertex's faces form one fan: following "next corner -> previous corner" around the vertex
// visits all of its faces in one cycle (no pinched vertex, which closed_and_oriented misses).
bool one_fan_per_vertex(const Faces& F, Eigen::Index vertices) {
  std::vector<std::map<int, int>> turn(static_cast<std::size_t>(vertices));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      auto& around = turn[static_cast<std::size_t>(F(f, c))];
      if (!around.emplace(F(f, (c + 1) % 3), F(f, (c + 2) % 3)).second) return false;
    }
  for (const auto& around : turn) {
    if (around.size() < 3) return false;
    int at = around.begin()->first;
    std::size_t steps = 0;
    do {
      const auto next = around.find(at);
      if (next == around.end()) return false;
      at = next->second;
      ++steps;
    } while (at != around.begin()->first && steps <= around.size());
    if (steps != around.size()) return false;
  }
  return true;
}

// A bottle-like solid: flat caps with sharp rims (costly collapses next to free ones), a long
// smooth body, and a radial wobble so that no two edges cost the same.
Mesh wobbly_cylinder() {
  Mesh m = make_cylinder(1.0, 0.0, 4.0, 96, 80, 12);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const double scale = 1.0 + 0.05 * std::sin(7.0 * m.V(i, 2) + 3.0 * std::atan2(m.V(i, 1), m.V(i, 0)));
    m.V(i, 0) *= scale;
    m.V(i, 1) *= scale;
  }
  return m;
}

void check_invariants(const Mesh& input, const DecimatedMesh& d, Eigen::Index expected_vertices, int genus) {
  CHECK(d.mesh.V.rows() == expected_vertices);
  CHECK(d.mesh.F.rows() == 2 * d.mesh.V.rows() - 4 + 4 * genus);  // Euler characteristic kept
  CHECK(closed_and_oriented(d.mesh.F));
  CHECK(one_fan_per_vertex(d.mesh.F, d.mesh.V.rows()));
  REQUIRE(d.coarse_vertex.size() == static_cast<std::size_t>(input.V.rows()));
  Eigen::Index kept = 0;
  for (int c : d.coarse_vertex) kept += c >= 0 ? 1 : 0;
  CHECK(kept == d.mesh.V.rows());
  for (std::size_t k = 0; k < d.input_vertex.size(); ++k) {
    CHECK(d.coarse_vertex[static_cast<std::size_t>(d.input_vertex[k])] == static_cast<int>(k));
    CHECK((d.mesh.V.row(static_cast<Eigen::Index>(k)) - input.V.row(d.input_vertex[k])).norm() == 0.0);
  }
}

}  // namespace

TEST_CASE("decimate_mesh's rounds keep a closed 2-manifold of input vertices, of the count asked, on a solid with rims") {
  const Mesh m = wobbly_cylinder();
  for (const int target : {4000, 1500, 300}) {
    CAPTURE(target);
    const DecimatedMesh d = decimate_mesh(m.V, m.F, target);
    check_invariants(m, d, target, 0);
    CHECK(signed_volume(d.mesh.V, d.mesh.F) > 0.0);
  }
  // Asked for fewer than any allowed collapse can reach: it stops at a closed manifold of at least 4.
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const DecimatedMesh small = decimate_mesh(box.V, box.F, 1);
  CHECK(small.mesh.V.rows() >= 4);
  CHECK(closed_and_oriented(small.mesh.F));
  CHECK(one_fan_per_vertex(small.mesh.F, small.mesh.V.rows()));
}

TEST_CASE("decimate_mesh keeps a closed oriented manifold of input vertices near the surface") {
  const double R = 2.0;
  const Mesh m = make_icosphere(R, 5);  // 10,242 vertices
  const DecimatedMesh d = decimate_mesh(m.V, m.F, 1000);
  CHECK(d.mesh.V.rows() == 1000);
  // Euler characteristic of a sphere: V - E + F = 2 with E = 3F/2.
  CHECK(d.mesh.F.rows() == 2 * d.mesh.V.rows() - 4);
  CHECK(closed_and_oriented(d.mesh.F));
  for (std::size_t k = 0; k < d.input_vertex.size(); ++k) {
    CHECK(d.coarse_vertex[static_cast<std::size_t>(d.input_vertex[k])] == static_cast<int>(k));
    CHECK((d.mesh.V.row(static_cast<Eigen::Index>(k)) - m.V.row(d.input_vertex[k])).norm() == 0.0);
  }
  // 1000 vertices on a sphere: the inscribed polyhedron keeps most of the ball's volume.
  const double ball = 4.0 / 3.0 * M_PI * R * R * R;
  CHECK(signed_volume(d.mesh.V, d.mesh.F) > 0.97 * ball);
  // A function of the mesh alone.
  const DecimatedMesh again = decimate_mesh(m.V, m.F, 1000);
  CHECK(again.input_vertex == d.input_vertex);
  CHECK(again.mesh.F == d.mesh.F);
}

TEST_CASE("decimate_mesh keeps the genus of a torus") {
  const Mesh m = make_torus(3.0, 1.0, 96, 32);
  const DecimatedMesh d = decimate_mesh(m.V, m.F, 600);
  CHECK(d.mesh.V.rows() == 600);
  CHECK(d.mesh.F.rows() == 2 * d.mesh.V.rows());  // V - E + F = 0
  CHECK(closed_and_oriented(d.mesh.F));
  check_invariants(m, d, 600, 1);
}

TEST_CASE("coarse-to-fine contraction: a torus reaches its core circle, close to the full contraction") {
  const double R = 3.0, r_tube = 1.0;
  const Mesh m = make_torus(R, r_tube, 192, 48);  // 9,216 vertices
  ContractionOptions full;
  full.coarse_above = 0;
  ContractionOptions coarse;
  coarse.coarse_above = 5000;
  coarse.coarse_vertices = 2000;
  const ContractionResult a = laplacian_contraction(m.V, m.F, full);
  const ContractionResult b = laplacian_contraction(m.V, m.F, coarse);
  CHECK(a.contracted_vertices == m.V.rows());
  CHECK(b.contracted_vertices == 2000);
  CHECK(b.status == ContractionStatus::volume_ratio_reached);
  REQUIRE(b.V.rows() == m.V.rows());
  CHECK(b.V.allFinite());
  double worst_core = 0.0, worst_gap = 0.0;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    worst_core = std::max(worst_core, std::hypot(std::hypot(b.V(i, 0), b.V(i, 1)) - R, b.V(i, 2)));
    worst_gap = std::max(worst_gap, (a.V.row(i) - b.V.row(i)).norm());
  }
  // The meso-skeleton stage (volume ratio 0.1) is not yet the circle: within half the tube.
  CHECK(worst_core < 0.5 * r_tube);
  CHECK(worst_gap < 0.25 * r_tube);
}

TEST_CASE("coarse_copy carries values back the same way on 1 and 3 threads, exactly at kept vertices") {
  const Mesh m = make_torus(3.0, 1.0, 192, 48);
  const CoarseCopy one = coarse_copy(m.V, m.F, 1500, 1);
  const CoarseCopy three = coarse_copy(m.V, m.F, 1500, 3);
  CHECK(one.corners == three.corners);
  CHECK(one.weights == three.weights);
  // Carrying the coarse positions back gives each kept vertex exactly and every other vertex a
  // point of the coarse surface near its own position (the torus is smooth at this sampling).
  const Eigen::MatrixXd back = carry_to_input(one, one.decimated.mesh.V);
  double worst = 0.0;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    if (one.decimated.coarse_vertex[static_cast<std::size_t>(i)] >= 0) CHECK((back.row(i) - m.V.row(i)).norm() == 0.0);
    worst = std::max(worst, (back.row(i) - m.V.row(i)).norm());
    double sum = 0.0;
    for (double w : one.weights[static_cast<std::size_t>(i)]) {
      CHECK(w >= 0.0);
      sum += w;
    }
    CHECK(std::fabs(sum - 1.0) < 1e-12);
  }
  CHECK(worst < 0.1);
}
