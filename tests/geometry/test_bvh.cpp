// BVH queries against brute force: closest ray hits, segment tests and point-in-solid agree with
// loops over every face (and, for inside tests, with the exact solid-angle winding number) on
// random rays and points from a fixed-seed offsetopt::Rng.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/bvh.h"
#include "geometry/point_in_solid.h"
#include "geometry/ray_cast.h"
#include "geometry/ray_triangle.h"
#include "mesh/primitives.h"
#include "util/det_math.h"
#include "util/rng.h"

using namespace offsetopt;

namespace {

Eigen::Vector3d random_unit(Rng& rng) {
  for (;;) {
    const Eigen::Vector3d d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double n = d.norm();
    if (n > 0.1 && n <= 1.0) return d / n;
  }
}

// Brute-force closest hit with t > 0 (no tolerance games: the plain Moller-Trumbore test).
double brute_force_closest(const Mesh& m, const Eigen::Vector3d& o, const Eigen::Vector3d& d, int& face) {
  double best = std::numeric_limits<double>::infinity();
  face = -1;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const RayTriangleHit h = ray_triangle(o, d, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                                          m.V.row(m.F(f, 2)).transpose(), 0.0);
    if (h.hit && h.t > 0.0 && h.t < best) {
      best = h.t;
      face = static_cast<int>(f);
    }
  }
  return best;
}

// A shape with concavities, a hole and thin parts: a torus twisted by a z-dependent rotation.
Mesh twisted_torus() {
  Mesh m = make_torus(1.0, 0.35, 48, 20);
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    double s, c;
    det_sincos(1.5 * m.V(i, 2) + 0.5 * m.V(i, 0), s, c);
    const double x = m.V(i, 0), y = m.V(i, 1);
    m.V(i, 0) = c * x - s * y;
    m.V(i, 1) = s * x + c * y;
    m.V(i, 2) *= 1.0 + 0.5 * x;
  }
  return m;
}

}  // namespace

TEST_CASE("ray-triangle hits match the plane intersection and area barycentrics") {
  Rng rng(5);
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Vector3d a(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Eigen::Vector3d b(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Eigen::Vector3d c(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const Eigen::Vector3d o(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    // Aim near the triangle so about half the rays hit.
    const Eigen::Vector3d target = a + rng.uniform(-0.3, 1.0) * (b - a) + rng.uniform(-0.3, 1.0) * (c - a);
    const Eigen::Vector3d d = (target - o).normalized();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double t = n.dot(a - o) / n.dot(d);
    const Eigen::Vector3d x = o + t * d;
    const double w1 = (c - x).cross(a - x).dot(n) / n.squaredNorm();  // barycentric of b
    const double w2 = (a - x).cross(b - x).dot(n) / n.squaredNorm();  // barycentric of c
    const bool inside = w1 >= 0 && w2 >= 0 && w1 + w2 <= 1;
    const RayTriangleHit h = ray_triangle(o, d, a, b, c, 0.0);
    REQUIRE(h.hit == inside);
    if (!inside) continue;
    ++hits;
    CHECK(h.t == doctest::Approx(t).epsilon(1e-9));
    CHECK(h.u == doctest::Approx(w1).epsilon(1e-9));
    CHECK(h.v == doctest::Approx(w2).epsilon(1e-9));
    CHECK((h.orientation > 0) == (d.dot(n) > 0));
  }
  CHECK(hits > 500);
}

TEST_CASE("every face is in exactly one leaf and node boxes contain their faces") {
  const Mesh m = twisted_torus();
  const TriangleBvh bvh(m.V, m.F);
  std::vector<int> seen(static_cast<std::size_t>(m.F.rows()), 0);
  for (int f : bvh.leaf_faces()) ++seen[static_cast<std::size_t>(f)];
  for (int count : seen) CHECK(count == 1);
  // Walk the tree: each child box lies inside its parent's.
  for (const BvhNode& node : bvh.nodes()) {
    if (node.is_leaf()) {
      for (int k = node.first; k < node.first + node.count; ++k)
        for (int c = 0; c < 3; ++c) CHECK(node.box.contains(bvh.corner(bvh.leaf_faces()[static_cast<std::size_t>(k)], c)));
    } else {
      for (int child : {node.left, node.right}) {
        const Aabb& b = bvh.nodes()[static_cast<std::size_t>(child)].box;
        CHECK((node.box.lo.array() <= b.lo.array()).all());
        CHECK((node.box.hi.array() >= b.hi.array()).all());
      }
    }
  }
}

TEST_CASE("closest ray hits agree with brute force on random rays") {
  const Mesh m = twisted_torus();
  const TriangleBvh bvh(m.V, m.F);
  Rng rng(20240501);
  int hits = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Vector3d o(rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6), rng.uniform(-0.8, 0.8));
    const Eigen::Vector3d d = random_unit(rng) * rng.uniform(0.5, 2.0);  // not unit: t scales
    int brute_face = -1;
    const double brute_t = brute_force_closest(m, o, d, brute_face);
    RayCastOptions options;
    options.tolerance = 0.0;
    const RayCastHit hit = ray_cast_closest(bvh, o, d, options);
    REQUIRE(hit.hit == (brute_face >= 0));
    if (!hit.hit) continue;
    ++hits;
    CHECK(hit.t == doctest::Approx(brute_t).epsilon(1e-12));
    CHECK(hit.face == brute_face);
    // The reported point lies on the reported face.
    const Eigen::Vector3d p = o + hit.t * d;
    const Eigen::Vector3d q = (1 - hit.u - hit.v) * bvh.corner(hit.face, 0) + hit.u * bvh.corner(hit.face, 1) + hit.v * bvh.corner(hit.face, 2);
    CHECK((p - q).norm() < 1e-12);
    // Exiting means the ray leaves through the outward face normal.
    const Eigen::Vector3d n = (bvh.corner(hit.face, 1) - bvh.corner(hit.face, 0)).cross(bvh.corner(hit.face, 2) - bvh.corner(hit.face, 0));
    CHECK(hit.exiting == (d.dot(n) > 0));
    // t_max cuts the hit off; ignoring the hit face moves to a later (or no) hit.
    options.t_max = 0.5 * hit.t;
    CHECK_FALSE(ray_cast_closest(bvh, o, d, options).hit);
    options.t_max = std::numeric_limits<double>::infinity();
    options.ignored_faces = {hit.face};
    const RayCastHit next = ray_cast_closest(bvh, o, d, options);
    if (next.hit) CHECK(next.t >= hit.t);
  }
  CHECK(hits > 100);  // the sample exercises the hit path, not only misses
}

TEST_CASE("segment tests agree with brute force") {
  const Mesh m = twisted_torus();
  const TriangleBvh bvh(m.V, m.F);
  Rng rng(77);
  int crossing = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d p(rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6), rng.uniform(-0.8, 0.8));
    const Eigen::Vector3d q = p + random_unit(rng) * rng.uniform(0.05, 1.5);
    int face = -1;
    const double t = brute_force_closest(m, p, q - p, face);
    const bool brute = face >= 0 && t <= 1.0;
    CHECK(segment_hits_mesh(bvh, p, q) == brute);
    crossing += brute;
  }
  CHECK(crossing > 30);
  CHECK(crossing < 270);
}

TEST_CASE("point in solid agrees with the exact winding number on random points") {
  const Mesh m = twisted_torus();
  const TriangleBvh bvh(m.V, m.F);
  Rng rng(4242);
  int inside = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Eigen::Vector3d p(rng.uniform(-1.6, 1.6), rng.uniform(-1.6, 1.6), rng.uniform(-0.9, 0.9));
    const double w = winding_number(m.V, m.F, p);
    // A closed mesh: the winding number is an integer away from the surface.
    REQUIRE(std::abs(w - std::round(w)) < 1e-6);
    CHECK(point_in_solid(bvh, p) == (w > 0.5));
    inside += w > 0.5;
  }
  CHECK(inside > 30);
}

TEST_CASE("point in solid survives rays through vertices and edges of structured meshes") {
  // Points on the axes and on grid-aligned lines send axis-parallel rays exactly through the
  // icosphere's and the box's vertices and edges; the probe directions avoid them.
  const Mesh sphere = make_icosphere(1.0, 3);
  const TriangleBvh bvh(sphere.V, sphere.F);
  for (double s : {-1.5, -0.99, -0.5, 0.0, 0.3, 0.999, 1.001, 2.0}) {
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      p[axis] = s;
      const bool expected = winding_number(sphere.V, sphere.F, p) > 0.5;
      CHECK(point_in_solid(bvh, p) == expected);
    }
  }
  const Mesh box = make_box({0, 0, 0}, {1, 1, 1});
  const TriangleBvh box_bvh(box.V, box.F);
  CHECK(point_in_solid(box_bvh, {0.5, 0.5, 0.5}));
  CHECK(point_in_solid(box_bvh, {0.25, 0.25, 0.25}));
  CHECK_FALSE(point_in_solid(box_bvh, {1.5, 0.5, 0.5}));
  CHECK_FALSE(point_in_solid(box_bvh, {0.5, 0.5, -0.5}));
}

TEST_CASE("empty and degenerate inputs") {
  const TriangleBvh empty;
  CHECK(empty.empty());
  CHECK_FALSE(ray_cast_closest(empty, {0, 0, 0}, {1, 0, 0}).hit);
  CHECK_FALSE(point_in_solid(empty, {0, 0, 0}));
  Mesh m = make_icosphere(1.0, 1);
  m.V(0, 0) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(TriangleBvh(m.V, m.F), std::invalid_argument);
  Mesh bad = make_icosphere(1.0, 1);
  bad.F(0, 0) = 1000;
  CHECK_THROWS_AS(TriangleBvh(bad.V, bad.F), std::invalid_argument);
  BvhOptions options;
  options.leaf_size = 0;
  CHECK(options.check() == "BvhOptions::leaf_size must be in [1, 64]");
  const Mesh good = make_icosphere(1.0, 1);
  CHECK_THROWS_AS(TriangleBvh(good.V, good.F, options), std::invalid_argument);
}

TEST_CASE("ray-cast options: check() names what is wrong") {
  CHECK(RayCastOptions{}.check().empty());
  RayCastOptions options;
  options.t_min = 2.0;
  options.t_max = 1.0;
  CHECK(options.check() == "RayCastOptions: need t_min <= t_max");
  options = RayCastOptions{};
  options.tolerance = -1e-3;
  CHECK(options.check() == "RayCastOptions::tolerance must be finite and >= 0");
  options = RayCastOptions{};
  options.ignored_faces = {3, -1};
  CHECK(options.check() == "RayCastOptions::ignored_faces must hold face numbers >= 0");
}

TEST_CASE("a tree built on two threads is the one-thread tree, node for node") {
  // Above kBvhSplitBuildFaces: a symmetric sphere (centroids tied on every axis) and the same
  // sphere jittered.
  Mesh sphere = make_icosphere(1.0, 5);
  REQUIRE(sphere.F.rows() >= kBvhSplitBuildFaces);
  Rng rng(77);
  for (int jitter = 0; jitter < 2; ++jitter) {
    if (jitter == 1)
      for (Eigen::Index i = 0; i < sphere.V.rows(); ++i)
        for (int c = 0; c < 3; ++c) sphere.V(i, c) += rng.uniform(-1e-3, 1e-3);
    BvhOptions two;
    two.threads = 2;
    const TriangleBvh serial(sphere.V, sphere.F), split(sphere.V, sphere.F, two);
    CAPTURE(jitter);
    REQUIRE(serial.nodes().size() == split.nodes().size());
    CHECK(serial.leaf_faces() == split.leaf_faces());
    int differing = 0;
    for (std::size_t n = 0; n < serial.nodes().size(); ++n) {
      const BvhNode &a = serial.nodes()[n], &b = split.nodes()[n];
      if (a.left != b.left || a.right != b.right || a.first != b.first || a.count != b.count || a.box.lo != b.box.lo ||
          a.box.hi != b.box.hi)
        ++differing;
    }
    CHECK(differing == 0);
  }
}

namespace {

// The faces below a node, in leaf order.
std::vector<int> faces_below(const TriangleBvh& bvh, int node) {
  std::vector<int> out;
  std::vector<int> stack{node};
  while (!stack.empty()) {
    const BvhNode& n = bvh.nodes()[static_cast<std::size_t>(stack.back())];
    stack.pop_back();
    if (n.is_leaf()) {
      out.insert(out.end(), bvh.leaf_faces().begin() + n.first, bvh.leaf_faces().begin() + n.first + n.count);
    } else {
      stack.push_back(n.right);
      stack.push_back(n.left);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("every split is the median split its header defines: the lower half by centroid, ties by face index") {
  // The tree is a function of the mesh alone: whatever selection the build uses, each internal
  // node's left child holds exactly the first half of its faces sorted by (centroid along the
  // longest axis of their centroids' bounds, face index), and leaves are sorted. Checked here
  // against a full sort, on a sphere large enough for long selections (centroids tied on every
  // axis) and on the same sphere with its vertices snapped to a coarse grid (ties by thousands).
  Mesh sphere = make_icosphere(1.0, 5);
  for (int variant = 0; variant < 2; ++variant) {
    if (variant == 1)
      for (Eigen::Index i = 0; i < sphere.V.rows(); ++i)
        for (int c = 0; c < 3; ++c) sphere.V(i, c) = std::round(sphere.V(i, c) * 8.0) / 8.0;
    const TriangleBvh bvh(sphere.V, sphere.F);
    std::vector<Eigen::Vector3d> centroids;
    for (int f = 0; f < static_cast<int>(sphere.F.rows()); ++f)
      centroids.push_back((bvh.corner(f, 0) + bvh.corner(f, 1) + bvh.corner(f, 2)) / 3.0);
    auto centroid = [&](int f) { return centroids[static_cast<std::size_t>(f)]; };
    int wrong = 0, splits = 0;
    for (std::size_t index = 0; index < bvh.nodes().size(); ++index) {
      const BvhNode& node = bvh.nodes()[index];
      if (node.is_leaf()) {
        if (!std::is_sorted(bvh.leaf_faces().begin() + node.first, bvh.leaf_faces().begin() + node.first + node.count)) ++wrong;
        continue;
      }
      std::vector<int> faces = faces_below(bvh, static_cast<int>(index));
      Aabb box;
      for (int f : faces) box.extend(centroid(f));
      const int axis = box.longest_axis();
      std::sort(faces.begin(), faces.end(), [&](int a, int b) {
        const double ca = centroid(a)[axis], cb = centroid(b)[axis];
        return ca < cb || (ca == cb && a < b);
      });
      std::vector<int> lower(faces.begin(), faces.begin() + static_cast<std::ptrdiff_t>(faces.size() / 2));
      std::vector<int> left = faces_below(bvh, node.left);
      std::sort(lower.begin(), lower.end());
      std::sort(left.begin(), left.end());
      if (left != lower) ++wrong;
      ++splits;
    }
    CAPTURE(variant);
    CHECK(splits > 1000);
    CHECK(wrong == 0);
  }
}
