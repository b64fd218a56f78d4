// The reachability stage in the pipeline (optimize/reachability_stage.h): a leaning cylinder whose
// centre of mass no void can bring over its base is refused at once (exit 3 material: goal not
// met, the input written as it is) with the shortfall in input units, which is at least what the
// geometry alone allows (the carvable cylinder leans as far as the solid); an upright cylinder is
// reachable, and the lowest centre of mass any void reaches lies between the closed forms for the
// carvable cylinder shrunk by the grid's two error bounds. A leaning funnel (narrow at the ground)
// is refused with a flat base among the remedies, and cut at the height named it stands, verified.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "geometry/flatten_base.h"
#include "mass/mass_properties.h"
#include "mesh/primitives.h"
#include "optimize/offset_optimization.h"
#include "optimize/reachability_stage.h"

using namespace offsetopt;

namespace {

// Cylinder of radius 1 from z = 0 to 10, sheared x += lean · z.
Mesh leaning_cylinder(double lean) {
  Mesh m = make_cylinder(1.0, 0.0, 10.0, 32, 20, 4);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) m.V(v, 0) += lean * m.V(v, 2);
  return m;
}

// A funnel standing on its narrow end: radius 0.3 + 0.4 z from z = 0 to 3, sheared x += lean · z.
Mesh leaning_funnel(double lean) {
  std::vector<std::pair<double, double>> profile{{0.0, 0.0}};
  for (int i = 0; i <= 12; ++i) profile.emplace_back(0.3 + 0.4 * (3.0 * i / 12.0), 3.0 * i / 12.0);
  profile.emplace_back(0.0, 3.0);
  Mesh m = make_revolution(profile, 32);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) m.V(v, 0) += lean * m.V(v, 2);
  return m;
}

}  // namespace

TEST_CASE("reachability stage: a leaning cylinder is refused before the solve, with the shortfall") {
  const Mesh mesh = leaning_cylinder(1.0);
  OptimizeOptions options;
  options.goal = GoalKind::stand;
  const OptimizeResult r = optimize_offsets(mesh, options);
  REQUIRE(r.status == OptimizeStatus::goal_not_met);
  REQUIRE(r.reachability);
  CHECK(!r.reachability->reachable);
  CHECK(r.reachability->decided);
  CHECK(r.message.find("no void can reach this") == 0);
  CHECK(r.message.find("outside support edge") != std::string::npos);
  // Any solid made by carving a sheared cylinder keeps its centre at x = lean · cz over the base,
  // and cz >= the height of the wall-thick floor's own centroid > 0: more than the base's radius 1
  // away once cz > 1 (the solid's own cz is 5). The best any void reaches is at least that far out.
  REQUIRE(r.reachability->best_margin_upper);
  CHECK(*r.reachability->best_margin_upper < -0.5);
  // The generous reading holds every void of the mid one: its bound is never below the mid best.
  if (r.reachability->best_margin) CHECK(*r.reachability->best_margin_upper >= *r.reachability->best_margin);
  CHECK(r.printable.F.rows() == mesh.F.rows());  // nothing carved
  CHECK(r.reachability->certificate);
  CHECK(r.before.self_intersecting_pairs == 0);

  // A refusal's report counts the input's own crossings as every report does: the count the input
  // boundary found (meshio/load_input) is carried, not dropped.
  options.input_self_intersections = SelfIntersectionReport{};
  options.input_self_intersections->pairs = 7;
  const OptimizeResult told = optimize_offsets(mesh, options);
  REQUIRE(told.status == OptimizeStatus::goal_not_met);
  CHECK(told.before.self_intersecting_pairs == 7);

  // With two threads the programme runs beside the solve, which it stops: the refusal is the same.
  options.input_self_intersections.reset();
  for (int threads : {1, 2}) {
    CAPTURE(threads);
    options.threads = threads;
    const OptimizeResult again = optimize_offsets(mesh, options);
    REQUIRE(again.status == OptimizeStatus::goal_not_met);
    REQUIRE(again.reachability);
    CHECK(again.message == r.message);
    CHECK(again.reachability->best_margin_upper == r.reachability->best_margin_upper);
    CHECK(again.printable.V == r.printable.V);
  }
}

TEST_CASE("reachability stage: an upright cylinder is reachable, its lowest centre of mass between closed forms") {
  const Mesh mesh = make_cylinder(3.0, 0.0, 10.0, 48, 24, 8);
  ReachabilityStageInput in;
  in.input = &mesh;
  in.goal.kind = GoalKind::stand;
  in.goal.margin = 0.02;
  for (int i = 0; i < 48; ++i) {
    const double a = 2.0 * 3.14159265358979 * i / 48.0;
    in.goal.support_polygon.emplace_back(3.0 * std::cos(a), 3.0 * std::sin(a));
  }
  in.wall = 0.3;
  in.outer_max = 0.6;
  in.ground_tol = 0.01;
  const ReachabilitySummary s = reachability_stage(in);
  CHECK(s.reachable);
  CHECK(s.decided);
  REQUIRE(s.lowest_cz);
  // The lowest centre: carve the carvable cylinder (radius R − s, from s to 10 − s) above the final
  // centre z*, which solves z* = cz(z*). The stage reads the mid cells (centres a wall deep): they
  // lie in the cylinder shrunk by wall − r and cover the one shrunk by wall + r (r = √3 h / 2, half
  // a cell's diagonal, h = wall / 1.5), on a 48-gon whose radius is between 3 cos(π/48) and 3.
  const Vector10d P = mass_properties(mesh);
  auto lowest = [&](double radius, double shrink) {
    const double area = 3.14159265358979 * (radius - shrink) * (radius - shrink), top = 10.0 - shrink;
    double z = P(kCz);
    for (int i = 0; i < 200; ++i) z = (P(kMass) * P(kCz) - area * 0.5 * (top * top - z * z)) / (P(kMass) - area * (top - z));
    return z;
  };
  const double r = 0.5 * std::sqrt(3.0) * 0.2;
  CHECK(*s.lowest_cz >= lowest(3.0, 0.3 - r) - 1e-9);
  CHECK(*s.lowest_cz <= lowest(3.0 * std::cos(3.14159265358979 / 48.0), 0.3 + r) + 1e-9);
  CHECK(s.remedies.empty());
}

TEST_CASE("reachability stage: a leaning funnel is refused with --flatten H, and cut at H it stands") {
  const Mesh mesh = leaning_funnel(0.5);
  OptimizeOptions options;
  options.goal = GoalKind::stand;
  options.wall = 0.1;  // 1.6% of the diagonal: a coarser programme than the default, as decisive
  const OptimizeResult refused = optimize_offsets(mesh, options);
  REQUIRE(refused.status == OptimizeStatus::goal_not_met);
  REQUIRE(refused.reachability);
  CHECK(refused.reachability->decided);
  const ReachabilityRemedy* flat = nullptr;
  for (const ReachabilityRemedy& remedy : refused.reachability->remedies)
    if (remedy.option.rfind("--flatten ", 0) == 0) flat = &remedy;
  REQUIRE(flat);
  CHECK(flat->reachable);
  CHECK(refused.message.find(flat->option) != std::string::npos);
  // The remedy as the user types it: the base cut at H, the goal met on the written solid.
  const double height = std::strtod(flat->option.c_str() + 10, nullptr);
  CHECK(height > 0.0);
  CHECK(height <= 0.75);  // at most a quarter of the height is searched
  FlattenOptions cut;
  cut.height = height;
  const FlattenResult flattened = flatten_base(mesh, cut);
  REQUIRE(flattened.status == FlattenStatus::ok);
  const OptimizeResult stands = optimize_offsets(flattened.mesh, options);
  CHECK(stands.status == OptimizeStatus::verified);
  CHECK(stands.after.goal_met);
  CHECK(stands.after.valid);
}
