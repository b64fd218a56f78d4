// verify_offsets (cavity/verify_offsets.h) on a box-shaped cavity inside a box, where every figure
// is known: the cavity's closedness count against hand-counted defects (a missing face leaves 3
// directed edges without their opposite; a duplicated face uses 3 edges twice one way; a flipped
// face leaves 3 edges used twice one way and never the other, 3 each), the wall against the
// analytic 3, a goal-only check that measures no validity, and a moved outer surface's new
// self-intersections against hand-placed crossing boxes.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "../mass/geometry_checks.h"
#include "cavity/verify_offsets.h"
#include "geometry/bvh.h"
#include "geometry/closest_point.h"
#include "geometry/intersecting_faces.h"
#include "mesh/primitives.h"

using namespace offsetopt;

namespace {

Mesh drop_face(const Mesh& m, Eigen::Index f) {
  Mesh out = m;
  out.F.resize(m.F.rows() - 1, 3);
  for (Eigen::Index r = 0, w = 0; r < m.F.rows(); ++r)
    if (r != f) out.F.row(w++) = m.F.row(r);
  return out;
}

Verification check_cavity(const Mesh& outer, const Mesh& inner, bool goal_only = false) {
  VerifyInput in;
  in.outer = &outer;
  in.inner = &inner;
  in.goal.kind = GoalKind::volume;
  in.goal.target_volume = 64.0;
  in.diagonal = std::sqrt(300.0);
  in.wall = 1.0;
  in.threads = 1;
  in.goal_only = goal_only;
  return verify_offsets(in);
}

}  // namespace

TEST_CASE("verify_offsets counts a box cavity's unmatched edges and measures its wall") {
  const Mesh outer = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, 10));
  const Mesh inner = make_box(Eigen::Vector3d(3, 3, 3), Eigen::Vector3d(7, 7, 7));

  const Verification closed = check_cavity(outer, inner);
  CHECK(closed.goal_met);
  CHECK(closed.valid);
  REQUIRE(closed.validity.has_value());
  CHECK(closed.validity->cavity_unmatched_edges == 0);
  REQUIRE(closed.validity->min_wall_measured.has_value());
  CHECK(*closed.validity->min_wall_measured == doctest::Approx(3.0).epsilon(1e-12));

  const Verification open = check_cavity(outer, drop_face(inner, 0));
  CHECK_FALSE(open.valid);
  CHECK(open.validity->cavity_unmatched_edges == 3);

  Mesh doubled = inner;
  doubled.F.conservativeResize(inner.F.rows() + 1, 3);
  doubled.F.row(inner.F.rows()) = inner.F.row(0);
  CHECK(check_cavity(outer, doubled).validity->cavity_unmatched_edges == 3);

  Mesh flipped = inner;
  std::swap(flipped.F(0, 1), flipped.F(0, 2));
  CHECK(check_cavity(outer, flipped).validity->cavity_unmatched_edges == 9);

  const Verification goal_only = check_cavity(outer, drop_face(inner, 0), true);
  CHECK_FALSE(goal_only.validity.has_value());
  CHECK_FALSE(goal_only.valid);
}

namespace {

// Boxes A = [0, 10]^3, B and C (1 by 0.6 by 1) as one mesh of three shells. A box standing
// through A's top face (z = 10) crosses it with its 4 sides, 8 triangles, each with an edge through
// the one top triangle it lies over (B and C each stay on one side of either diagonal of the top).
Mesh three_boxes(double b_z, double c_z) {
  const Mesh parts[3] = {make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 10, 10)),
                         make_box(Eigen::Vector3d(1, 4.2, b_z), Eigen::Vector3d(2, 4.8, b_z + 1)),
                         make_box(Eigen::Vector3d(8, 5.2, c_z), Eigen::Vector3d(9, 5.8, c_z + 1))};
  Mesh out;
  out.V.resize(24, 3);
  out.F.resize(36, 3);
  for (int p = 0; p < 3; ++p) {
    out.V.middleRows(8 * p, 8) = parts[p].V;
    out.F.middleRows(12 * p, 12) = parts[p].F.array() + 8 * p;
  }
  return out;
}

}  // namespace

TEST_CASE("verify_offsets counts a moved outer surface's self-intersections that the input lacked, pair by pair") {
  const Mesh input = three_boxes(9.5, 12.0);  // B crosses A's top: 8 pairs, the input's own
  const Mesh moved = three_boxes(12.0, 9.5);  // B lifted clear, C lowered through: 8 other pairs
  REQUIRE(test::self_intersections(input) == 8);
  REQUIRE(test::self_intersections(moved) == 8);
  const std::vector<std::pair<int, int>> own = self_intersections(TriangleBvh(input.V, input.F), 1000).pairs;
  REQUIRE(own.size() == 8);
  const Mesh inner = make_box(Eigen::Vector3d(3, 3, 3), Eigen::Vector3d(7, 7, 7));
  VerifyInput in;
  in.inner = &inner;
  in.goal.kind = GoalKind::volume;
  in.goal.target_volume = 64.0;
  in.diagonal = std::sqrt(300.0);
  in.wall = 1.0;
  in.threads = 1;
  in.outer_own_pairs = &own;

  in.outer = &moved;  // the same count as the input's, none of its pairs: 8 new
  const Verification crossed = verify_offsets(in);
  REQUIRE(crossed.validity);
  CHECK(crossed.validity->outer_new_self_intersections == 8);
  CHECK(crossed.validity->outer_own_self_intersections == 0);
  CHECK_FALSE(crossed.valid);

  in.outer = &input;  // unmoved: every pair is the input's own
  const Verification kept = verify_offsets(in);
  CHECK(kept.validity->outer_new_self_intersections == 0);
  CHECK(kept.validity->outer_own_self_intersections == 8);
  CHECK(kept.valid);

  in.outer_own_pairs = nullptr;  // the outer surface is the input: not searched
  CHECK_FALSE(verify_offsets(in).validity->outer_new_self_intersections.has_value());
}

TEST_CASE("find_surface_defects' wall scan in ranges: every vertex's closest point, the thinnest by lowest index") {
  // An off-centre sphere in a sphere: walls from 1.3 to 4.7, thinnest near one pole, and a
  // threshold that makes a few hundred vertices thin; above the split's size (1024 vertices).
  const Mesh outer = make_icosphere(10.0, 4);
  Mesh inner = make_icosphere(7.0, 4);
  inner.V.col(0).array() += 1.7;
  const TriangleBvh bvh(outer.V, outer.F);
  const double thin_below = 2.0;
  double thinnest = std::numeric_limits<double>::infinity();
  int thinnest_vertex = -1;
  std::vector<int> thin;
  auto measure_every_vertex = [&] {
    thinnest = std::numeric_limits<double>::infinity();
    thinnest_vertex = -1;
    thin.clear();
    for (Eigen::Index i = 0; i < inner.V.rows(); ++i) {
      const double d = closest_point(bvh, inner.V.row(i).transpose()).distance;
      if (d < thinnest) {
        thinnest = d;
        thinnest_vertex = static_cast<int>(i);
      }
      if (d < thin_below) thin.push_back(static_cast<int>(i));
    }
  };
  measure_every_vertex();
  // The thinnest vertex (in the second half) copied to the first place: an exact tie across the
  // ranges the scan is cut into, which the lower index wins.
  const int first_thinnest = thinnest_vertex;
  REQUIRE(first_thinnest >= inner.V.rows() / 2);
  inner.V.row(0) = inner.V.row(first_thinnest);
  measure_every_vertex();
  CHECK(thinnest_vertex == 0);
  CHECK(std::find(thin.begin(), thin.end(), first_thinnest) != thin.end());
  REQUIRE(inner.V.rows() >= 1024);
  REQUIRE(thin.size() > 50);
  REQUIRE(thin.size() < static_cast<std::size_t>(inner.V.rows()) / 2);
  for (const int threads : {1, 2}) {
    CAPTURE(threads);
    const SurfaceDefects d = find_surface_defects(outer, inner, {}, {}, thin_below, threads);
    CHECK(d.thinnest_wall == thinnest);
    CHECK(d.thinnest_vertex == thinnest_vertex);
    CHECK(d.thin_wall_vertices == thin);
    // A threshold below every wall (the verification's usual case): only the thinnest is kept,
    // and the pruning radius is the thinnest so far.
    const SurfaceDefects thick = find_surface_defects(outer, inner, {}, {}, 0.5 * thinnest, threads);
    CHECK(thick.thinnest_wall == thinnest);
    CHECK(thick.thinnest_vertex == thinnest_vertex);
    CHECK(thick.thin_wall_vertices.empty());
  }
}

TEST_CASE("find_surface_defects from an earlier scan's bounds: the walls of the moved surfaces as measuring every vertex finds them") {
  // The off-centre sphere pair above, scanned once recording its bounds; then the inner surface
  // is moved by at most delta per coordinate (as rounding for output moves it, only more) so that
  // the second-thinnest vertex becomes the thinnest, and the moved pair is scanned from the
  // recorded bounds with the slack such a move allows (2√3 delta: the vertex and the surface
  // point each move at most √3 delta).
  // Vertex 0 is made a thinnest one, so the scan's seed (vertex 0 among its samples) is the
  // thinnest wall and every range prunes at it from its first vertex: a bound taken without its
  // slack would skip the runner-up.
  const Mesh outer = make_icosphere(10.0, 4);
  Mesh inner = make_icosphere(7.0, 4);
  inner.V.col(0).array() += 1.7;
  const TriangleBvh bvh(outer.V, outer.F);
  std::vector<double> distance(static_cast<std::size_t>(inner.V.rows()));
  auto measure = [&] {
    for (Eigen::Index i = 0; i < inner.V.rows(); ++i)
      distance[static_cast<std::size_t>(i)] = closest_point(bvh, inner.V.row(i).transpose()).distance;
  };
  measure();
  inner.V.row(0) = inner.V.row(std::min_element(distance.begin(), distance.end()) - distance.begin());
  measure();
  std::vector<int> order(distance.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::make_pair(distance[static_cast<std::size_t>(a)], a) < std::make_pair(distance[static_cast<std::size_t>(b)], b);
  });
  const int thinnest = order[0];
  int runner_up = -1;  // the nearest vertex clearly farther than the thinnest (symmetric ones tie)
  for (const int v : order)
    if (distance[static_cast<std::size_t>(v)] > distance[static_cast<std::size_t>(thinnest)] + 1e-6) {
      runner_up = v;
      break;
    }
  REQUIRE(runner_up >= 0);
  const double gap = distance[static_cast<std::size_t>(runner_up)] - distance[static_cast<std::size_t>(thinnest)];
  REQUIRE(gap > 0.0);
  const double delta = 2.0 * gap;  // per coordinate: brings the runner-up nearer than the thinnest
  const double slack = 2.0 * std::sqrt(3.0) * delta;

  for (const double thin_below : {2.0, 0.5 * distance[static_cast<std::size_t>(thinnest)]}) {
    for (const int threads : {1, 2}) {
      CAPTURE(thin_below);
      CAPTURE(threads);
      std::vector<double> lower;
      WallBounds record;
      record.record = &lower;
      const SurfaceDefects before = find_surface_defects(outer, inner, {}, {}, thin_below, threads, nullptr, nullptr, nullptr, record);
      REQUIRE(thinnest == 0);
      CHECK(before.thinnest_vertex == thinnest);
      REQUIRE(lower.size() == distance.size());
      for (std::size_t i = 0; i < lower.size(); ++i) CHECK(lower[i] <= distance[i] * (1.0 + 1e-12));

      // The runner-up towards its closest outer point by delta per coordinate, and every tenth
      // vertex (not vertex 0) away from it by delta/2.
      Mesh moved = inner;
      for (Eigen::Index i = 0; i < moved.V.rows(); ++i) {
        const Eigen::Vector3d p = inner.V.row(i).transpose();
        const Eigen::Vector3d towards = closest_point(bvh, p).point - p;
        const double step = i == runner_up ? delta : i % 10 == 5 ? -0.5 * delta : 0.0;
        for (int c = 0; c < 3; ++c) moved.V(i, c) += step * (towards(c) > 0.0 ? 1.0 : towards(c) < 0.0 ? -1.0 : 0.0);
      }
      double moved_thinnest = std::numeric_limits<double>::infinity();
      int moved_vertex = -1;
      std::vector<int> moved_thin;
      for (Eigen::Index i = 0; i < moved.V.rows(); ++i) {
        const double d = closest_point(bvh, moved.V.row(i).transpose()).distance;
        if (d < moved_thinnest) {
          moved_thinnest = d;
          moved_vertex = static_cast<int>(i);
        }
        if (d < thin_below) moved_thin.push_back(static_cast<int>(i));
      }
      REQUIRE(moved_vertex == runner_up);  // the bounds had a winner to miss

      WallBounds known;
      known.known = &lower;
      known.slack = slack;
      const SurfaceDefects after = find_surface_defects(outer, moved, {}, {}, thin_below, threads, nullptr, nullptr, nullptr, known);
      CHECK(after.thinnest_wall == moved_thinnest);
      CHECK(after.thinnest_vertex == runner_up);
      CHECK(after.thin_wall_vertices == moved_thin);
    }
  }
}
