#include "optimize/reachability_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "geometry/bvh.h"
#include "geometry/flatten_base.h"
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
  o.share_levels = in.share_levels;
  o.mid_reading = true;
  o.volume_start = in.volume_start;
  o.bound_undecided = in.bound_undecided;
  return o;
}

// A roly-poly's sphere whose centre is not above the ground: the sphere fitted to a bottom that is
// not rounded (legs, a flat or hollow base; --radius puts the centre above the lowest point). No
// solid resting on the ground, carved, thickened or not, has its centre of mass under it. The
// census had 16 such of 49 roly-poly refusals, one of them a flat base fitted with a sphere of
// radius 3566 below the ground ("leaves the centre of mass 3566 above the sphere centre").
bool sphere_centre_below_ground(const ReachabilityStageInput& in) {
  return in.goal.kind == GoalKind::roly_poly && in.goal.axis_point.z() <= in.ground_z;
}

// "the best any void reaches leaves the centre of mass 0.27 outside support edge 6", in the
// goal's own terms.
std::string shortfall(const ReachabilityStageInput& in, const Reachability& r) {
  const GoalSpec& goal = in.goal;
  if (sphere_centre_below_ground(in))
    return "the sphere fitted to the bottom has its centre " + format_double(in.ground_z - goal.axis_point.z()) +
           " below the ground (the bottom is not rounded), and no centre of mass can lie under it";
  // Every void keeping the wall lies in the cells that may hold a point a wall deep.
  if (goal.kind == GoalKind::volume)
    return "the region at least a wall inside holds at most " + format_double(r.carvable_volume_outer) +
           ", less than the target " + format_double(goal.target_volume);
  const std::string binding = r.binding.empty() ? "the goal's rows" : r.binding;
  if (!r.best_margin && !r.best_margin_upper) return "no void meets " + binding;
  // With the generous reading's optimum, a bound on every void; else the best void of mid cells
  // found, which some void reaches (the shortfall is at most that).
  const bool bound = r.best_margin_upper.has_value();
  const double best = bound ? *r.best_margin_upper : *r.best_margin;
  const std::string who = bound ? "the best any void reaches" : "the best void of cells a wall deep";
  const std::string how_far = bound ? " at least " : " ";
  const std::string required = goal.kind == GoalKind::stand || goal.kind == GoalKind::stand_filled
                                   ? format_double(goal.margin)
                                   : format_double(goal.epsilon);
  switch (goal.kind) {
    case GoalKind::stand:
    case GoalKind::stand_filled:
      return best < 0.0 ? who + " leaves the centre of mass" + how_far + format_double(-best) + " outside " + binding
                        : who + " keeps the centre of mass only " + format_double(best) + " inside " + binding +
                              ", less than the margin " + required;
    case GoalKind::roly_poly:
    case GoalKind::floating: {
      const std::string centre = goal.kind == GoalKind::roly_poly ? "the sphere centre" : "the centre of buoyancy";
      return best < 0.0 ? who + " leaves the centre of mass" + how_far + format_double(-best) + " above " + centre
                        : who + " puts the centre of mass only " + format_double(best) + " below " + centre +
                              ", less than the margin " + required;
    }
    default: return "no void meets " + binding;
  }
}

// Another pose for a stand goal: the same cells, their integrals rotated (cavity/reachability.h),
// the ground and support polygon of the rotated input. Coordinates are R·p (no translation).
// The goal's support polygon and ground of a re-posed or re-cut input, for a stand remedy.
struct Standing {
  GoalSpec goal;
  double ground_z = 0.0;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
};

std::optional<Standing> standing_on(const Mesh& mesh, const ReachabilityStageInput& in) {
  const Vector10d P = mass_properties(mesh);
  StabilityOptions so;
  so.ground_tol = in.ground_tol;
  const Stability st = compute_stability(mesh, Eigen::Vector3d(P(kCx), P(kCy), P(kCz)), so);
  if (st.support_polygon.size() < 3) return std::nullopt;
  Standing s;
  s.goal = in.goal;
  s.goal.support_polygon = st.support_polygon;
  s.ground_z = st.ground_z;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  int contacts = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (mesh.V(v, 2) <= st.ground_z + in.ground_tol) {
      centroid += mesh.V.row(v).head<2>().transpose();
      ++contacts;
    }
  centroid /= std::max(1, contacts);
  s.origin = Eigen::Vector3d(centroid.x(), centroid.y(), st.ground_z);
  return s;
}

ReachabilityRemedy remedy_from(const std::string& option, const Reachability& r) {
  ReachabilityRemedy remedy;
  remedy.option = option;
  remedy.reachable = r.reachable;
  remedy.decided = r.decided;
  remedy.best_margin = r.reachable ? r.best_margin : r.outer_margin_found;
  return remedy;
}

std::optional<ReachabilityRemedy> try_pose(const ReachabilityStageInput& in, const std::shared_ptr<const CarvableCells>& cells,
                                           const VolumeIntegrals& integrals, const Eigen::Matrix3d& R, const std::string& option) {
  Mesh turned = *in.input;
  for (Eigen::Index v = 0; v < turned.V.rows(); ++v) turned.V.row(v) = (R * in.input->V.row(v).transpose()).transpose();
  const std::optional<Standing> standing = standing_on(turned, in);
  if (!standing) return std::nullopt;
  const Eigen::Vector3d lo = in.input->V.colwise().minCoeff().transpose(), hi = in.input->V.colwise().maxCoeff().transpose();
  ReachabilityOptions o = options_for(in, false);
  o.lowest_cz = false;
  const Reachability r =
      reachability(cells, integrals, R, standing->goal, standing->ground_z, standing->origin, (hi - lo).norm(), o);
  if (!r.ok) return std::nullopt;
  return remedy_from(option, r);
}

// The input cut flat `height` above its lowest point (geometry/flatten_base.h), as --flatten
// would cut it, and the programme on it, on the mid cells or on the inner ones (`inner`: every
// corner keeps the wall); none when the cut or the programme fails.
std::optional<Reachability> reach_flattened(const ReachabilityStageInput& in, double height, bool inner) {
  FlattenOptions fo;
  fo.height = height;
  const FlattenResult cut = flatten_base(*in.input, fo);
  if (cut.status != FlattenStatus::ok) return std::nullopt;
  const std::optional<Standing> standing = standing_on(cut.mesh, in);
  if (!standing) return std::nullopt;
  const TriangleBvh bvh(cut.mesh.V, cut.mesh.F);
  ReachabilityOptions o = options_for(in, false);
  o.lowest_cz = false;
  o.mid_reading = !inner;
  o.share_levels = 0;  // a base is searched for where it reaches the goal, not where it is proved not to
  Reachability r = reachability(cut.mesh, bvh, standing->goal, standing->ground_z, standing->origin, o);
  if (!r.ok) return std::nullopt;
  return r;
}

// The first of `tries` (each farther from `start` than the last) at which `passes` holds, moved
// back by two bisections towards the last that did not (`start` before the first); none when none
// passes. The remedies' searches: heights growing, walls thinning.
template <class Passes>
std::optional<double> first_passing(double start, const std::vector<double>& tries, const Passes& passes) {
  double failing = start;
  for (const double value : tries) {
    if (!passes(value)) {
      failing = value;
      continue;
    }
    double passing = value;
    for (int step = 0; step < 2; ++step) {
      const double middle = 0.5 * (failing + passing);
      (passes(middle) ? passing : failing) = middle;
    }
    return passing;
  }
  return std::nullopt;
}

// `value` rounded up or down to two significant digits, for the text the user will type.
double two_digits(double value, bool up) {
  const double unit = std::pow(10.0, std::floor(std::log10(value)) - 1.0);
  return (up ? std::ceil(value / unit - 1e-9) : std::floor(value / unit)) * unit;
}

std::string two_digit_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", value);
  return text;
}

// A height to type and the programme at exactly that height.
struct FlatBase {
  std::string text;
  Reachability programme;
};

// The smallest flat base from `from` up whose programme (`inner` as above) reaches a stand goal,
// to two significant digits and checked at the height named: heights double from `from` up to a
// quarter of the model's height, then two bisections, then the named height, rounded up, is
// checked once more.
std::optional<FlatBase> smallest_flat_base(const ReachabilityStageInput& in, double from, bool inner) {
  const double tall = in.input->V.col(2).maxCoeff() - in.input->V.col(2).minCoeff();
  if (!(tall > 0.0) || !(from > 0.0)) return std::nullopt;
  std::vector<double> heights;
  for (double h = from; h <= tall / 4.0 * (1.0 + 1e-12); h *= 2.0) heights.push_back(h);
  const std::optional<double> above = first_passing(0.0, heights, [&in, inner](double h) {
    const std::optional<Reachability> r = reach_flattened(in, h, inner);
    return r && r->reachable;
  });
  if (!above) return std::nullopt;
  // Rounded up, in the text the user will type: the total from the original lowest point.
  const std::string text = two_digit_text(in.flatten + two_digits(*above, true));
  const double total = std::strtod(text.c_str(), nullptr);
  std::optional<Reachability> r = reach_flattened(in, total - in.flatten, inner);
  if (!r) return std::nullopt;
  return FlatBase{text, std::move(*r)};
}

// The flat bases to name, as --outer is named: to be tried, the smallest whose inner cells reach
// the goal (a void the tool writes); as undecided, a smaller one only the mid cells reach. Mid
// cells alone were too hopeful near the limit: on the census laid on its side (--up +x) four
// bunnies' heights, named by the mid cells, exited 3 as typed (cgal-data_bunny00 at 0.045: mid
// cells 0.0067 inside, the voids written 0.0029 and 0.0020, the margin 0.0032), where thin parts
// hold much of the carvable volume and the contour at wall / 1.5 loses it.
std::vector<ReachabilityRemedy> flatten_remedies(const ReachabilityStageInput& in) {
  const double tall = in.input->V.col(2).maxCoeff() - in.input->V.col(2).minCoeff();
  const std::optional<FlatBase> mid = smallest_flat_base(in, tall / 32.0, false);
  if (!mid) return {};
  const double mid_height = std::strtod(mid->text.c_str(), nullptr) - in.flatten;
  std::optional<Reachability> inner_there = reach_flattened(in, mid_height, true);
  if (inner_there && inner_there->reachable) return {remedy_from("--flatten " + mid->text, *inner_there)};
  std::vector<ReachabilityRemedy> remedies;
  if (const std::optional<FlatBase> inner = smallest_flat_base(in, mid_height * 1.25, true))
    remedies.push_back(remedy_from("--flatten " + inner->text, inner->programme));
  ReachabilityRemedy hopeful = remedy_from("--flatten " + mid->text, mid->programme);
  hopeful.reachable = hopeful.decided = false;
  hopeful.mid_cells_reach = true;
  remedies.push_back(hopeful);
  return remedies;
}

// A volume out of reach: the thickest wall at which the inner cells (a void the tool writes) hold
// the target, to two significant digits rounded down and checked at the value named. Walls from
// 0.8 times the user's down by factors of 0.8, at most 5 (to a third of it: the cells grow as the
// wall's inverse cube, their nodes capped at 2^23), then two bisections.
constexpr int kThinnerWallSteps = 5;
constexpr std::int64_t kThinnerWallMaxNodes = std::int64_t{1} << 23;

std::optional<ReachabilityRemedy> thinner_wall(const ReachabilityStageInput& in, const TriangleBvh& bvh) {
  auto holds = [&in, &bvh](double wall) {
    ReachabilityOptions o = options_for(in, false);
    o.wall = wall;
    o.mid_reading = false;
    o.lowest_cz = false;
    o.max_nodes = std::min(o.max_nodes, kThinnerWallMaxNodes);
    o.share_levels = 0;  // only "holds" is asked: the shell's shares would prove nothing wanted
    return reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, o);
  };
  std::vector<double> walls;
  for (int k = 1; k <= kThinnerWallSteps; ++k) walls.push_back(in.wall * std::pow(0.8, k));
  const std::optional<double> thin = first_passing(in.wall, walls, [&holds](double wall) {
    const Reachability r = holds(wall);
    return r.ok && r.reachable;
  });
  if (!thin) return std::nullopt;
  const std::string text = two_digit_text(two_digits(*thin, false));
  const Reachability r = holds(std::strtod(text.c_str(), nullptr));
  if (!r.ok || !r.reachable) return std::nullopt;
  return remedy_from("--wall " + text, r);
}

// Cells half as large, when the programme cannot tell at the contour's scale: the generous
// reading's cells shrink towards the exact wall and the mid reading's grow towards it, so the
// bracket between them narrows (docs/reachability.md "Finer cells"). On the census's 12 undecided
// refusals one halving decided 10 (the roly-poly census took 113.7 s in all, 106.7 s before).
constexpr double kFinerCellsPerWallFactor = 2.0;
constexpr std::int64_t kFinerMaxNodes = std::int64_t{1} << 24;

Reachability decide_on_finer_cells(const ReachabilityStageInput& in, const TriangleBvh& bvh, ReachabilityOptions o,
                                   Reachability coarse) {
  if (!coarse.ok || coarse.decided) return coarse;
  o.cells_per_wall = std::min(8.0, o.cells_per_wall * kFinerCellsPerWallFactor);
  o.max_nodes = std::min(o.max_nodes, kFinerMaxNodes);
  o.shell_in_part_first = coarse.partial_cells;
  Reachability finer = reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, o);
  // The node budget may leave the grid as coarse as it was: nothing learned.
  if (!finer.ok || !(finer.cells->grid.spacing < 0.9 * coarse.cells->grid.spacing)) return coarse;
  finer.lps += coarse.lps;
  finer.lp_iterations += coarse.lp_iterations;
  return finer;
}

// The programme set by `o` read on the inner cells (every corner passes the contour's node test:
// a void the tool can write), on the contour's cells and, where they cannot tell, on finer ones.
// Only the claim: the optimum and the lowest centre of mass stay the mid reading's.
Reachability on_inner_cells(const ReachabilityStageInput& in, const TriangleBvh& bvh, ReachabilityOptions o) {
  o.mid_reading = false;
  o.lowest_cz = false;
  return decide_on_finer_cells(in, bvh, o, reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, o));
}

// The programme's answer into the summary: the claim, its margins and the cells it was read on,
// and its certificate where it has one (else the summary keeps the one it had, if any).
void take_claim(const Reachability& r, ReachabilitySummary& s) {
  s.reachable = r.reachable;
  s.decided = r.decided;
  s.evidence = r.reachable ? "programme" : r.decided ? "certificate" : "";
  s.best_margin = r.best_margin;
  s.best_margin_upper = r.best_margin_upper;
  s.binding = r.binding;
  s.cell_spacing = r.cells->grid.spacing;
  if (r.certificate.present) {
    s.certificate = true;
    s.certificate_origin = r.certificate.origin;
    s.quadric = r.certificate.quadric;
  }
}

// "; try --pose stable, --up +y; undecided with --outer", or `none` when no remedy reaches the goal.
std::string remedy_clauses(const ReachabilitySummary& s, const std::string& none) {
  std::string clauses = s.remedy_list.empty() ? none : "; try " + s.remedy_list;
  if (!s.undecided_remedies.empty()) clauses += "; undecided with " + s.undecided_remedies;
  return clauses;
}

// The stage's programme: on the contour's cells and, where they cannot tell, on finer ones. Not
// on finer cells with --outer: there the bracket is the band's (the generous reading lets
// material come as near the input as the band is thick), which finer cells do not narrow.
Reachability stage_programme(const ReachabilityStageInput& in, const TriangleBvh& bvh, const ReachabilityOptions& o) {
  Reachability first = reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, o);
  if (in.outer) return first;
  return decide_on_finer_cells(in, bvh, o, std::move(first));
}

}  // namespace

ReachabilitySummary reachability_stage(const ReachabilityStageInput& in) {
  ReachabilitySummary s;
  std::optional<TriangleBvh> own;
  const TriangleBvh& bvh = in.input_bvh ? *in.input_bvh : own.emplace(in.input->V, in.input->F);
  s.options = options_for(in, in.outer);
  const auto programme = std::make_shared<const Reachability>(stage_programme(in, bvh, s.options));
  const Reachability& r = *programme;
  if (!r.ok) {
    s.decided = false;
    return s;
  }
  s.programme = programme;
  take_claim(r, s);
  s.lowest_cz = r.lowest_cz;
  s.carvable_volume = r.carvable_volume;
  s.lps = r.lps;
  s.lp_iterations = r.lp_iterations;
  // Reachable: nothing to remedy. Undecided: the remedies wait until the run has missed the goal
  // (add_remedies).
  if (r.reachable || !r.decided) return s;
  s.shortfall = shortfall(in, r);
  if (sphere_centre_below_ground(in)) s.no_remedy_hint = "a roly-poly rocks on a rounded bottom: re-pose the model on one";
  if (in.goal.kind == GoalKind::volume) s.no_remedy_hint = "a thinner --wall leaves room for more";
  add_remedies(in, s);
  s.refusal = reachability_note(s);
  return s;
}

void bound_undecided(const ReachabilityStageInput& in, ReachabilitySummary& s) {
  if (s.reachable || s.decided || s.best_margin_upper || !s.programme || !s.programme->outer_margin_found) return;
  std::optional<TriangleBvh> own;
  const TriangleBvh& bvh = in.input_bvh ? *in.input_bvh : own.emplace(in.input->V, in.input->F);
  ReachabilityOptions o = s.options;
  o.bound_undecided = true;
  const Reachability r = stage_programme(in, bvh, o);
  if (!r.ok) return;
  s.lps += r.lps;
  s.lp_iterations += r.lp_iterations;
  // The same cells and rows: the claim is the stage's; only the generous reading went on.
  if (r.reachable || r.decided) return;
  s.best_margin_upper = r.best_margin_upper;
  s.binding = r.binding;
}

void confirm_reachable(const ReachabilityStageInput& in, ReachabilitySummary& s) {
  if (!s.reachable || s.evidence != "programme" || s.inner_reading) return;
  std::optional<TriangleBvh> own;
  const TriangleBvh& bvh = in.input_bvh ? *in.input_bvh : own.emplace(in.input->V, in.input->F);
  const Reachability r = on_inner_cells(in, bvh, options_for(in, in.outer));
  s.inner_reading = true;
  if (!r.ok) return;
  s.lps += r.lps;
  s.lp_iterations += r.lp_iterations;
  if (r.reachable) return;
  take_claim(r, s);
  if (r.decided) s.shortfall = shortfall(in, r);
}

void add_remedies(const ReachabilityStageInput& in, ReachabilitySummary& s) {
  if (!s.programme || s.reachable || !s.remedies.empty()) return;
  const Reachability& r = *s.programme;
  const bool band_helps =
      in.goal.kind != GoalKind::floating && in.goal.kind != GoalKind::volume && !sphere_centre_below_ground(in);
  if (!in.outer && band_helps) {
    std::optional<TriangleBvh> own;
    const TriangleBvh& bvh = in.input_bvh ? *in.input_bvh : own.emplace(in.input->V, in.input->F);
    // Named to be tried only where a void the tool can write reaches it with the band:
    // euclid-data_sharp_sphere spinning, whose mid reading reached it, exited 3 with --outer.
    Reachability with_band = reachability(*in.input, bvh, in.goal, in.ground_z, in.origin, options_for(in, true));
    bool mid_cells_reach = false;
    if (with_band.ok && with_band.reachable) {
      Reachability inner = on_inner_cells(in, bvh, options_for(in, true));
      if (inner.ok && !inner.reachable) {
        with_band = std::move(inner);
        mid_cells_reach = true;
      }
    }
    if (with_band.ok) {
      s.remedies.push_back(remedy_from("--outer", with_band));
      s.remedies.back().mid_cells_reach = mid_cells_reach;
    }
  }
  if (in.goal.kind == GoalKind::volume) {
    std::optional<TriangleBvh> own;
    const TriangleBvh& bvh = in.input_bvh ? *in.input_bvh : own.emplace(in.input->V, in.input->F);
    if (auto remedy = thinner_wall(in, bvh)) s.remedies.push_back(*remedy);
  }
  // Other poses (stand goals): the most stable hull facet and the file's other five axes up,
  // ranked by the best margin a void reaches there. Each is tried as the CLI would pose the file
  // with it: the input here is the file turned by the user's --up U, so "--up b" is the turn
  // P_b · U⁻¹ of it. Not after --flatten (the CLI cuts after turning: the cut would be another), and
  // no --up after --pose stable (the CLI would re-pose whatever the axis).
  if (in.goal.kind == GoalKind::stand || in.goal.kind == GoalKind::stand_filled) {
    const VolumeIntegrals integrals = volume_integrals(*in.input);
    std::vector<ReachabilityRemedy> poses;
    AxisPermutation user_up;
    if (!(in.flatten > 0.0) && !in.posed_stable && up_axis_permutation(in.up, user_up)) {
      const Vector10d P = mass_properties(*in.input);
      const StablePose stable = stable_pose(*in.input, Eigen::Vector3d(P(kCx), P(kCy), P(kCz)));
      if (stable.status == StablePoseStatus::ok)
        if (auto remedy = try_pose(in, r.cells, integrals, stable.motion.rotation, "--pose stable")) poses.push_back(*remedy);
      const Eigen::Matrix3d undo = user_up.matrix().transpose();
      for (const char* up : {"+z", "+x", "-x", "+y", "-y", "-z"}) {
        AxisPermutation permutation;
        if (!up_axis_permutation(up, permutation) || permutation.matrix() == user_up.matrix()) continue;
        if (auto remedy = try_pose(in, r.cells, integrals, permutation.matrix() * undo, std::string("--up ") + up))
          poses.push_back(*remedy);
      }
    }
    std::stable_sort(poses.begin(), poses.end(), [](const ReachabilityRemedy& a, const ReachabilityRemedy& b) {
      return a.best_margin.value_or(-1e300) > b.best_margin.value_or(-1e300);
    });
    s.remedies.insert(s.remedies.end(), poses.begin(), poses.end());
    // A new cut means new cells, several times over: only for a proved refusal.
    if (s.decided)
      for (ReachabilityRemedy& remedy : flatten_remedies(in)) s.remedies.push_back(std::move(remedy));
  }
  // Named to be tried: the remedies whose programme reaches the goal (--outer, --flatten: on the inner
  // cells too). Named as undecided: those only the mid cells reach, a void half a cell past the wall at
  // most (a user who tries one may or may not get there: euclid-data_rocker_arm's roly-poly does).
  // Those only the generous reading reaches are not named: on the census it reached almost every
  // goal with the band ("--outer (may)" on 36 of 49 roly-poly refusals said little).
  for (const ReachabilityRemedy& remedy : s.remedies) {
    if (!remedy.reachable && !remedy.mid_cells_reach) continue;
    std::string& names = remedy.reachable ? s.remedy_list : s.undecided_remedies;
    names += (names.empty() ? "" : ", ") + remedy.option;
  }
}

std::string reachability_note(const ReachabilitySummary& summary) {
  if (!summary.reachable && summary.decided)
    return "no void can reach this: " + summary.shortfall +
           remedy_clauses(summary, "; no remedy tried is known to reach it (" + summary.no_remedy_hint + ")");
  if (summary.reachable) {
    std::string note = "a void the tool can write reaches it";
    if (summary.best_margin) note += " (best margin " + format_double(*summary.best_margin) + ")";
    return note + ", so this is the tool's shortfall, not the model's";
  }
  std::string note = "undecided whether any void reaches it";
  if (summary.best_margin || summary.best_margin_upper) {
    note += " (best margin " + (summary.best_margin ? format_double(*summary.best_margin) : std::string("none")) + " to " +
            (summary.best_margin_upper ? format_double(*summary.best_margin_upper) : std::string("none")) + ")";
  }
  return note + remedy_clauses(summary, "");
}

}  // namespace offsetopt
