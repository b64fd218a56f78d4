// verify_offsets (cavity/verify_offsets.h) on a box-shaped cavity inside a box, where every figure
// is known: the cavity's closedness count against hand-counted defects (a missing face leaves 3
// directed edges without their opposite; a duplicated face uses 3 edges twice one way; a flipped
// face leaves 3 edges used twice one way and never the other, 3 each), the wall against the
// analytic 3, and a goal-only check that measures no validity.
#include <doctest/doctest.h>

#include "mesh/primitives.h"
#include "cavity/verify_offsets.h"

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
