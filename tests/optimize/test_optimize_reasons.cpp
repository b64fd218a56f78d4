// Why `optimize` says a goal was not met: the reason must name what happened (the solver's
// evaluation budget ran out, or the repairs of folds took away a goal the first solve had met)
// rather than blame the basis. Run through the library on the bottle demo with options the
// command line does not expose.
#include <doctest/doctest.h>

#include <string>

#include "mesh/demo_meshes.h"
#include "optimize/offset_optimization.h"

using namespace offsetopt;

TEST_CASE("optimize: a solve cut off by its evaluation budget says so") {
  const Mesh bottle = make_demo_mesh("bottle");
  OptimizeOptions options = OptimizeOptions::defaults();
  options.goal = GoalKind::stand;
  options.solver.max_evaluations = 3;
  options.cavity = CavityMode::contour;  // the offset model's reason, not the quadric void's rescue
  const OptimizeResult r = optimize_offsets(bottle, options);
  MESSAGE(r.message);
  CHECK(r.status == OptimizeStatus::goal_not_met);
  CHECK(r.solver.status == AlStatus::max_evaluations);
  CHECK(std::string(to_string(r.solver.status)) == "max-evaluations");
  CHECK(r.solver.evaluations <= 3);
  CHECK(r.message.find("the solver used its 3 evaluations before meeting the constraints") == 0);
}

TEST_CASE("optimize: repairs that make the goal unreachable say the first solve had met it") {
  const Mesh bottle = make_demo_mesh("bottle");
  OptimizeOptions options = OptimizeOptions::defaults();
  options.goal = GoalKind::stand;
  options.repair_shrink = 0.01;
  options.cavity = CavityMode::offset;  // repairs run only when the offset surface is written
  const OptimizeResult r = optimize_offsets(bottle, options);
  MESSAGE(r.message);
  CHECK(r.status == OptimizeStatus::goal_not_met);
  CHECK(r.solver.repair_rounds >= 1);
  CHECK(r.solver.repairs.size() == static_cast<std::size_t>(r.solver.repair_rounds));
  CHECK(r.message.find("the constraints were met before repair round") == 0);
}
