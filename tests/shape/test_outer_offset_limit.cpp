// outer_offset_limit (shape/outer_offset_limit.h): thickening two parts that lie closer than twice
// the requested offset, and a ring whose hole is narrower than that. Without the limit the
// thickened surface intersects itself; with it (any offset between 0 and the limit) it does not.
// Crossings are counted by the independent test code (tests/mass/geometry_checks.h), not by the
// verifier's BVH search. shrink_outer_limit (shape/shrink_outer_limit.h) on a sphere.
#include <doctest/doctest.h>

#include "../mass/geometry_checks.h"
#include "geometry/bvh.h"
#include "geometry/vertex_normals.h"
#include "mesh/primitives.h"
#include "shape/outer_offset_limit.h"
#include "shape/shrink_outer_limit.h"

using namespace offsetopt;

namespace {

// Two icospheres of radius 1, their centres 2 + gap apart along x, as one mesh of two shells. The
// second is nudged off the symmetry planes: the test's crossing count counts crossings through a
// face's interior only, and mirrored tessellations put every crossing on an edge.
Mesh two_spheres(double gap) {
  const Mesh one = make_icosphere(1.0, 3);
  Mesh both;
  both.V.resize(2 * one.V.rows(), 3);
  both.F.resize(2 * one.F.rows(), 3);
  both.V.topRows(one.V.rows()) = one.V;
  both.V.bottomRows(one.V.rows()) = one.V;
  both.V.bottomRows(one.V.rows()).col(0).array() += 2.0 + gap;
  both.V.bottomRows(one.V.rows()).col(1).array() += 0.0123;
  both.V.bottomRows(one.V.rows()).col(2).array() += 0.0071;
  both.F.topRows(one.F.rows()) = one.F;
  both.F.bottomRows(one.F.rows()) = one.F.array() + static_cast<int>(one.V.rows());
  return both;
}

Mesh thickened(const Mesh& mesh, const Vertices& directions, const Eigen::VectorXd& offsets) {
  Mesh out = mesh;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) out.V.row(i) += offsets(i) * directions.row(i);
  return out;
}

OuterOffsetLimit limits_along_normals(const Mesh& mesh, double requested, Vertices& normals) {
  normals = vertex_normals(mesh.V, mesh.F);
  const TriangleBvh bvh(mesh.V, mesh.F);
  OuterOffsetLimitOptions options;
  options.threads = 1;
  return outer_offset_limit(mesh, bvh, normals, normals, Eigen::VectorXd::Constant(mesh.V.rows(), requested), options);
}

}  // namespace

TEST_CASE("two spheres closer than twice the thickening: the limit keeps them apart and the far sides whole") {
  const Mesh mesh = two_spheres(0.2);
  const double requested = 0.3;
  Vertices normals;
  const OuterOffsetLimit limit = limits_along_normals(mesh, requested, normals);
  REQUIRE(test::self_intersections(mesh) == 0);
  // The uniform thickening (the request everywhere) makes the spheres overlap by 0.4.
  CHECK(test::self_intersections(thickened(mesh, normals, Eigen::VectorXd::Constant(mesh.V.rows(), requested))) > 0);
  // The limit, and any smooth fraction of it, do not intersect.
  CHECK(test::self_intersections(thickened(mesh, normals, limit.limit)) == 0);
  Eigen::VectorXd partial(mesh.V.rows());
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) partial(i) = limit.limit(i) * (0.5 + 0.25 * (mesh.V(i, 1) + mesh.V(i, 2)) / 1.0);
  CHECK(test::self_intersections(thickened(mesh, normals, partial.cwiseMax(0.0))) == 0);
  // Facing poles: at most half the gap each. Far poles (x = -1 and x = 4.2): the full request.
  Eigen::Index near_pole = 0, far_pole = 0;
  mesh.V.topRows(mesh.V.rows() / 2).col(0).maxCoeff(&near_pole);
  mesh.V.topRows(mesh.V.rows() / 2).col(0).minCoeff(&far_pole);
  CHECK(limit.limit(near_pole) <= 0.1 + 1e-12);
  CHECK(limit.limit(far_pole) == doctest::Approx(requested));
  CHECK(limit.free_limited > 0);
  CHECK((limit.limit.array() >= 0.0).all());
  CHECK((limit.limit.array() <= requested).all());
}

TEST_CASE("a ring whose hole is narrower than twice the thickening: the limit leaves the hole open") {
  // Hole radius R - r = 0.1: thickened by 0.3 along the normals the inner equator passes the axis.
  // Odd segment counts: no two sides of the hole mirror each other (see two_spheres).
  const Mesh ring = make_torus(1.0, 0.9, 47, 23);
  const double requested = 0.3;
  Vertices normals;
  const OuterOffsetLimit limit = limits_along_normals(ring, requested, normals);
  REQUIRE(test::self_intersections(ring) == 0);
  CHECK(test::self_intersections(thickened(ring, normals, Eigen::VectorXd::Constant(ring.V.rows(), requested))) > 0);
  CHECK(test::self_intersections(thickened(ring, normals, limit.limit)) == 0);
  // The outer equator (radius 1.9) is convex and far from everything: the full request.
  Eigen::Index outermost = 0;
  ring.V.col(0).maxCoeff(&outermost);
  CHECK(limit.limit(outermost) == doctest::Approx(requested));
}

TEST_CASE("outer_offset_limit: options are checked, a zero request stays zero, the slope is bounded") {
  OuterOffsetLimitOptions bad;
  bad.free_fraction = 0.0;
  CHECK_FALSE(bad.check().empty());
  CHECK(OuterOffsetLimitOptions{}.check().empty());
  const Mesh sphere = make_icosphere(1.0, 2);
  const Vertices normals = vertex_normals(sphere.V, sphere.F);
  const TriangleBvh bvh(sphere.V, sphere.F);
  Eigen::VectorXd requested = Eigen::VectorXd::Constant(sphere.V.rows(), 0.5);
  requested(0) = 0.0;
  OuterOffsetLimitOptions options;
  options.threads = 1;
  const OuterOffsetLimit limit = outer_offset_limit(sphere, bvh, normals, normals, requested, options);
  CHECK(limit.limit(0) == 0.0);
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = sphere.F(f, c), b = sphere.F(f, (c + 1) % 3);
      CHECK(std::fabs(limit.limit(a) - limit.limit(b)) <= options.slope * (sphere.V.row(a) - sphere.V.row(b)).norm() + 1e-12);
    }
}

TEST_CASE("shrink_outer_limit lowers the corners of crossing faces and their ring, and nothing far away") {
  const Mesh sphere = make_icosphere(1.0, 3);
  const Eigen::VectorXd limit = Eigen::VectorXd::Constant(sphere.V.rows(), 0.1);
  const Eigen::VectorXd shrunk = shrink_outer_limit(sphere, limit, {{0, 1}}, 0.5, 0.5);
  for (int face : {0, 1})
    for (int c = 0; c < 3; ++c) CHECK(shrunk(sphere.F(face, c)) == doctest::Approx(0.05));
  // A vertex sharing a face with a corner of face 0 (but not a corner itself) is lowered too.
  std::vector<char> corner(static_cast<std::size_t>(sphere.V.rows()), 0);
  for (int face : {0, 1})
    for (int c = 0; c < 3; ++c) corner[static_cast<std::size_t>(sphere.F(face, c))] = 1;
  int ring = 0;
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    bool touches = false;
    for (int c = 0; c < 3; ++c) touches = touches || corner[static_cast<std::size_t>(sphere.F(f, c))];
    if (touches)
      for (int c = 0; c < 3; ++c) ring += shrunk(sphere.F(f, c)) < 0.1 ? 1 : 0;
  }
  CHECK(ring > 0);
  // The antipode of face 0's first corner keeps its limit; nothing rises.
  const Eigen::Vector3d p = sphere.V.row(sphere.F(0, 0)).transpose();
  Eigen::Index far = 0;
  (sphere.V * p).minCoeff(&far);
  CHECK(shrunk(far) == 0.1);
  CHECK((shrunk.array() <= limit.array()).all());
}
