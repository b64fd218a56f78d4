// outer_offset_limit (shape/outer_offset_limit.h): thickening two parts that lie closer than twice
// the requested offset, and a ring whose hole is narrower than that. Without the limit the
// thickened surface intersects itself; with it (any offset between 0 and the limit) it does not.
// Crossings are counted by the independent test code (tests/mass/geometry_checks.h), not by the
// verifier's BVH search. shrink_outer_limit (shape/shrink_outer_limit.h) on a sphere.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "../mass/geometry_checks.h"
#include "../mesh_checks.h"
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

// The boundary of a set of unit cubes (cells of an nx x ny x nz grid, `solid(i, j, k)`), each
// boundary square split into two triangles, normals out: a CAD-like part with flat faces and sharp
// convex and concave creases. No two solid cells may touch along an edge only.
template <class Solid>
Mesh voxel_surface(int nx, int ny, int nz, Solid solid) {
  const auto inside = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && solid(i, j, k);
  };
  const auto node = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  Mesh mesh;
  mesh.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.V.row(node(i, j, k)) << i, j, k;
  std::vector<int> faces;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!inside(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side : {0, 1}) {
            int d[3] = {0, 0, 0};
            d[axis] = side ? 1 : -1;
            if (inside(i + d[0], j + d[1], k + d[2])) continue;
            // The square's corners in the plane across `axis`, counter-clockwise seen from outside.
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            int q[4];
            for (int c = 0; c < 4; ++c) {
              int at[3] = {i, j, k};
              at[axis] += side;
              const int cu = (c == 1 || c == 2) ? 1 : 0, cv = (c >= 2) ? 1 : 0;
              at[u] += side ? cu : cv;
              at[v] += side ? cv : cu;
              q[c] = node(at[0], at[1], at[2]);
            }
            faces.insert(faces.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
          }
      }
  mesh.F.resize(static_cast<Eigen::Index>(faces.size() / 3), 3);
  for (std::size_t f = 0; f < faces.size() / 3; ++f) mesh.F.row(static_cast<Eigen::Index>(f)) << faces[3 * f], faces[3 * f + 1], faces[3 * f + 2];
  // Drop the grid nodes no face uses.
  std::vector<int> index(static_cast<std::size_t>(mesh.V.rows()), -1);
  int used = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (index[static_cast<std::size_t>(mesh.F(f, c))] < 0) index[static_cast<std::size_t>(mesh.F(f, c))] = used++;
  Vertices kept(used, 3);
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    if (index[static_cast<std::size_t>(i)] >= 0) kept.row(index[static_cast<std::size_t>(i)]) = mesh.V.row(i);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) mesh.F(f, c) = index[static_cast<std::size_t>(mesh.F(f, c))];
  mesh.V = kept;
  return mesh;
}

}  // namespace

TEST_CASE("an engraved slot's floor keeps its thickening at the concave creases, and the slot does not close") {
  // A 6 x 6 x 3 block with a slot 2 wide, 4 long and 1 deep in its top, like an engraved letter
  // of a CAD part. The slot's floor meets its walls at right-angled concave creases, where the
  // faces across the crease are nearer to the thickened point than its height above the tangent
  // plane at every scale (0.71 of it on a crease, 0.58 in a corner): a rule comparing with that
  // height halved the creases' limits to 0 and, through the slope bound, the rim's to half a cell.
  const Mesh block = voxel_surface(6, 6, 3, [](int i, int j, int k) { return !(k == 2 && i >= 2 && i <= 3 && j >= 1 && j <= 4); });
  REQUIRE(test::closed_and_oriented(block));
  REQUIRE(test::self_intersections(block) == 0);
  Vertices normals;
  for (double requested : {0.4, 1.5}) {
    CAPTURE(requested);
    const OuterOffsetLimit limit = limits_along_normals(block, requested, normals);
    // Every vertex of the slot's floor (z = 2), creases and corners included, keeps the small
    // request whole, and a quarter of a cell of the wide one (whose free share across the 2-wide
    // slot is 1, and which, taken whole, would lift the floor over the rim).
    const double floor_least = requested < 1.0 ? requested : 0.25;
    int floor_vertices = 0;
    for (Eigen::Index i = 0; i < block.V.rows(); ++i)
      if (block.V(i, 2) == 2.0 && block.V(i, 0) >= 2.0 && block.V(i, 0) <= 4.0 && block.V(i, 1) >= 1.0 && block.V(i, 1) <= 5.0) {
        ++floor_vertices;
        CHECK(limit.limit(i) >= floor_least);
      }
    CHECK(floor_vertices == 15);
    // The thickened block does not intersect itself (the test's own crossing count).
    CHECK(test::self_intersections(thickened(block, normals, limit.limit)) == 0);
  }
  // The wide request, taken uniformly, closes the slot: its walls pass each other.
  CHECK(test::self_intersections(thickened(block, normals, Eigen::VectorXd::Constant(block.V.rows(), 1.5))) > 0);
}

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
