#include "optimize/reachability_stage.h"

#include "geometry/bvh.h"
#include "util/format_double.h"

namespace offsetopt {

namespace {

ReachabilityOptions options_for(const ReachabilityStageInput& in, bool outer) {
  ReachabilityOptions o;
  o.wall = in.wall;
  o.outer_max = in.outer_max;
  o.ground_tol = in.ground_tol;
  o.outer = outer;
  o.cells_per_wall = in.cavity_cells_per_wall;
  o.contour_cells_per_wall = in.cavity_cells_per_wall;
  o.margin_cells = in.cavity_margin_cells;
  o.threads = in.threads;
  o.mid_reading = true;
  return o;
}

// "the best any void reaches leaves the centre of mass 0.27 outside support edge 6", in the
// goal's own terms.
std::string shortfall(const GoalSpec& goal, const Reachability& r) {
  const std::string binding = r.binding.empty() ? "the goal's rows" : r.binding;
  if (!r.best_margin && !r.best_margin_upper) return "no void meets " + binding;
  const double best = r.best_margin_upper ? *r.best_margin_upper : *r.best_margin;
  const std::string required = goal.kind == GoalKind::stand || goal.kind == GoalKind::stand_filled
                                   ? format_double(goal.margin)
                                   : format_double(goal.epsilon);
  switch (goal.kind) {
    case GoalKind::stand:
    case GoalKind::stand_filled:
      return best < 0.0 ? "the best any void reaches leaves the centre of mass at least " + format_double(-best) + " outside " + binding
                        : "the best any void reaches keeps the centre of mass only " + format_double(best) + " inside " +
                              binding + ", less than the margin " + required;
    case GoalKind::roly_poly:
      return "the best any void reaches puts the centre of mass " + format_double(best) +
             " below the sphere centre, less than the margin " + required;
    case GoalKind::floating:
      return "the best any void reaches puts the centre of mass " + format_double(best) +
             " below the centre of buoyancy, less than the margin " + required;
    default: return "no void meets " + binding;
  }
}

}  // namespace

ReachabilitySummary reachability_stage(const ReachabilityStageInput& in) {
  ReachabilitySummary s;
  const TriangleBvh bvh(in.input->V, in.input->F);
  s.options = options_for(in, in.outer);
  const auto programme = std::make_shared<const Reachability>(reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, s.options));
  const Reachability& r = *programme;
  if (!r.ok) {
    s.decided = false;
    return s;
  }
  s.programme = programme;
  s.reachable = r.reachable;
  s.decided = r.decided;
  s.best_margin = r.best_margin;
  s.best_margin_upper = r.best_margin_upper;
  s.binding = r.binding;
  s.lowest_cz = r.lowest_cz;
  s.certificate = r.certificate.present;
  s.certificate_origin = r.certificate.origin;
  s.quadric = r.certificate.quadric;
  s.carvable_volume = r.carvable_volume;
  s.lps = r.lps;
  s.lp_iterations = r.lp_iterations;
  if (r.reachable) return s;

  // Remedies, each checked by the same programme.
  const bool band_helps = in.goal.kind != GoalKind::floating && in.goal.kind != GoalKind::volume;
  if (!in.outer && band_helps) {
    const Reachability with_band = reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, options_for(in, true));
    if (with_band.ok) {
      ReachabilityRemedy remedy;
      remedy.option = "--outer";
      remedy.reachable = with_band.reachable;
      remedy.best_margin = with_band.reachable ? with_band.best_margin : with_band.best_margin_upper;
      s.remedies.push_back(remedy);
    }
  }
  {
    s.refusal = (r.decided ? "no void can reach this: "
                           : "no void the programme knows reaches this, though at the cell scale it cannot prove that none "
                             "does: ") +
                shortfall(in.goal, r);
    std::string names;
    for (const ReachabilityRemedy& remedy : s.remedies) {
      const bool may = remedy.reachable || (remedy.best_margin && *remedy.best_margin >=
                                                (in.goal.kind == GoalKind::stand || in.goal.kind == GoalKind::stand_filled
                                                     ? in.goal.margin
                                                     : in.goal.epsilon));
      if (may) names += (names.empty() ? "" : ", ") + remedy.option + (remedy.reachable ? "" : " (may)");
    }
    s.refusal += names.empty() ? "; no remedy tried reaches it (re-pose the model or thicken it)" : "; try " + names;
  }
  return s;
}

}  // namespace offsetopt
