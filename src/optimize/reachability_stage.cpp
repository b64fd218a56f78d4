#include "optimize/reachability_stage.h"

#include <algorithm>

#include "geometry/bvh.h"
#include "geometry/pose.h"
#include "mass/mass_properties.h"
#include "mass/stability.h"
#include "mass/stable_pose.h"
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
    case GoalKind::floating: {
      const std::string centre = goal.kind == GoalKind::roly_poly ? "the sphere centre" : "the centre of buoyancy";
      return best < 0.0 ? "the best any void reaches leaves the centre of mass at least " + format_double(-best) + " above " + centre
                        : "the best any void reaches puts the centre of mass only " + format_double(best) + " below " + centre +
                              ", less than the margin " + required;
    }
    default: return "no void meets " + binding;
  }
}

// Another pose for a stand goal: the same cells, their integrals rotated (cavity/reachability.h),
// the ground and support polygon of the rotated input. Coordinates are R·p (no translation).
std::optional<ReachabilityRemedy> try_pose(const ReachabilityStageInput& in, const std::shared_ptr<const CarvableCells>& cells,
                                           const VolumeIntegrals& integrals, const Eigen::Matrix3d& R, const std::string& option) {
  Mesh turned = *in.input;
  for (Eigen::Index v = 0; v < turned.V.rows(); ++v) turned.V.row(v) = (R * in.input->V.row(v).transpose()).transpose();
  const Vector10d P = mass_properties(turned);
  StabilityOptions so;
  so.ground_tol = in.ground_tol;
  const Stability st = compute_stability(turned, Eigen::Vector3d(P(kCx), P(kCy), P(kCz)), so);
  if (st.support_polygon.size() < 3) return std::nullopt;
  GoalSpec goal = in.goal;
  goal.support_polygon = st.support_polygon;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int contacts = 0;
  for (Eigen::Index v = 0; v < turned.V.rows(); ++v)
    if (turned.V(v, 2) <= st.ground_z + in.ground_tol) {
      centroid += turned.V.row(v).head<2>().transpose();
      ++contacts;
    }
  centroid /= std::max(1, contacts);
  const Eigen::Vector3d lo = in.input->V.colwise().minCoeff().transpose(), hi = in.input->V.colwise().maxCoeff().transpose();
  ReachabilityOptions o = options_for(in, false);
  o.lowest_cz = false;
  const Reachability r = reachability(cells, integrals, R, goal, st.ground_z, Eigen::Vector3d(centroid.x(), centroid.y(), st.ground_z),
                                      (hi - lo).norm(), o);
  if (!r.ok) return std::nullopt;
  ReachabilityRemedy remedy;
  remedy.option = option;
  remedy.reachable = r.reachable;
  remedy.best_margin = r.reachable ? r.best_margin : r.best_margin_upper;
  return remedy;
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
  // Other poses (stand goals): the most stable hull facet and the other five axes up, ranked by
  // the best margin a void reaches there.
  if (in.goal.kind == GoalKind::stand || in.goal.kind == GoalKind::stand_filled) {
    const VolumeIntegrals integrals = volume_integrals(*in.input);
    std::vector<ReachabilityRemedy> poses;
    const Vector10d P = mass_properties(*in.input);
    const StablePose stable = stable_pose(*in.input, Eigen::Vector3d(P(kCx), P(kCy), P(kCz)));
    if (stable.status == StablePoseStatus::ok)
      if (auto remedy = try_pose(in, r.cells, integrals, stable.motion.rotation, "--pose stable")) poses.push_back(*remedy);
    for (const char* up : {"+x", "-x", "+y", "-y", "-z"}) {
      AxisPermutation permutation;
      if (!up_axis_permutation(up, permutation)) continue;
      if (auto remedy = try_pose(in, r.cells, integrals, permutation.matrix(), std::string("--up ") + up)) poses.push_back(*remedy);
    }
    std::stable_sort(poses.begin(), poses.end(), [](const ReachabilityRemedy& a, const ReachabilityRemedy& b) {
      return a.best_margin.value_or(-1e300) > b.best_margin.value_or(-1e300);
    });
    s.remedies.insert(s.remedies.end(), poses.begin(), poses.end());
  }
  std::string& names = s.remedy_list;
  for (const ReachabilityRemedy& remedy : s.remedies) {
    const bool may = remedy.reachable || (remedy.best_margin && *remedy.best_margin >=
                                              (in.goal.kind == GoalKind::stand || in.goal.kind == GoalKind::stand_filled
                                                   ? in.goal.margin
                                                   : in.goal.epsilon));
    if (may) names += (names.empty() ? "" : ", ") + remedy.option + (remedy.reachable ? "" : " (may)");
  }
  if (r.decided) {
    s.refusal = "no void can reach this: " + shortfall(in.goal, r);
    s.refusal += names.empty() ? "; no remedy tried reaches it (re-pose the model or thicken it)" : "; try " + names;
  }
  return s;
}

std::string reachability_note(const ReachabilitySummary& summary) {
  std::string note = "undecided whether any void reaches it";
  if (summary.best_margin || summary.best_margin_upper) {
    note += " (best margin " + (summary.best_margin ? format_double(*summary.best_margin) : std::string("none")) + " to " +
            (summary.best_margin_upper ? format_double(*summary.best_margin_upper) : std::string("none")) + ")";
  }
  if (!summary.remedy_list.empty()) note += "; try " + summary.remedy_list;
  return note;
}

}  // namespace offsetopt
